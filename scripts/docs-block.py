#!/usr/bin/python3
"""Replace a generated block of a docs page with what a script printed (used by scripts/figures.sh).

    some-benchmark-script | scripts/docs-block.py docs/page.md NAME [--provenance "commit X, machine Y"]

The page marks the block with a comment line `<!-- generated: NAME -->` directly followed by a fenced
code block (```); everything inside that fence is replaced by standard input, with the provenance as a
first line "# made at <provenance>" when given. Exits 1 when the page has no such marker, or has it twice.
"""
import argparse, sys


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("page")
    ap.add_argument("name")
    ap.add_argument("--provenance")
    a = ap.parse_args()
    lines = open(a.page).read().split("\n")
    marker = "<!-- generated: %s -->" % a.name
    at = [i for i, l in enumerate(lines) if l.strip() == marker]
    if len(at) != 1:
        sys.exit("docs-block.py: %s has %d markers '%s' (expected one)" % (a.page, len(at), marker))
    i = at[0] + 1
    if i >= len(lines) or not lines[i].startswith("```"):
        sys.exit("docs-block.py: in %s the marker '%s' is not followed by a fenced block" % (a.page, marker))
    j = i + 1
    while j < len(lines) and lines[j] != "```":
        j += 1
    if j == len(lines):
        sys.exit("docs-block.py: in %s the block after '%s' is not closed" % (a.page, marker))
    new = sys.stdin.read().rstrip("\n").split("\n")
    if a.provenance:
        new = ["# made at %s" % a.provenance] + new
    lines[i + 1:j] = new
    with open(a.page, "w") as f:
        f.write("\n".join(lines))
    print("docs-block.py: %s: block '%s' replaced (%d lines)" % (a.page, a.name, len(new)))


if __name__ == "__main__":
    main()
