#!/usr/bin/env bash
# Check (or with --fix, apply) clang-format on our C/C++ sources. Exit 1 lists unformatted files.
set -euo pipefail
cd "$(dirname "$0")/.."
# tracked files and new ones not yet added (a new test file is formatted before its first commit), not ignored ones
mapfile -t files < <(git ls-files --cached --others --exclude-standard '*.c' '*.cxx' '*.h' '*.hpp' 2>/dev/null || find src include tests tutorials -name '*.c' -o -name '*.cxx' -o -name '*.h')
[ ${#files[@]} -eq 0 ] && exit 0
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "not clang-formatted (run scripts/check-format.sh --fix):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "clang-format: ${#files[@]} files ok"
