#!/usr/bin/python3
"""The counts the docs give as the current build's must be the current build's.

Each claim below is a command of the conefeti program and a sentence of a page, with {expressions} of the
fields of the command's JSON line (iter, n_A, n_A_other, kplus_blocks, subdomains, n, ...). The test runs the
command, fills the sentence in and looks for it in the page (whitespace, line breaks included, counts as one
space). A change of the solver that moves one of these counts fails here, naming the page, the sentence, what
the page says and what the build gives, so that the page is rerun and rewritten. Counts do not depend on the
load; they are those of this build on this host (its BLAS and solver packages): a host whose libraries round
differently may move one by a product, and then the page's numbers are this host's to restate.

    doc-counts.py --conefeti build/conefeti --source . [--mpiexec mpiexec] [--only NAME]
"""
import argparse
import json
import os
import re
import shlex
import subprocess
import sys

# (name, page, sentence with {expressions}, ranks, arguments of conefeti)
BRICK = "-options_file petsc-options/brick.opts"
CLAIMS = [
    ("readme_default_tolerance", "README.md", "(the default 1e-6: {n_A} products,", 1, BRICK + " -scene_refine 12"),
    ("readme_tight_tolerance", "README.md", "1e-10: {n_A})", 1, BRICK + " -scene_refine 12 -contact_rtol 1e-10"),
    ("brick_benchmark_paper_size", "docs/brick-benchmark.md", "Iter {iter} and `n_A` {n_A} in the JSON line", 1, BRICK + " -scene_refine 12"),
    ("feti_twobodies_blocks", "docs/feti.md",
     "`build/conefeti -options_file petsc-options/twobodies.opts` (1 and 3 ranks): a block in {kplus_blocks} of {subdomains} subdomains", 3,
     "-options_file petsc-options/twobodies.opts"),
    ("scale_table_p2", "docs/scale.md", "| {n} | {subdomains} | 1 | defaults | {iter} | {n_A} | auto: blocks in {kplus_blocks} of {subdomains} subdomains |", 1,
     BRICK + " -scene_refine 12 -scene_body0_subdomains 6,2,2"),
    ("scale_table_p4", "docs/scale.md", "| {n} | {subdomains} | 1 | defaults | {iter} | {n_A} | auto: blocks in {kplus_blocks} of {subdomains} subdomains |", 1,
     BRICK + " -scene_refine 24 -scene_body0_subdomains 12,4,4"),
]


def normalized(text):
    return re.sub(r"\s+", " ", text)


FIELD = re.compile(r"\{([^{}]+)\}")


def fill(sentence, fields):
    return FIELD.sub(lambda m: str(eval(m.group(1), {}, dict(fields))), sentence)


def page_values(sentence, text):
    """What the page says in the sentence's place: the values at its {fields}, or None if the words changed."""
    parts = FIELD.split(sentence)  # literal, expression, literal, ...
    pattern = "".join(re.escape(normalized(p)) if i % 2 == 0 else r"(\S+?)" for i, p in enumerate(parts))
    m = re.search(pattern, text)
    return list(m.groups()) if m else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--conefeti", required=True)
    ap.add_argument("--source", required=True, help="the repository (pages and options files)")
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--only", help="run only the claim of this name")
    a = ap.parse_args()
    failures = 0
    runs = {}  # (ranks, args) -> JSON fields, so that claims on one command run it once
    claims = [c for c in CLAIMS if not a.only or c[0] == a.only]
    if not claims:
        sys.exit("doc-counts.py: no claim named %s" % a.only)
    for name, page, sentence, ranks, args in claims:
        cmd = [a.mpiexec, "-n", str(ranks), os.path.abspath(a.conefeti)] + shlex.split(args) + ["-summary_table", "0", "-quiet"]
        try:
            if (ranks, args) not in runs:
                run = subprocess.run(cmd, cwd=a.source, capture_output=True, text=True)
                lines = [l for l in run.stdout.splitlines() if l.startswith('{"conefeti":')]
                if run.returncode != 0 or not lines:
                    raise RuntimeError("the command ended with exit %d%s:\n%s" % (run.returncode, "" if lines else " and no JSON line", run.stderr[-2000:]))
                runs[(ranks, args)] = json.loads(lines[-1])
            fields = runs[(ranks, args)]
            expected = normalized(fill(sentence, fields))
            with open(os.path.join(a.source, page), encoding="utf-8") as f:
                text = normalized(f.read())
        except Exception as e:  # one broken claim must not hide the others
            print("%s: %s (command: %s)" % (name, e, " ".join(cmd)))
            failures += 1
            continue
        if expected in text:
            print("%s: %s says it: %s" % (name, page, expected))
            continue
        said = page_values(sentence, text)
        builds = [str(eval(m.group(1), {}, dict(fields))) for m in FIELD.finditer(sentence)]
        where = ("the page says %s where this build gives %s" % (", ".join(said), ", ".join(builds))) if said else "the page no longer has this sentence"
        print("%s: %s does not say \"%s\": %s (command: %s); rerun the page's numbers and rewrite it, or update the claim here"
              % (name, page, expected, where, " ".join(cmd)))
        failures += 1
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
