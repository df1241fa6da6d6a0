#!/usr/bin/python3
"""The peers program solves the same mechanics as conefeti: on a scene, conefeti at a tight tolerance writes its
displacement (-peers_save), then a peer solves the assembled primal problem and must agree with it.

usage: peers_agree.py --tol T -- command-prefix... peers-exe scene-args... -- peer-args...
The command prefix (mpiexec -n N) runs the peer; the reference runs on one rank. The test fails unless both
runs exit 0 with one {"peers": JSON line, both call their answer right (every mechanical residual within the
acceptance), they see the same n, contact nodes and pressed nodes, and |u - u_ref| / |u_ref| <= T."""
import json, os, subprocess, sys, tempfile


def run(cmd):
    out = subprocess.run(cmd, capture_output=True, text=True)
    print("$ " + " ".join(cmd))
    print(out.stdout + out.stderr)
    lines = [l for l in out.stdout.splitlines() if l.startswith('{"peers":')]
    if out.returncode != 0 or len(lines) != 1:
        sys.exit("peers_agree.py: exit status %d, %d JSON lines" % (out.returncode, len(lines)))
    return json.loads(lines[0])["peers"]


def main():
    args = sys.argv[1:]
    if len(args) < 5 or args[0] != "--tol" or args[2] != "--":
        sys.exit(__doc__)
    tol = float(args[1])
    rest = args[3:]
    second = rest.index("--")
    command, peer = rest[:second], rest[second + 1:]
    exe = next(i for i, a in enumerate(command) if a.endswith("peers"))
    prefix, program = command[:exe], command[exe:]
    with tempfile.TemporaryDirectory() as tmp:
        ref = os.path.join(tmp, "ref.bin")
        r = run(program + ["-peers_solver", "conefeti", "-contact_rtol", "1e-10", "-peers_save", ref])
        p = run(prefix + program + peer + ["-peers_reference", ref])
    fails = []
    for name, x in (("conefeti", r), ("peer", p)):
        if not x["right"]:
            fails.append("%s: largest mechanical residual %g above %g" % (name, x["residual_max"], x["acceptance"]))
    for key in ("n", "contact_nodes", "pressed"):
        if r[key] != p[key]:
            fails.append("%s: conefeti %d, peer %d" % (key, r[key], p[key]))
    if not 0 <= p["error_u"] <= tol:
        fails.append("|u - u_ref| / |u_ref| = %g above %g" % (p["error_u"], tol))
    if fails:
        sys.exit("peers_agree.py: " + "; ".join(fails))
    print("peers_agree.py: %s agrees with conefeti: |u - u_ref| / |u_ref| = %.1e <= %g, %d of %d contact nodes pressed in both" % (p["solver"], p["error_u"], tol, p["pressed"], p["contact_nodes"]))


if __name__ == "__main__":
    main()
