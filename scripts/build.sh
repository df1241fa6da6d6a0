#!/usr/bin/env bash
# Configure and build conefeti (library, programs, tutorials, tests) in ./build.
# Re-running only rebuilds what changed. BUILD_DIR and BUILD_TYPE may be overridden.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
type=${BUILD_TYPE:-Release}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE="$type"
fi
cmake --build "$build" -j "$(nproc)"
