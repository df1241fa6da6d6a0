#!/usr/bin/python3
"""usage: kplus-auto.py [--mixed] [--ratio r] [--speedup s] [--budget MB] -- conefeti-command... -info :sys,feti

-feti_kplus auto chose each subdomain's K+ as its rule says (fetimemory.cxx, FETIChooseKplusBlocks()), recomputed
here from the counts the -info lines give: a subdomain is a candidate when its factor's reads per F product are at
least s times its block's (the triangle, |b|^2/2); the candidates get their blocks in decreasing order of
(factor reads - block reads) / |b|^2 (ties: lower subdomain number first), a block that does not fit being
skipped, while all blocks' numbers stay within r times all factors' entries and the budget (MB / 8 bytes). Also:
every factor's entries were measured by its package (not estimated), the blocks together respect the bound, and
the JSON summary counts the blocks as the -info lines do. --mixed: some subdomains got blocks and some the factor."""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

args = sys.argv[1:sys.argv.index("--")]
cmd = sys.argv[sys.argv.index("--") + 1:]


def opt(name, default):
    return float(args[args.index(name) + 1]) if name in args else default


ratio, speedup, budget = opt("--ratio", 1.0), opt("--speedup", 2.0), opt("--budget", -1.0)
# each rank writes its -info lines to a file of its own (PETSc appends the rank): on 2 ranks, lines that both ranks
# write to one pipe can be cut and interleaved, which lost a subdomain's line now and then
tmp = tempfile.mkdtemp(prefix="kplus-auto-")
if "-info" in cmd:
    i = cmd.index("-info")
    if i + 1 < len(cmd) and cmd[i + 1].startswith(":"):
        cmd[i + 1] = os.path.join(tmp, "info") + cmd[i + 1]
proc = subprocess.run(cmd, capture_output=True, text=True)
out = proc.stdout + proc.stderr
for f in sorted(glob.glob(os.path.join(tmp, "info*"))):
    out += "\n" + open(f).read()
shutil.rmtree(tmp, ignore_errors=True)
fail = []
if proc.returncode != 0:
    fail.append("exit status %d" % proc.returncode)
subs = {}
pattern = re.compile(r"Subdomain (\d+): (dense block|factor): block \(K\+\)_bb (\d+)\^2 = (\d+) numbers, factor (\d+) entries; reads per F product: factor (\d+), "
                     r"block (\d+), speedup [0-9.]+ \(-feti_kplus_speedup ([0-9.e+-]+)\)")
for line in out.splitlines():
    m = pattern.search(line)
    if not m:
        continue
    s, choice = int(m.group(1)), m.group(2)
    nb, numbers, entries, freads, breads = (int(m.group(i)) for i in range(3, 8))
    sp = float(m.group(8))
    subs[s] = dict(choice=choice, nb=nb, entries=entries, freads=freads, breads=breads)
    print("subdomain %d: %s, |b| = %d, block %d, factor %d entries, reads %d against %d" % (s, choice, nb, numbers, entries, freads, breads))
    if numbers != nb * nb:
        fail.append("subdomain %d: the block has %d numbers, not |b|^2 = %d" % (s, numbers, nb * nb))
    if abs(breads - nb * nb / 2) > 1:
        fail.append("subdomain %d: the block reads %d numbers, not |b|^2/2 = %g" % (s, breads, nb * nb / 2))
    floatcopy = abs(freads - 2 * (0.5 + 0.5 / 9) * entries) <= 1  # -feti_kplus_precision single: half a number per entry and per block index
    if freads < 2 * entries - 1 and not floatcopy:
        fail.append("subdomain %d: the factor reads %d numbers, less than its entries twice (%d)" % (s, freads, 2 * entries))
    if sp != speedup:
        fail.append("subdomain %d: speedup %g used, %g given" % (s, sp, speedup))
measured = len(re.findall(r"Factor of \d+ dofs \(\w+\): \d+ entries measured", out))
if measured != len(subs):
    fail.append("%d factors measured by their package, %d subdomains" % (measured, len(subs)))
# the rule, from the counts
total = sum(d["entries"] for d in subs.values())
cap = ratio * total
if budget > 0:
    cap = min(cap, budget * 1048576.0 / 8)
cands = [s for s, d in subs.items() if d["nb"] > 0 and d["freads"] >= speedup * d["breads"]]
cands.sort(key=lambda s: (-(subs[s]["freads"] - subs[s]["breads"]) / subs[s]["nb"] ** 2, s))
used, want = 0, set()
for s in cands:
    if used + subs[s]["nb"] ** 2 <= cap:
        want.add(s)
        used += subs[s]["nb"] ** 2
got = {s for s, d in subs.items() if d["choice"] == "dense block"}
for s in sorted(set(subs)):
    if (s in got) != (s in want):
        fail.append("subdomain %d: %s chosen, the rule gives %s" % (s, subs[s]["choice"], "dense block" if s in want else "factor"))
blocknumbers = sum(subs[s]["nb"] ** 2 for s in got)
print("candidates %s, blocks %s: %d numbers, bound %.0f (%d factor entries)" % (sorted(cands), sorted(got), blocknumbers, cap, total))
if blocknumbers > cap * (1 + 1e-12):
    fail.append("the blocks take %d numbers, more than the bound %.0f" % (blocknumbers, cap))
lines = [l for l in out.splitlines() if l.startswith('{"conefeti":')]
if len(lines) != 1:
    fail.append("%d JSON summary lines, expected 1" % len(lines))
else:
    d = json.loads(lines[0])
    blocks = len(got)
    print("JSON: kplus %r, kplus_blocks %d, subdomains %d; -info: %d blocks in %d subdomains" % (d["kplus"], d["kplus_blocks"], d["subdomains"], blocks, len(subs)))
    if len(subs) != d["subdomains"]:
        fail.append("-info gave the choice of %d subdomains, the scene has %d" % (len(subs), d["subdomains"]))
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
