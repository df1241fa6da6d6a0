#!/usr/bin/python3
"""Check the layout of the manual pages (/*@ ... @*/) that clang-format can break: in the lists of parameters and
options (Input Parameter(s), Output Parameter(s), Options Database Key(s)) every line is an item (+, ., -) or the
indented continuation of one. A line of a list longer than the column limit makes clang-format reflow the rest of
the list into one paragraph, which PETSc's manual page tools then read as one item.
Usage: scripts/check-manpages.py [files...] (default: the C/C++ sources git knows of). Exit 1 lists the breaks."""
import pathlib
import re
import subprocess
import sys

LISTS = re.compile(r"^\s*(Input Parameters?|Output Parameters?|Options Database Keys?|Collective Input Parameters?)\s*:?\s*$")


def sources():
    root = pathlib.Path(__file__).resolve().parent.parent
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.c", "*.cxx", "*.h", "*.hpp"], cwd=root,
                         capture_output=True, text=True, check=True).stdout.split()
    return [root / f for f in out]


def check(path):
    bad = []
    inpage = inlist = False
    for no, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        if line.startswith(("/*@", "/*MC")):
            inpage, inlist = True, False
            continue
        if inpage and ("@*/" in line or "M*/" in line):
            inpage = inlist = False
            continue
        if not inpage:
            continue
        if LISTS.match(line):
            inlist = True
            continue
        if inlist:
            if not line.strip():
                inlist = False
            elif not (line[:2] in ("+ ", ". ", "- ") or line[:1] in (" ", "\t")):
                bad.append(f"{path}:{no}: a list line that is neither an item (+ . -) nor indented: {line[:80]}")
            elif line[:2] in ("+ ", ". ", "- ") and re.search(r"\S \. -\w", line[2:]):
                bad.append(f"{path}:{no}: two items on one line (reflowed?): {line[:80]}")
    return bad


def main():
    files = [pathlib.Path(f) for f in sys.argv[1:]] or sources()
    bad = [b for f in files for b in check(f)]
    for b in bad:
        print(b)
    if bad:
        print(f"{len(bad)} manual page list line(s) broken (clang-format reflowed a list? keep each item within the column limit)")
        return 1
    print(f"manual pages: {len(files)} files ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
