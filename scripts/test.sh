#!/usr/bin/env bash
# Set up, build and run every test. This is the README's test command and what CI runs.
# Extra arguments go to ctest (e.g. -R qp_ to select tests).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
cd "${BUILD_DIR:-build}"
ctest --output-on-failure -j "$(nproc)" "$@"
