#!/usr/bin/python3
"""A cost model of conefeti past one machine: memory and time per rank against n, subdomains and ranks.

--measure runs two cheap series on this machine (one rank, one run at a time) and saves them to --data:
  coarse     the coarse problem against the number of subdomains Ns: the linear scene (petsc-options/linear.opts,
             Total FETI, every subdomain floating: coarse dimension 6 Ns) cut into many small cubes of H/h = 2
             cells per edge (-scene_refine 2p -scene_body0_subdomains 4p,p,p), -feti_kplus_explicit 0. Per run:
             time_phases.coarse (load, R, G G' and its factor: the coarse setup), -log_view's FETICoarseSolve
             (count, time: per solve), FETI_MultF, and the coarse factor's size and flops (CHOLMOD's lnz and fl
             from -feti_view).
  subdomain  the per-subdomain costs at H/h = 4, 6, 8 (the same scene, 4p x p x p cubes, p = 2): factor time
             (FETIFactor / count), F product time per subdomain (FETI_MultF / count / Ns) and peak memory per
             unknown (/usr/bin/time %M).
Without --measure it reads --data, fits the model and prints the fitted constants, the prediction table for
n = 10^7, 10^8, 10^9 on 10, 100, 1000 nodes and the remedies at 10^8 (markdown), and writes --png.

usage: scripts/scale-model.py [--measure] [--coarse-sizes 2,4,6,8,10,12] [--build build] [--data scripts/data/scale-model.json]
                              [--png docs/figures/scale-model.png] [--ranks-per-node 32] [--node-memory 128]
                              [--latency 2e-6] [--bandwidth 1e10]
Assumptions (not measured here; change them with the options): a node of 32 ranks and 128 GB, a network latency
of 2 microseconds and a bandwidth of 10 GB/s per rank; the times measured on this 2-core machine are used as
they are (wall seconds; under load they are 2-5x longer, which moves the crossovers against the assumed network
terms but not the ranking of the remedies).
"""
import argparse, json, math, os, re, subprocess, sys

import hugepages
import logview

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINEAR = os.path.join(ROOT, "petsc-options", "linear.opts")

# From the table of docs/scale.md (the brick, Coulomb F = 0.3, H/h = 6, the defaults, n = 1 037 232, one rank; made
# by scripts/bench-scale.py): the contact solver's coarse solves per F product (FETICoarseSolve 859 / FETI_MultF 238)
# and F products per solve (n_A = 206 at 10^6, 148 at n = 18 252: a growth of 1.21x per decade of n).
CONTACT_COARSE_PER_PRODUCT = 859 / 238
CONTACT_NA_1E6, NA_GROWTH_PER_DECADE = 206, (206 / 148) ** (1 / math.log10(1037232 / 18252))


def run(cmd, env):
    timed = ["/usr/bin/time", "-f", "scale-model-maxrss-kb %M"] + cmd
    out = subprocess.run(timed, capture_output=True, text=True, env=env)
    line = next((l for l in out.stdout.splitlines() if l.startswith('{"conefeti":')), None)
    if out.returncode not in (0, 2) or line is None:
        sys.exit("scale-model: failed (%s):\n%s" % (" ".join(cmd), (out.stdout + out.stderr)[-3000:]))
    rss = sum(int(m) * 1024 for m in re.findall(r"scale-model-maxrss-kb (\d+)", out.stderr))
    return json.loads(line), rss, out.stdout


def scene(hh, p):
    return ["-options_file", LINEAR, "-scene_refine", str(hh * p), "-scene_body0_subdomains", "%d,%d,%d" % (4 * p, p, p), "-feti_kplus_explicit", "0", "-summary_table", "0", "-log_view"]


def measure(a):
    env = hugepages.environment(True)
    exe = os.path.join(a.build, "conefeti")
    data = dict(coarse=[], subdomain=[], machine="2 cores, load average %.1f at the start; wall seconds" % os.getloadavg()[0], command="scripts/scale-model.py --measure --coarse-sizes %s" % a.coarse_sizes)
    for p in [int(x) for x in a.coarse_sizes.split(",") if x]:
        # the model is that of one sequential factor (single mode); auto would split coarse dimensions 1000-9999
        j, rss, out = run([exe] + scene(2, p) + ["-feti_view", "-feti_coarse_mode", "single"], env)
        ev = logview.events(out)
        lnz = re.findall(r"Common\.lnz\s*([0-9.eE+]+)", out)
        fl = re.findall(r"Common\.fl\s*([0-9.eE+]+)", out)
        row = dict(hh=2, p=p, n=j["n"], Ns=j["subdomains"], coarse_dim=j["rigid_modes"], iter=j["iter"], coarse_setup=j["time_phases"]["coarse"],
                   coarse_solves=ev.get("FETICoarseSolve", (0, 0))[0], coarse_solve_time=ev.get("FETICoarseSolve", (0, 0))[1],
                   products=ev.get("FETI_MultF", (0, 0))[0], product_time=ev.get("FETI_MultF", (0, 0))[1],
                   factor_count=ev.get("FETIFactor", (0, 0))[0], factor_time=ev.get("FETIFactor", (0, 0))[1],
                   lnz=float(lnz[-1]) if lnz else None, flops=float(fl[-1]) if fl else None, mem=rss, setup=j["time_setup"], solve=j["time_solve"])
        data["coarse"].append(row)
        print("coarse: Ns %d dim %d n %d setup %.3f s, %d solves %.3f s, lnz %s, fl %s, mem %.0f MB" % (
            row["Ns"], row["coarse_dim"], row["n"], row["coarse_setup"], row["coarse_solves"], row["coarse_solve_time"], row["lnz"], row["flops"], rss / 1e6), flush=True)
    for hh in (4, 6, 8):
        j, rss, out = run([exe] + scene(hh, 2), env)
        ev = logview.events(out)
        row = dict(hh=hh, p=2, n=j["n"], Ns=j["subdomains"], iter=j["iter"], factor_count=ev.get("FETIFactor", (0, 0))[0], factor_time=ev.get("FETIFactor", (0, 0))[1],
                   products=ev.get("FETI_MultF", (0, 0))[0], product_time=ev.get("FETI_MultF", (0, 0))[1], coarse_setup=j["time_phases"]["coarse"],
                   factorization=j["time_phases"]["factorization"], mem=rss)
        data["subdomain"].append(row)
        print("subdomain: H/h %d Ns %d n %d factor %.3f s (%d), F %.3f s (%d), mem %.0f MB" % (hh, row["Ns"], row["n"], row["factor_time"], row["factor_count"], row["product_time"], row["products"], rss / 1e6), flush=True)
    os.makedirs(os.path.dirname(a.data), exist_ok=True)
    with open(a.data, "w") as f:
        json.dump(data, f, indent=1)
    print("wrote %s" % a.data)


def powerfit(x, y):
    """y = c x^e by least squares in log-log: (c, e)"""
    lx, ly = [math.log(v) for v in x], [math.log(v) for v in y]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    e = sum((u - mx) * (v - my) for u, v in zip(lx, ly)) / sum((u - mx) ** 2 for u in lx)
    return math.exp(my - e * mx), e


# Peak memory per unknown of the contact brick with the defaults at n = 135 000 and H/h = 4, 6, 8 (/usr/bin/time %M of
# build/conefeti -options_file petsc-options/brick.opts -scene_refine 24 -scene_body0_subdomains 18,6,6 | 12,4,4 |
# 9,3,3: 342 076, 311 916, 358 736 KiB; docs/scale.md, "Past this machine"): the runs of --measure are too small
# (n <= 6e4) for the program's fixed ~50 MB not to dominate.
MEM_PER_DOF_DOC = {4: 342076 * 1024 / 135000, 6: 311916 * 1024 / 135000, 8: 358736 * 1024 / 135000}


def fit(data):
    """The coarse problem from its own counts: factor entries lnz and flops fl (CHOLMOD's, exact) as powers of Ns;
    a solve costs a time per factor entry (memory-bound triangular solves), the setup a time per subdomain (R, G,
    G G') plus a time per factor flop. Plain power fits of the times are given too (alpha, beta)."""
    rows = sorted([r for r in data["coarse"] if r["Ns"] >= 256], key=lambda r: r["Ns"])
    big = rows[-3:]
    m = {}
    Ns = [r["Ns"] for r in rows]
    m["alpha"] = powerfit(Ns, [r["coarse_setup"] for r in rows])
    m["beta"] = powerfit(Ns, [r["coarse_solve_time"] / r["coarse_solves"] for r in rows])
    m["lnz"] = powerfit([r["Ns"] for r in big], [r["lnz"] for r in big])
    m["flops"] = powerfit([r["Ns"] for r in big], [r["flops"] for r in big])
    m["t_entry"] = sum(r["coarse_solve_time"] / r["coarse_solves"] for r in big) / sum(r["lnz"] for r in big)
    # setup = u Ns + v fl: 2x2 normal equations, relative residuals (each row divided by its time)
    A = [(r["Ns"] / r["coarse_setup"], r["flops"] / r["coarse_setup"]) for r in rows]
    a11, a12, a22 = sum(x * x for x, _ in A), sum(x * y for x, y in A), sum(y * y for _, y in A)
    b1, b2 = sum(x for x, _ in A), sum(y for _, y in A)
    det = a11 * a22 - a12 * a12
    m["t_sub_setup"], m["t_flop"] = (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det
    m["largest"] = big[-1]
    sub = sorted(data["subdomain"], key=lambda r: r["hh"])
    hh = [r["hh"] for r in sub]
    m["sub_product"] = powerfit(hh, [r["product_time"] / r["products"] / r["Ns"] for r in sub])  # s per subdomain per product
    m["sub_factor"] = powerfit(hh, [r["factor_time"] / r["factor_count"] for r in sub])  # s per factorization
    m["mem_per_dof"] = powerfit(sorted(MEM_PER_DOF_DOC), [MEM_PER_DOF_DOC[h] for h in sorted(MEM_PER_DOF_DOC)])
    m["factors_per_subdomain"] = sum(r["factor_count"] for r in sub) / sum(r["Ns"] for r in sub)
    m["linear_coarse_per_product"] = sum(r["coarse_solves"] for r in rows) / sum(r["products"] for r in rows)
    return m


def coarse_costs(m, Nc, nd=False):
    """(factor entries, setup seconds, seconds per solve) of a coarse problem of Nc subdomains (6 Nc unknowns);
    nd: nested-dissection exponents (4/3 for the entries, 2 for the flops) from the largest measured run instead"""
    if nd:
        r = m["largest"]
        lnz, fl = r["lnz"] * (Nc / r["Ns"]) ** (4 / 3), r["flops"] * (Nc / r["Ns"]) ** 2
    else:
        lnz, fl = m["lnz"][0] * Nc ** m["lnz"][1], m["flops"][0] * Nc ** m["flops"][1]
    return lnz, m["t_sub_setup"] * Nc + m["t_flop"] * fl, m["t_entry"] * lnz


def predict(m, n, nodes, hh, a, mode="single", cluster=1, nd=False):
    """Per F product and setup, seconds; memory per rank, bytes. mode: single (rank 0 factors and solves),
    redundant (every rank), parallel (the factor spread evenly over the ranks, and its solve sqrt(ranks) times
    faster: an optimistic assumption, not measured; MUMPS's solve phase scales far less than its factorization).
    cluster: subdomains per cluster in hybrid FETI (coarse dimension divided by it; the clusters' own small coarse
    problems, local to a few ranks, are left out)."""
    R = nodes * a.ranks_per_node
    d = 3 * hh ** 3  # owned unknowns per subdomain
    Ns = n / d
    Nc = Ns / cluster
    lnz, coarse_setup, coarse_one = coarse_costs(m, Nc, nd)
    coarse_mem = 12.0 * lnz  # 8 bytes and a 4-byte index per entry
    sub = m["sub_product"][0] * hh ** m["sub_product"][1] * max(1.0, Ns / R)  # a rank has at least one subdomain
    gather = 2 * (a.latency * math.log2(R) + 8 * 6 * Nc / a.bandwidth)  # right-hand side to rank 0, solution back
    if mode == "redundant":
        gather = a.latency * math.log2(R) + 8 * 6 * Nc / a.bandwidth  # an allgather, nothing sent back
    if mode == "parallel":
        s = math.sqrt(R)
        coarse_one, coarse_setup, coarse_mem = coarse_one / s + 2 * a.latency * math.log2(R) * math.log2(max(Nc, 2)), coarse_setup / s, coarse_mem / R
        gather = 0.0
    coarse = CONTACT_COARSE_PER_PRODUCT * (coarse_one + gather)
    comm = 4 * a.latency * math.log2(R)  # four reductions per product (dot products, norms): an assumption
    factors = m["sub_factor"][0] * hh ** m["sub_factor"][1] * m["factors_per_subdomain"] * max(1.0, Ns / R)
    mem_rank = m["mem_per_dof"][0] * hh ** m["mem_per_dof"][1] * n / R
    nA = CONTACT_NA_1E6 * NA_GROWTH_PER_DECADE ** math.log10(n / 1e6)
    return dict(R=R, Ns=Ns, dim=6 * Nc, sub=sub, coarse=coarse, comm=comm, product=sub + coarse + comm, factors=factors, coarse_setup=coarse_setup,
                mem_rank=mem_rank, mem0=mem_rank + coarse_mem, coarse_mem=coarse_mem, nA=nA, total=factors + coarse_setup + nA * (sub + coarse + comm))


def crossover(m, nodes, hh, a, what):
    """The smallest n (10^4 to 10^10, 40 steps per decade) where the coarse part of a product exceeds the subdomain
    work (what = "time") or rank 0's memory exceeds its share of the node (what = "memory")"""
    for e in range(160, 401):
        n = 10 ** (e / 40)
        p = predict(m, n, nodes, hh, a)
        if (what == "time" and p["coarse"] > p["sub"]) or (what == "memory" and p["mem0"] > a.node_memory * 1e9 / a.ranks_per_node):
            return n
    return float("inf")


def fmt_t(t):
    return "%.2g s" % t if t >= 1 else "%.2g ms" % (t * 1e3) if t >= 1e-3 else "%.2g us" % (t * 1e6)


def fmt_b(b):
    return "%.3g GB" % (b / 1e9) if b >= 1e9 else "%.3g MB" % (b / 1e6)


def report(data, a):
    m = fit(data)
    out = []
    out.append("Fitted on `%s` (saved in %s; %s):" % (data["command"], os.path.relpath(a.data, ROOT), data["machine"]))
    out.append("")
    out.append("| measured | Ns | coarse dim | coarse setup [s] | coarse solves | per solve [ms] | factor entries (lnz) | factor flops | peak memory |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    for r in sorted(data["coarse"], key=lambda r: r["Ns"]):
        out.append("| H/h = 2, p = %d, n = %d | %d | %d | %.3f | %d | %.3f | %s | %s | %s |" % (
            r["p"], r["n"], r["Ns"], r["coarse_dim"], r["coarse_setup"], r["coarse_solves"], 1e3 * r["coarse_solve_time"] / r["coarse_solves"],
            "%.3g" % r["lnz"] if r.get("lnz") else "-", "%.3g" % r["flops"] if r.get("flops") else "-", fmt_b(r["mem"])))
    out.append("")
    out.append("| measured | Ns | n | factorizations | per factorization [ms] | F products | per product per subdomain [ms] | peak memory per unknown |")
    out.append("|---|---|---|---|---|---|---|---|")
    for r in sorted(data["subdomain"], key=lambda r: r["hh"]):
        out.append("| H/h = %d | %d | %d | %d | %.2f | %d | %.3f | %.2f KB |" % (r["hh"], r["Ns"], r["n"], r["factor_count"], 1e3 * r["factor_time"] / r["factor_count"], r["products"],
                                                                             1e3 * r["product_time"] / r["products"] / r["Ns"], r["mem"] / r["n"] / 1e3))
    out.append("")
    out.append("Fits (least squares in log-log; Ns = floating subdomains, coarse dimension 6 Ns; the times of the runs above):")
    out.append("")
    out.append("- coarse setup (R, G, G G' and its Cholesky) = %.3g s x Ns^%.2f (alpha) and coarse solve = %.3g s x Ns^%.2f per solve (beta), over Ns = 256 to %d" % (
        m["alpha"] + m["beta"] + (m["largest"]["Ns"],)))
    out.append("- the coarse factor (CHOLMOD's own counts, largest three runs): entries lnz = %.3g x Ns^%.2f (nested dissection of a 3D-connected graph: Ns^(4/3) = Ns^1.33), flops fl = %.3g x Ns^%.2f (nested dissection: Ns^2)" % (
        m["lnz"] + m["flops"]))
    out.append("- hence the model: a coarse solve = %.3g ns per factor entry x lnz; the coarse setup = %.3g ms per subdomain + %.3g ns per factor flop x fl" % (
        m["t_entry"] * 1e9, m["t_sub_setup"] * 1e3, m["t_flop"] * 1e9))
    out.append("- subdomain work per F product = %.3g s x (H/h)^%.2f per subdomain; factorizations %.3g s x (H/h)^%.2f each, %.1f per subdomain (its own and the Dirichlet preconditioner's)" % (
        m["sub_product"] + m["sub_factor"] + (m["factors_per_subdomain"],)))
    out.append("- peak memory = %.3g B x (H/h)^%.2f per unknown (the contact brick with the defaults at n = 135 000: %.2f, %.2f, %.2f KB at H/h = 4, 6, 8)" % (m["mem_per_dof"] + tuple(MEM_PER_DOF_DOC[h] / 1e3 for h in (4, 6, 8))))
    out.append("- coarse solves per F product: %.2f in the contact solver (docs/scale.md, the 10^6 brick of the table: FETICoarseSolve 859 / FETI_MultF 238), %.2f in the linear runs above" % (
        CONTACT_COARSE_PER_PRODUCT, m["linear_coarse_per_product"]))
    out.append("")
    out.append("Prediction (contact brick, single mode; node = %d ranks, %.0f GB; latency %.0f us, bandwidth %.0f GB/s: assumed; F products per solve n_A = %d x %.2f^log10(n/10^6), from the table at the top):" % (
        a.ranks_per_node, a.node_memory, a.latency * 1e6, a.bandwidth / 1e9, CONTACT_NA_1E6, NA_GROWTH_PER_DECADE))
    out.append("")
    out.append("| n | nodes | H/h | subdomains | coarse dim | F product: subdomains + coarse + reductions | setup: factorizations + coarse factor | memory per rank; rank 0's coarse factor | whole solve (n_A products) | bottleneck |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    grid = []
    for n in (1e7, 1e8, 1e9):
        for nodes in (10, 100, 1000):
            for hh in a.hh:
                p = predict(m, n, nodes, hh, a)
                grid.append((n, nodes, hh, p))
                parts = dict(subdomains=p["sub"], coarse=p["coarse"], reductions=p["comm"])
                bott = max(parts, key=parts.get)
                share = a.node_memory * 1e9 / a.ranks_per_node
                if p["mem_rank"] > share:
                    bott += "; every rank out of memory (more nodes)"
                elif p["mem0"] > share:
                    bott += "; rank 0 out of memory"
                out.append("| 10^%d | %d | %d | %.3g | %.3g | %s + %s + %s = %s | %s + %s | %s; %s | %s | %s |" % (
                    round(math.log10(n)), nodes, hh, p["Ns"], p["dim"], fmt_t(p["sub"]), fmt_t(p["coarse"]), fmt_t(p["comm"]), fmt_t(p["product"]),
                    fmt_t(p["factors"]), fmt_t(p["coarse_setup"]), fmt_b(p["mem_rank"]), fmt_b(p["coarse_mem"]), fmt_t(p["total"]), bott))
    out.append("")
    out.append("Where the coarse problem becomes the bottleneck (single mode, H/h = 6): the smallest n at which its part of an F product exceeds the subdomain work per rank, and at which rank 0 (its share of the node plus the coarse factor) runs out of memory:")
    out.append("")
    out.append("| nodes | ranks | coarse time > subdomain time from n = | coarse factor does not fit rank 0 from n = |")
    out.append("|---|---|---|---|")
    for nodes in (1, 10, 100, 1000):
        ct, cm = crossover(m, nodes, 6, a, "time"), crossover(m, nodes, 6, a, "memory")
        below = lambda c: ("<= %.2g (the smallest n scanned)" if c <= 1e4 else "%.2g") % c  # noqa: E731
        out.append("| %d | %d | %s | %s |" % (nodes, nodes * a.ranks_per_node, below(ct), below(cm)))
    out.append("")
    p6, p6nd = predict(m, 1e8, 100, 6, a), predict(m, 1e8, 100, 6, a, nd=True)
    out.append("With the nested-dissection exponents (entries Ns^(4/3), flops Ns^2) from the largest run instead of the fitted ones, 10^8 on 100 nodes at H/h = 6 would have a coarse factor of %s (not %s), a coarse part of %s per product (not %s) and a coarse setup of %s (not %s)." % (
        fmt_b(p6nd["coarse_mem"]), fmt_b(p6["coarse_mem"]), fmt_t(p6nd["coarse"]), fmt_t(p6["coarse"]), fmt_t(p6nd["coarse_setup"]), fmt_t(p6["coarse_setup"])))
    lnz, st, so = coarse_costs(m, 50000 / 6)
    out.append("At the coarse dimension 50 000 (Ns = 8 333; -feti_coarse_parallel_dim's default) the model gives a factor of %s, a coarse setup of %s and %s per solve on rank 0." % (fmt_b(12 * lnz), fmt_t(st), fmt_t(so)))
    out.append("")
    out.append("Remedies at n = 10^8 on 100 nodes (H/h = 6 unless said; time per F product, setup, rank 0's memory):")
    out.append("")
    out.append("| remedy | F product | coarse part | setup | rank 0 memory | whole solve |")
    out.append("|---|---|---|---|---|---|")
    rem = [("single (what auto picks from a coarse dimension of 10 000 to 50 000)", dict()), ("redundant", dict(mode="redundant")), ("parallel, ideal sqrt(ranks) speedup (assumed)", dict(mode="parallel")),
           ("fewer larger subdomains, H/h = 10", dict(hh=10)), ("fewer larger subdomains, H/h = 12", dict(hh=12)),
           ("hybrid FETI, clusters of 8 subdomains", dict(cluster=8)), ("hybrid FETI, clusters of 64", dict(cluster=64)),
           ("H/h = 12 and parallel", dict(hh=12, mode="parallel"))]
    ranked = []
    for name, kw in rem:
        p = predict(m, 1e8, 100, kw.get("hh", 6), a, kw.get("mode", "single"), kw.get("cluster", 1))
        ranked.append((p["total"], name, p))
    for t, name, p in ranked:
        out.append("| %s | %s | %s | %s | %s | %s |" % (name, fmt_t(p["product"]), fmt_t(p["coarse"]), fmt_t(p["factors"] + p["coarse_setup"]), fmt_b(p["mem0"]) + (" (every rank)" if "redundant" in name else ""), fmt_t(t)))
    text = "\n".join(out)
    print(text)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
        rows = sorted(data["coarse"], key=lambda r: r["Ns"])
        Ns = [r["Ns"] for r in rows]
        ax1.loglog(Ns, [r["coarse_setup"] for r in rows], "o", label="coarse setup (measured)")
        ax1.loglog(Ns, [r["coarse_solve_time"] / r["coarse_solves"] for r in rows], "s", label="coarse solve (measured)")
        xs = [10 ** (e / 10) for e in range(10, 61)]
        ax1.loglog(xs, [coarse_costs(m, x)[1] for x in xs], "-", label="setup model: per subdomain + per factor flop")
        ax1.loglog(xs, [coarse_costs(m, x)[2] for x in xs], "--", label="solve model: per factor entry")
        ax1.loglog(xs, [coarse_costs(m, x, nd=True)[2] for x in xs], ":", label="solve, nested-dissection exponent")
        ax1.set_xlabel("floating subdomains Ns (coarse dimension 6 Ns)")
        ax1.set_ylabel("seconds (one rank)")
        ax1.set_title("coarse problem, measured and extrapolated")
        colors = {10: "C0", 100: "C1", 1000: "C2"}
        for hh, mark in zip(a.hh, ("o", "s", "^", "v")):
            for nodes in (10, 100, 1000):
                sel = [(n, p) for n, nd, h, p in grid if nd == nodes and h == hh]
                ax2.loglog([n for n, _ in sel], [p["sub"] for _, p in sel], mark + "-", color=colors[nodes], label="subdomains, %d nodes, H/h %d" % (nodes, hh))
                ax2.loglog([n for n, _ in sel], [p["coarse"] for _, p in sel], mark + "--", color="C3", label="coarse (single; any node count), H/h %d" % hh if nodes == 10 else None)
        ax2.set_xlabel("n (primal unknowns)")
        ax2.set_ylabel("seconds per F product")
        ax2.set_title("model: time per F product and rank")
        for ax in (ax1, ax2):
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        fig.tight_layout()
        os.makedirs(os.path.dirname(a.png), exist_ok=True)
        fig.savefig(a.png, dpi=110)
        print("\nwrote %s" % a.png)
    except ImportError:
        print("scale-model: matplotlib missing (apt-get install python3-matplotlib): no plot")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--measure", action="store_true")
    ap.add_argument("--coarse-sizes", default="2,4,6,8,10,12", help="p of the H/h = 2 series: 4p^3 subdomains")
    ap.add_argument("--build", default="build")
    ap.add_argument("--data", default=os.path.join(ROOT, "scripts", "data", "scale-model.json"))
    ap.add_argument("--png", default=os.path.join(ROOT, "docs", "figures", "scale-model.png"))
    ap.add_argument("--ranks-per-node", type=int, default=32)
    ap.add_argument("--node-memory", type=float, default=128, help="GB")
    ap.add_argument("--latency", type=float, default=2e-6, help="seconds per message hop (assumed)")
    ap.add_argument("--bandwidth", type=float, default=1e10, help="bytes per second (assumed)")
    ap.add_argument("--hh", default="6,12", help="subdomain sizes of the prediction table")
    a = ap.parse_args()
    a.hh = [int(x) for x in a.hh.split(",")]
    if a.measure:
        measure(a)
    report(json.load(open(a.data)), a)


if __name__ == "__main__":
    main()
