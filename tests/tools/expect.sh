#!/usr/bin/env bash
# usage: expect.sh [--status N] [--expect REGEX]... [--reject REGEX]... -- command...
# Runs the command, prints its output, and fails when it exits with another status than N (default 0), when an --expect
# extended regex matches no line, or when a --reject regex matches some line.
set -uo pipefail
expects=(); rejects=(); status=0
while [ $# -gt 0 ]; do
  case "$1" in
    --status) status=$2; shift 2 ;;
    --expect) expects+=("$2"); shift 2 ;;
    --reject) rejects+=("$2"); shift 2 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
out=$(mktemp); trap 'rm -f "$out"' EXIT
"$@" >"$out" 2>&1; rc=$?
cat "$out"
fail=0
if [ $rc -ne "$status" ]; then echo "expect.sh: command exited with $rc, expected $status"; fail=1; fi
for e in ${expects[@]+"${expects[@]}"}; do
  grep -Eq -- "$e" "$out" || { echo "expect.sh: no line matches: $e"; fail=1; }
done
for r in ${rejects[@]+"${rejects[@]}"}; do
  grep -Eq -- "$r" "$out" && { echo "expect.sh: a line matches rejected: $r"; fail=1; }
done
exit $fail
