#!/usr/bin/python3
"""Which solver configurations meet the benchmark's goals on the seed paper's brick, and what they cost elsewhere.

For each configuration (a set of extra brick options) runs the brick at the paper's five sizes for
F = 0.1 and 0.3 and checks the goals: Iter <= 5 (F = 0.1) and <= 7 (F = 0.3), n_A <= the paper's at
every size, n_A growing by at most 1.3x from n = 900 to n = 18252, and setup + solve of the largest size
under 1 s. With --others it also sums n_A over 18 other bricks (k = 3, 5, 7, 9, 11, 14 and F = 0.05,
0.2, 0.5): products are what a solve costs in time, so a configuration that meets the goals by spending
more products elsewhere is a trade, not a better default. Iter and n_A are machine independent; times
are measured only with --jobs 1 (runs side by side would disturb them).

usage: scripts/goals-brick.py [--config "label=options"]... [--grid "-option=v1,v2 -option2=v3,v4"]
                              [--others] [--jobs 2] [--rtol 1e-4] [--build build]
  --config  one configuration (repeatable); "default" is the brick's defaults
  --grid    every combination of the listed values (each -option=v1,v2,...; a value "off" leaves the
            option out, a flag takes the value "on"); a row is labelled by the values that vary
"""
import argparse, itertools, sys
from concurrent.futures import ThreadPoolExecutor

import hugepages
from seedpaper import GROWTH_GOAL, ITER_GOAL, PAPER, TIME_GOAL, brick_n, run

SIZES = (4, 6, 8, 10, 12)  # k of the paper's n = 900 ... 18252
OTHERS = [(k, F) for F in (0.05, 0.2, 0.5) for k in (3, 5, 7, 9, 11, 14)]


def evaluate(a, env, label, options):
    row = dict(label=label, unmet=[], paper_total=0, others=None)
    for F in (0.1, 0.3):
        rs = [run(a.build, k, F, a.rtol, options, env) for k in SIZES]
        its, nas = [r["iter"] for r in rs], [r["nA"] for r in rs]
        growth = nas[-1] / nas[0]
        row[F] = dict(its=its, nas=nas, growth=growth, time=rs[-1]["setup"] + rs[-1]["solve"])
        row["paper_total"] += sum(nas)
        if not all(r["converged"] for r in rs):
            row["unmet"].append("F=%g converged" % F)
        if max(its) > ITER_GOAL[F]:
            row["unmet"].append("F=%g Iter" % F)
        if any(n > PAPER[brick_n(k)][1][F][1] for n, k in zip(nas, SIZES)):
            row["unmet"].append("F=%g n_A" % F)
        if growth > GROWTH_GOAL:
            row["unmet"].append("F=%g growth" % F)
        if a.jobs == 1 and row[F]["time"] >= TIME_GOAL:
            row["unmet"].append("F=%g time" % F)
    if a.others:
        rs = [run(a.build, k, F, a.rtol, options, env) for k, F in OTHERS]
        row["others"] = (sum(r["nA"] for r in rs), max(r["iter"] for r in rs))
    return row


def grid(spec):
    axes = []
    for item in spec.split():
        name, _, values = item.partition("=")
        if not name.startswith("-") or not values:
            sys.exit("--grid: expected -option=v1,v2,..., got %r" % item)
        axes.append([(name, v) for v in values.split(",")])
    for combo in itertools.product(*axes):
        options, label = [], []
        for (name, v), axis in zip(combo, axes):
            if len(axis) > 1:  # the label names only what varies (the last word of the option name)
                label.append("%s %s" % (name.rsplit("_", 1)[-1], v))
            if v == "off":
                continue
            options += [name] if v == "on" else [name, v]
        yield ", ".join(label) or " ".join(options) or "default", options


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", action="append", default=[])
    ap.add_argument("--grid", default="")
    ap.add_argument("--others", action="store_true")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--rtol", default="1e-4")
    ap.add_argument("--build", default="build")
    ap.add_argument("--hugepages", type=int, default=1, help="1: run with transparent huge pages (scripts/hugepages.py), 0: without")
    a = ap.parse_args()
    if a.jobs < 1:
        sys.exit("--jobs must be at least 1, got %d" % a.jobs)
    env = hugepages.environment(a.hugepages)
    configs = []
    for c in a.config:
        label, eq, opts = c.partition("=")
        if not eq and label != "default":
            sys.exit("--config: expected label=options (or default), got %r" % c)
        configs.append((label, opts.split()))
    if a.grid:
        configs += list(grid(a.grid))
    if not configs:
        configs = [("default", [])]
    print("# the benchmark's goals on the brick, per configuration (this machine, %s)" % hugepages.describe(a.hugepages))
    print("# command: %s" % " ".join(sys.argv))
    print("# Iter and n_A at n = 900, 2646, 5832, 10890, 18252; growth = n_A(18252)/n_A(900); paper total = n_A summed over both tables"
          + ("; others = n_A summed over 18 other bricks (largest Iter)" if a.others else ""))
    print()
    print("| configuration | F=0.1 Iter | F=0.1 n_A | growth | F=0.3 Iter | F=0.3 n_A | growth | paper total |%s goals not met |" % (" others |" if a.others else ""))
    print("|---|---|---|---|---|---|---|---|%s---|" % ("---|" if a.others else ""))
    met = 0
    with ThreadPoolExecutor(a.jobs) as ex:
        for row in ex.map(lambda c: evaluate(a, env, *c), configs):
            cells = [row["label"]]
            for F in (0.1, 0.3):
                r = row[F]
                cells += ["".join(map(str, r["its"])), ",".join(map(str, r["nas"])), "%.2fx" % r["growth"]]
            cells.append(str(row["paper_total"]))
            if a.others:
                cells.append("%d (Iter <= %d)" % row["others"])
            cells.append(", ".join(row["unmet"]) or "none")
            met += not row["unmet"]
            print("| " + " | ".join(cells) + " |", flush=True)
    print()
    print("%d of %d configurations meet every goal%s" % (met, len(configs), "" if a.jobs == 1 else " (the time goal not checked: --jobs > 1)"))


if __name__ == "__main__":
    main()
