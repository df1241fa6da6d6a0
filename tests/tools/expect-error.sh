#!/usr/bin/env bash
# usage: expect-error.sh [--nan-input] REGEX [NOFILE...] -- command...
# Bad input must end the run with an error: the command must exit non-zero, its output must match the
# extended REGEX (the message naming the option, file or value), and must not show a crash (a signal,
# a segmentation violation) or a NaN -- and every NOFILE path must not exist afterwards.
# --nan-input: the bad value is itself a NaN, which the message and PETSc's listing of the options
# repeat, so a NaN in the output is expected (a crash still fails).
set -uo pipefail
nan_input=0
if [ "${1:-}" = "--nan-input" ]; then nan_input=1; shift; fi
regex=$1; shift
nofiles=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do nofiles+=("$1"); shift; done
shift
# The two streams are kept apart: under mpiexec they reach us through separate channels, so a line of
# one (the JSON summary, flushed in pieces) can be cut by a line of the other in a merged file; the
# message is looked for in each stream whole.
out=$(mktemp); err=$(mktemp); trap 'rm -f "$out" "$err"' EXIT
"$@" >"$out" 2>"$err"; rc=$?
grep -v "Configure options" "$out"
grep -v "Configure options" "$err"
fail=0
if [ $rc -eq 0 ]; then echo "expect-error.sh: the command succeeded, expected an error"; fail=1; fi
grep -Eq -- "$regex" "$err" || grep -Eq -- "$regex" "$out" || { echo "expect-error.sh: no line matches: $regex"; fail=1; }
crash="Segmentation Violation|Caught signal|SIGSEGV|SIGABRT"
[ $nan_input -eq 0 ] && crash="$crash|\b[Nn]a[Nn]\b"
cat "$out" "$err" | grep -Eq -- "$crash" && { echo "expect-error.sh: a crash or NaN"; fail=1; }
for f in ${nofiles[@]+"${nofiles[@]}"}; do
  if [ -e "$f" ]; then echo "expect-error.sh: $f exists, expected no file"; fail=1; fi
done
[ $fail -eq 0 ] && echo "expect-error.sh: failed as expected with a clear message"
exit $fail
