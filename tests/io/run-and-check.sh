#!/usr/bin/env bash
# usage: run-and-check.sh BASENAME [--exit N] [check-output.py options] -- command...
# Removes BASENAME.{h5,xmf,json}, runs the command (a conefeti run that must be given
# -output BASENAME -summary_json BASENAME.json), then checks the files with check-output.py.
# The run must exit with 0, or with N when given (2: not converged, output written on request).
set -uo pipefail
base=$1; shift
want=0
if [ "${1:-}" = "--exit" ]; then want=$2; shift 2; fi
checks=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do checks+=("$1"); shift; done
shift
rm -f "$base.h5" "$base.xmf" "$base.json" "$base.h5.tmp" "$base.xmf.tmp"
"$@" 2>&1 | grep -v "Configure options"
rc=${PIPESTATUS[0]}
if [ "$rc" -ne "$want" ]; then echo "run-and-check.sh: the run exited with $rc, expected $want"; exit 1; fi
exec "$(dirname "$0")/check-output.py" "$base" --json "$base.json" ${checks[@]+"${checks[@]}"}
