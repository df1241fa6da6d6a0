#!/usr/bin/env bash
# usage: brick-variants.sh DIR
# The brick variants (F = 0.1, frictionless, Tresca) must be the brick scene of brick.opts with only the
# scene name and the contact law changed: when brick.opts is retuned (tractions, gap, mesh), the variants
# must follow. Comments and blank lines are ignored.
set -uo pipefail
dir=$1
strip() { sed -e 's/#.*//' -e 's/[[:space:]]*$//' -e '/^$/d' "$1" | grep -vE '^-scene_name |^-scene_zone0_(law|friction|slip_bound) '; }
fail=0
for v in brick-f01 brick-frictionless brick-tresca; do
  if ! diff <(strip "$dir/brick.opts") <(strip "$dir/$v.opts"); then
    echo "brick-variants.sh: $v.opts differs from brick.opts beyond the scene name and the law"; fail=1
  else echo "brick-variants.sh: $v.opts = brick.opts up to the name and the law"; fi
done
exit $fail
