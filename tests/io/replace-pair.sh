#!/usr/bin/env bash
# usage: replace-pair.sh BASENAME -- conefeti-command...
# The .h5 and .xmf are replaced together or not at all: with a directory in the place of BASENAME.xmf
# the run must fail naming it (since the driver checks its output paths before the solve, there; the library's
# write still refuses it), and create no BASENAME.h5, no temporary and no .old file; once the
# directory is gone a run writes both files and a rerun replaces both, leaving no .old file.
set -uo pipefail
base=$1; shift 2
rm -rf "$base".h5 "$base".xmf "$base".h5.tmp "$base".xmf.tmp "$base".h5.old "$base".xmf.old
mkdir -p "$base.xmf"
out=$("$@" -output "$base" 2>&1); rc=$?
fail=0
[ $rc -ne 0 ] || { echo "replace-pair.sh: the run exited with 0 although $base.xmf is a directory"; fail=1; }
echo "$out" | grep -Eq -- "-output: cannot (replace $base.xmf: Is a directory|write $base.xmf: Is a directory \(checked before the solve\))" || { echo "replace-pair.sh: no message naming $base.xmf; the run printed:"; echo "$out" | tail -5; fail=1; }
for f in "$base.h5" "$base.h5.tmp" "$base.xmf.tmp" "$base.h5.old"; do [ -e "$f" ] && { echo "replace-pair.sh: $f left behind"; fail=1; }; done
rmdir "$base.xmf"
out=$("$@" -output "$base" 2>&1) || { echo "replace-pair.sh: the first write failed:"; echo "$out" | tail -5; fail=1; }
out=$("$@" -output "$base" -scene_name second 2>&1) || { echo "replace-pair.sh: the second write failed:"; echo "$out" | tail -5; fail=1; }
grep -q 'scene "second"' "$base.xmf" || { echo "replace-pair.sh: the second run did not replace $base.xmf"; fail=1; }
for f in "$base.h5.old" "$base.xmf.old"; do [ -e "$f" ] && { echo "replace-pair.sh: $f left behind"; fail=1; }; done
[ $fail -eq 0 ] && echo "replace-pair.sh: the pair was replaced together or not at all"
exit $fail
