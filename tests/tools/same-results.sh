#!/usr/bin/env bash
# usage: same-results.sh [--strip REGEX] [--count-rtol R] -- 'command 1' 'command 2' ...
# Runs each command (through bash), keeps the lines that start with RESULT, removes the parts
# matching --strip (e.g. the scale that differs on purpose), and fails unless all commands
# succeed and print the same RESULT lines. With --count-rtol R, integer fields (key=123) may differ
# from the first command's by a relative R (for solvers whose path through curved boundaries
# depends on rounding-level tie breaks; small fields get an extra slack of 3); everything else must
# match exactly.
# Used for: same counts on 1, 2, 3 ranks; same counts when A and b are scaled by 1e-12 or 1e+12.
set -uo pipefail
strip='$^'; rtol=""
while [ $# -gt 0 ]; do
  case "$1" in
    --strip) strip=$2; shift 2 ;;
    --count-rtol) rtol=$2; shift 2 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
ref=""; first=1; fail=0
close() { # close REF_LINES NEW_LINES: same text, integer fields within rtol
  local a b; a=$(echo "$1" | sed -E 's/=[0-9]+/=N/g'); b=$(echo "$2" | sed -E 's/=[0-9]+/=N/g')
  [ "$a" = "$b" ] || return 1
  paste <(echo "$1" | grep -oE '=[0-9]+( |$)' | tr -d '= ') <(echo "$2" | grep -oE '=[0-9]+( |$)' | tr -d '= ') |
    awk -v r="$rtol" '{d=$1-$2; if (d<0) d=-d; m=($1>$2)?$1:$2; if (d > r*m + 3) bad=1} END {exit bad}'
}
for cmd in "$@"; do
  out=$(bash -c "$cmd" 2>&1); rc=$?
  echo "### $cmd"; echo "$out" | grep -E '^RESULT|rror' | head -20
  if [ $rc -ne 0 ]; then echo "same-results.sh: exit $rc"; fail=1; continue; fi
  res=$(echo "$out" | grep -E '^RESULT' | sed -E "s/$strip//g")
  if [ -z "$res" ]; then echo "same-results.sh: no RESULT line"; fail=1; continue; fi
  if [ $first -eq 1 ]; then ref=$res; first=0; continue; fi
  if [ "$res" = "$ref" ]; then continue; fi
  if [ -n "$rtol" ] && close "$ref" "$res"; then echo "same-results.sh: counts within a relative $rtol of the first command's"; continue; fi
  echo "same-results.sh: RESULT differs from the first command's:"; diff <(echo "$ref") <(echo "$res"); fail=1
done
exit $fail
