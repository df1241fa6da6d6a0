#!/usr/bin/python3
"""CPU seconds spent inside given functions, from perf samples (a loaded machine's wall times hide them).

-log_view reports wall time, which on a shared machine mostly measures the other processes. perf's cpu-clock
samples count only the CPU time of the process, so the samples whose call stack contains a function, divided by
the sampling rate, are the CPU seconds spent inside it (its callees included). Usage:

  perf record -F 499 --call-graph dwarf,16384 -o run.perf build/conefeti -options_file petsc-options/brick.opts ...
  perf script -i run.perf -F comm,ip,sym,dso | scripts/perf-cpu.py --hz 499 ContactSceneSetUp FETISetUp MatConvert

prints one line per function (and the total): CPU seconds. With --below F it prints instead the CPU seconds of
each function called directly by F (the frames just below F in the stacks; inlined static functions count as
their caller), the largest first: where the time of F goes.
"""
import argparse
import collections
import sys


def stacks(lines):
    """the call stacks (leaf first) of perf script's output"""
    stack = []
    for line in lines:
        if not line.strip():
            if stack:
                yield stack
            stack = []
        elif line[0] in "\t ":
            parts = line.strip().split(" ", 1)
            if len(parts) > 1:
                sym = parts[1].rsplit(" (", 1)[0]
                if not sym.startswith("0x") and sym != "[unknown]":
                    stack.append(sym)
    if stack:
        yield stack


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hz", type=float, default=499.0, help="the sampling rate of perf record -F")
    ap.add_argument("--below", help="break this function down by its direct callees")
    ap.add_argument("functions", nargs="*")
    a = ap.parse_args()
    count, total = collections.Counter(), 0
    for st in stacks(sys.stdin):
        total += 1
        if a.below:
            if a.below in st:
                i = st.index(a.below)
                count[st[i - 1] if i > 0 else "(self)"] += 1
                count[a.below] += 1
        else:
            seen = set(st)
            for f in a.functions:
                if f in seen:
                    count[f] += 1
    print("%-40s %8.2f" % ("total", total / a.hz))
    names = [n for n, _ in count.most_common()] if a.below else a.functions
    for f in names:
        print("%-40s %8.2f" % (f, count[f] / a.hz))


if __name__ == "__main__":
    main()
