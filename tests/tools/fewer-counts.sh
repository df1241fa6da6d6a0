#!/usr/bin/env bash
# usage: fewer-counts.sh FIELD... -- COMMAND_A -- COMMAND_B
# Runs both commands (each prints its counts as FIELD=<int> or "FIELD <int>" on some line) and
# fails unless every FIELD of A is strictly smaller than B's. Prints both values per field.
set -uo pipefail
fields=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do fields+=("$1"); shift; done
shift
a=(); while [ $# -gt 0 ] && [ "$1" != "--" ]; do a+=("$1"); shift; done
shift
b=("$@")
outa=$("${a[@]}" 2>&1) || { echo "$outa"; echo "fewer-counts.sh: command A failed"; exit 1; }
outb=$("${b[@]}" 2>&1) || { echo "$outb"; echo "fewer-counts.sh: command B failed"; exit 1; }
value() { grep -oE "(^|[ {\"])$1[=\": ]+[0-9]+" <<<"$2" | head -1 | grep -oE '[0-9]+$'; }
fail=0
for f in "${fields[@]}"; do
  va=$(value "$f" "$outa"); vb=$(value "$f" "$outb")
  if [ -z "$va" ] || [ -z "$vb" ]; then echo "fewer-counts.sh: no value of $f (A: '$va', B: '$vb')"; fail=1; continue; fi
  echo "$f: A $va, B $vb"
  [ "$va" -lt "$vb" ] || { echo "fewer-counts.sh: $f of A is not smaller"; fail=1; }
done
exit $fail
