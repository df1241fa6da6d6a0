#!/usr/bin/env bash
# The README's main command: set up (Debian packages), build, then solve the seed paper's brick
# (petsc-options/brick.opts, Coulomb friction) at a few of the paper's sizes with the conefeti program
# and print one table in the layout of the paper's Tables 1-2, followed by the full summary of the
# largest run. Under a minute on 2 cores once built (the first build takes about two minutes more).
#
# Environment: SIZES (default "4 6 8": -scene_refine values, n = 900, 2646, 5832; "4 6 8 10 12" adds
#              the paper's 10890 and 18252),
#              SCENE (default petsc-options/brick.opts), RANKS (default 1), BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh >/dev/null
build=${BUILD_DIR:-build}
scene=${SCENE:-petsc-options/brick.opts}
ranks=${RANKS:-1}
run=("$build/conefeti")
if [ "$ranks" -gt 1 ]; then run=(mpiexec --allow-run-as-root --oversubscribe -n "$ranks" "$build/conefeti"); fi
py=/usr/bin/python3
json=$(mktemp); log=$(mktemp); trap 'rm -f "$json" "$log"' EXIT
echo "scene: $scene (conefeti -options_file $scene -scene_refine K)"
status=0
for k in ${SIZES:-4 6 8}; do
  rc=0
  "${run[@]}" -options_file "$scene" -scene_refine "$k" >"$log" 2>&1 || rc=$?
  if ! grep -q '^{"conefeti":' "$log"; then cat "$log"; echo "main.sh: the run with -scene_refine $k failed (exit $rc)"; exit 1; fi
  grep '^{"conefeti":' "$log" >>"$json"
  [ $rc -eq 0 ] || status=$rc
done
grep -m1 '^conefeti .*: pipeline' "$log"
$py - "$json" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
print("%8s %6s %6s %6s %6s %6s %6s %6s %6s %6s %9s %9s  %s" % ("n", "m", "Iter", "n_A", "QPP", "QPQ", "other", "sep", "stick", "slip", "setup[s]", "solve[s]", "residual"))
for r in rows:
    print("%8d %6d %6d %6d %6d %6d %6d %6d %6d %6d %9.3f %9.3f  %.1e%s" % (r["n"], r["m"], r["iter"], r["n_A"], r["n_A_qpp"], r["n_A_qpq"], r["n_A_other"],
          r["separated"], r["stick"], r["slip"], r["time_setup"], r["time_solve"], r["residuals"]["max"], "" if r["converged"] else "  NOT CONVERGED: " + r["reason"]))
PY
echo
echo "the largest run in full:"
grep -v '^{"conefeti":' "$log" | grep -v '^conefeti .*: pipeline'
exit $status
