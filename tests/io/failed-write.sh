#!/usr/bin/env bash
# usage: failed-write.sh BASENAME -- conefeti-command...
# The output is written atomically: a first run writes BASENAME.{h5,xmf}; a second run that fails while
# writing (-output_test_failure: after the temporary files are complete, before the rename) must end
# with an error, leave the first run's files byte for byte, and leave no temporary file.
set -uo pipefail
base=$1; shift 2
rm -f "$base".h5 "$base".xmf "$base".h5.tmp "$base".xmf.tmp
"$@" -output "$base" >/dev/null 2>&1 || { echo "failed-write.sh: the first run failed"; exit 1; }
before=$(md5sum "$base.h5" "$base.xmf") || { echo "failed-write.sh: the first run wrote no output"; exit 1; }
out=$("$@" -output "$base" -output_test_failure 2>&1); rc=$?
echo "$out" | grep -E "error: .*output_test_failure" | head -3
fail=0
[ $rc -ne 0 ] || { echo "failed-write.sh: the failing run exited with 0"; fail=1; }
echo "$out" | grep -q "failing on purpose after writing" || { echo "failed-write.sh: no message about the failed write"; fail=1; }
[ "$(md5sum "$base.h5" "$base.xmf")" = "$before" ] || { echo "failed-write.sh: the previous output changed"; fail=1; }
for f in "$base.h5.tmp" "$base.xmf.tmp"; do [ -e "$f" ] && { echo "failed-write.sh: $f left behind"; fail=1; }; done
[ $fail -eq 0 ] && echo "failed-write.sh: the failed write left the previous output intact and no temporary file"
exit $fail
