#!/usr/bin/python3
"""Where the products of a contact solve go, outer iteration by outer iteration.

Runs the conefeti program on the brick at a fixed subdomain size H/h = 6 (petsc-options/brick.opts,
-scene_refine 6p -scene_body0_subdomains 3p,p,p, -feti_kplus_explicit 0 so that p = 4 stays near 0.45 GB) with
-info :tao,contact and prints, per outer iteration k of the augmented Lagrangian: the change of the Coulomb radii F l_n
before the inner solve (relative in the 2-norm / largest over the largest contact force), the products with F of
the inner solve split into CG, expansion (two products each) and proportioning steps, the inner solve's stopping
precision M |Cx - d| and its result |gP|, both over the final tolerance of |gP|, |Cx - d| over its final
tolerance, the factor by which |Cx - d| fell, and the Coulomb consistency check. All counts; no times.

usage: scripts/outer-breakdown.py [--sizes 1,2,3,4] [--options brick.opts] [--extra "-option value ..."] [--build build]
"""
import argparse, json, re, subprocess, sys

FLOAT = r"([-+0-9.e]+|inf|nan)"


def parse(text):
    rows, cur = [], {}
    for line in text.splitlines():
        m = re.search(r"Coulomb radii F l_n before the inner solve: relative change " + FLOAT + ", largest " + FLOAT, line)
        if m:
            cur.setdefault("dr", float(m.group(1)))
            cur.setdefault("dl", float(m.group(2)))
            continue
        m = re.search(r"TAO smalxe outer (\d+) block (\d+): (\d+) products, (\d+) CG \+ (\d+) expansion \+ (\d+) proportioning steps, "
                      r"\|gP\| " + FLOAT + r" \(M \|Cx - d\| with M " + FLOAT + ", eta " + FLOAT + r"\), rho " + FLOAT, line)
        if m:
            for key, g in (("prod", 3), ("cg", 4), ("exp", 5), ("prop", 6)):
                cur[key] = cur.get(key, 0) + int(m.group(g))
            cur.update(M=float(m.group(8)), eta=float(m.group(9)), rho=float(m.group(10)))
            continue
        m = re.search(r"TAO smalxe outer (\d+): \|gP\| = " + FLOAT + r" \(tol " + FLOAT + r"\), \|Cx - d\| = " + FLOAT + r" \(tol " + FLOAT + r"\)", line)
        if m:
            cur.update(k=int(m.group(1)), gp=float(m.group(2)), tg=float(m.group(3)), e=float(m.group(4)), te=float(m.group(5)))
            rows.append(cur)
            cur = {}
            continue
        m = re.search(r"Coulomb radii used vs F l_n of the result: .*\((consistent|not yet)\)", line)
        if m and rows:
            rows[-1]["check"] = m.group(1)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="1,2,3,4", help="p: -scene_refine 6p, subdomains 3p x p x p")
    ap.add_argument("--options", default="brick.opts", help="the options file in petsc-options/")
    ap.add_argument("--extra", default="")
    ap.add_argument("--build", default="build")
    a = ap.parse_args()
    print(f"# command: scripts/outer-breakdown.py --sizes {a.sizes} --options {a.options}" + (f' --extra "{a.extra}"' if a.extra else ""))
    for p in [int(s) for s in a.sizes.split(",")]:
        cmd = [f"{a.build}/conefeti", "-options_file", f"petsc-options/{a.options}", "-scene_refine", str(6 * p), "-scene_body0_subdomains", f"{3 * p},{p},{p}",
               "-feti_kplus_explicit", "0", "-info", ":tao,contact"] + a.extra.split()
        r = subprocess.run(cmd, capture_output=True, text=True)
        js = [json.loads(l) for l in r.stdout.splitlines() if l.startswith("{")]
        if not js:
            sys.exit(f"outer-breakdown.py: no JSON line from {' '.join(cmd)} (exit {r.returncode}):\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
        j = js[-1]
        rows = parse(r.stdout + r.stderr)
        print(f"\np = {p}: n = {j['n']}, contact nodes {j['contact_nodes']} ({j['separated']}/{j['stick']}/{j['slip']} separated/stick/slip), "
              f"Iter {j['iter']}, n_A {j['n_A']}, largest residual {j['residuals']['max']:.2e}, converged {j['converged']}")
        print("| k | radii change (2-norm / largest) | products | CG + expansion + proportioning | M \\|Cx - d\\| / tol_g (end) | \\|gP\\| / tol_g | \\|Cx - d\\| / tol_e | fall of \\|Cx - d\\| |")
        print("|---|---|---|---|---|---|---|---|")
        prev, total, early = None, 0, 0
        for w in rows:
            total += w.get("prod", 0)
            radii = f"{w['dr']:.1e} / {w['dl']:.1e}" if "dr" in w else "-"
            fall = f"{prev / w['e']:.1f}" if prev else "-"
            check = f" ({w['check']})" if "check" in w else ""
            print(f"| {w['k']} | {radii} | {w.get('prod', 0)} | {w.get('cg', 0)} + {w.get('exp', 0)} + {w.get('prop', 0)} | {w.get('M', 0) * w['e'] / w['tg']:.2g} | "
                  f"{w['gp'] / w['tg']:.2g} | {w['e'] / w['te']:.3g} | {fall}{check} |")
            prev = w["e"]
        print(f"inner products {total} (+ {j['n_A'] - total} outside the inner solves = n_A {j['n_A']})")


if __name__ == "__main__":
    main()
