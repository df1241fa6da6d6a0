#!/usr/bin/python3
"""usage: kplus-auto.py [--mixed] [--ratio r] -- conefeti-command... -info :sys,feti

-feti_kplus auto chose each subdomain's K+ as its rule says (fetimemory.cxx, FETISubdomainChooseKplus()): a
dense block (K+)_bb exactly where the block has nb^2 <= r times the factor's entries and its triangle is at most
twice the factor (nb^2 <= 4 entries), the factor's entries measured by its package (not the estimate), and the
JSON summary counts the blocks as the -info lines do. --mixed: some subdomains got blocks and some the factor."""
import json
import re
import subprocess
import sys

args = sys.argv[1:sys.argv.index("--")]
cmd = sys.argv[sys.argv.index("--") + 1:]
ratio = float(args[args.index("--ratio") + 1]) if "--ratio" in args else 1.0
proc = subprocess.run(cmd, capture_output=True, text=True)
out = proc.stdout + proc.stderr
fail = []
if proc.returncode != 0:
    fail.append("exit status %d" % proc.returncode)
choices = {}
pattern = re.compile(r"Subdomain (\d+): (dense block|factor): block \(K\+\)_bb (\d+)\^2 = (\d+) numbers, factor (\d+) entries \((measured|estimated)\), ratio [0-9.]+ "
                     r"\(-feti_kplus_memory_ratio ([0-9.e+-]+)\)")
for line in out.splitlines():
    m = pattern.search(line)
    if not m:
        continue
    s, choice, nb, numbers, entries, how, r = int(m.group(1)), m.group(2), int(m.group(3)), int(m.group(4)), int(m.group(5)), m.group(6), float(m.group(7))
    choices[s] = choice
    print("subdomain %d: %s, |b| = %d, block %d, factor %d (%s)" % (s, choice, nb, numbers, entries, how))
    if numbers != nb * nb:
        fail.append("subdomain %d: the block has %d numbers, not |b|^2 = %d" % (s, numbers, nb * nb))
    if how != "measured":
        fail.append("subdomain %d: the factor's entries were estimated, not read from the factor" % s)
    if r != ratio:
        fail.append("subdomain %d: ratio %g used, %g given" % (s, r, ratio))
    want = "dense block" if nb > 0 and numbers <= ratio * entries and numbers <= 4 * entries else "factor"
    if choice != want:
        fail.append("subdomain %d: %s chosen, the rule gives %s" % (s, choice, want))
lines = [l for l in out.splitlines() if l.startswith('{"conefeti":')]
if len(lines) != 1:
    fail.append("%d JSON summary lines, expected 1" % len(lines))
else:
    d = json.loads(lines[0])
    blocks = sum(1 for c in choices.values() if c == "dense block")
    print("JSON: kplus %r, kplus_blocks %d, subdomains %d; -info: %d blocks in %d subdomains" % (d["kplus"], d["kplus_blocks"], d["subdomains"], blocks, len(choices)))
    if len(choices) != d["subdomains"]:
        fail.append("-info gave the choice of %d subdomains, the scene has %d" % (len(choices), d["subdomains"]))
    if d["kplus_blocks"] != blocks:
        fail.append("JSON kplus_blocks %d, -info counts %d blocks" % (d["kplus_blocks"], blocks))
    if d["kplus"] != "auto: blocks in %d of %d subdomains" % (blocks, d["subdomains"]):
        fail.append("JSON kplus %r does not say auto and the counts" % d["kplus"])
    if "--mixed" in args and not 0 < blocks < d["subdomains"]:
        fail.append("not a mixed choice: %d blocks in %d subdomains" % (blocks, d["subdomains"]))
if fail:
    print(out[-3000:])
    sys.exit("kplus-auto.py: " + "; ".join(fail))
print("the auto choice follows its rule")
