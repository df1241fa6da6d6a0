#!/usr/bin/env bash
# The README's main command: set up (Debian packages), build, then solve the seed paper's brick with
# Coulomb friction F = 0.1 (petsc-options/brick-f01.opts) and F = 0.3 (petsc-options/brick.opts) at the
# paper's sizes n = 900, 2646, 5832, 10890, 18252 with the conefeti program, and print one table per
# friction coefficient in the layout of the paper's Tables 1 and 2 (the paper's Iter and n_A beside ours;
# its times were Matlab on a 2008 PC, ours are this machine's), then the full summary of the last run.
# About a minute on 2 cores once built (the first build takes about two minutes more).
#
# The contact tolerance is 1e-4 (-contact_rtol; docs/brick-benchmark.md states the same), where the
# paper's iteration counts are comparable; the scenes' own default is 1e-6.
# Environment: RTOL (default 1e-4), SCENES (default "petsc-options/brick-f01.opts petsc-options/brick.opts"),
#              SIZES (default "4 6 8 10 12": -scene_refine values), RANKS (default 1), BUILD_DIR (default build),
#              HUGEPAGES (default 1: glibc's large allocations on transparent huge pages, scripts/hugepages.py
#              says why; 0: 4 KB pages; the results are the same, only the setup time changes).
# Exit status: 0 when every run converged, else the last failing run's status (2: not converged).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh >/dev/null
build=${BUILD_DIR:-build}
export OMP_NUM_THREADS=1
if [ "${HUGEPAGES:-1}" != 0 ]; then
  case ":${GLIBC_TUNABLES:-}:" in
    *glibc.malloc.hugetlb*) ;;
    *) export GLIBC_TUNABLES="${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1" ;;
  esac
fi
ranks=${RANKS:-1}
run=("$build/conefeti")
if [ "$ranks" -gt 1 ]; then run=(mpiexec --allow-run-as-root --oversubscribe -n "$ranks" "$build/conefeti"); fi
py=/usr/bin/python3
json=$(mktemp); log=$(mktemp); trap 'rm -f "$json" "$log"' EXIT
status=0
for scene in ${SCENES:-petsc-options/brick-f01.opts petsc-options/brick.opts}; do
  : >"$json"
  for k in ${SIZES:-4 6 8 10 12}; do
    rc=0
    "${run[@]}" -options_file "$scene" -scene_refine "$k" -contact_rtol "${RTOL:-1e-4}" >"$log" 2>&1 || rc=$?
    if ! grep -q '^{"conefeti":' "$log"; then cat "$log"; echo "main.sh: $scene with -scene_refine $k failed (exit $rc)"; exit 1; fi
    grep '^{"conefeti":' "$log" >>"$json"
    [ $rc -eq 0 ] || status=$rc
  done
  echo
  echo "$scene ($(grep -m1 '^conefeti .*: pipeline' "$log" | sed 's/^conefeti [0-9.]*: //'); -contact_rtol ${RTOL:-1e-4})"
  $py - "$json" <<'PY'
import json, sys
# the seed paper's Tables 1 (F = 0.1) and 2 (F = 0.3): n -> (Iter, n_A)
paper = {"brick-f01": {900: (5, 102), 2646: (5, 180), 5832: (5, 156), 10890: (5, 112), 18252: (5, 155)},
         "brick": {900: (7, 140), 2646: (7, 186), 5832: (7, 169), 10890: (7, 153), 18252: (7, 176)}}
rows = [json.loads(l) for l in open(sys.argv[1])]
print("%8s %6s %6s %6s %6s %6s %6s | %5s %5s | %5s %6s %5s %9s %9s  %s" % ("n", "m", "Iter", "n_A", "QPP", "QPQ", "other", "paper", "paper", "sep", "stick", "slip", "setup[s]", "solve[s]", "residual"))
print("%8s %6s %6s %6s %6s %6s %6s | %5s %5s |" % ("", "", "", "", "", "", "", "Iter", "n_A"))
for r in rows:
    p = paper.get(r["scene"], {}).get(r["n"], ("", ""))
    print("%8d %6d %6d %6d %6d %6d %6d | %5s %5s | %5d %6d %5d %9.3f %9.3f  %.1e%s" % (r["n"], r["m"], r["iter"], r["n_A"], r["n_A_qpp"], r["n_A_qpq"], r["n_A_other"], p[0], p[1],
          r["separated"], r["stick"], r["slip"], r["time_setup"], r["time_solve"], r["residuals"]["max"], "" if r["converged"] else "  NOT CONVERGED: " + r["reason"]))
PY
done
echo
echo "the last run in full:"
grep -v '^{"conefeti":' "$log" | grep -v '^conefeti .*: pipeline'
exit $status
