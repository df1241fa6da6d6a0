#!/usr/bin/env bash
# usage: short-error.sh MAXLINES REGEX -- command...
# An error of the conefeti program is its message and a line of hint, not PETSc's report of some 55
# lines: the command must exit with a status other than 0 and 2 (2 = not converged), print at most
# MAXLINES lines besides the notes of Open MPI's launcher (blocks between lines of dashes, which mpiexec
# adds for any non-zero exit), and print the message, matching the extended REGEX, exactly once (one
# rank reports it), without PETSc's banner or traceback.
set -uo pipefail
max=$1; regex=$2; shift 3
out=$(mktemp); trap 'rm -f "$out"' EXIT
"$@" >"$out" 2>&1; rc=$?
own=$(awk '/^--------------------+$/ { inside = !inside; next } !inside' "$out")
echo "$own"
fail=0
if [ $rc -eq 0 ] || [ $rc -eq 2 ]; then echo "short-error.sh: exit status $rc, expected an error (not 0, not 2)"; fail=1; fi
lines=$(printf '%s\n' "$own" | grep -c .)
[ "$lines" -le "$max" ] || { echo "short-error.sh: $lines lines, expected at most $max"; fail=1; }
count=$(printf '%s\n' "$own" | grep -Ec -- "$regex")
[ "$count" -eq 1 ] || { echo "short-error.sh: the message matching '$regex' is printed $count times, expected once"; fail=1; }
printf '%s\n' "$own" | grep -Eq "PETSC ERROR|Configure options|MPI_ABORT" && { echo "short-error.sh: PETSc's report or an MPI_ABORT is printed"; fail=1; }
[ $fail -eq 0 ] && echo "short-error.sh: $lines line(s), the message once, exit status $rc"
exit $fail
