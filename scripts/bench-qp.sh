#!/usr/bin/env bash
# QP benchmark (docs/qp-benchmark.md): builds the tutorials and runs scripts/bench-qp.py
# with numpy-free system Python. Arguments go to bench-qp.py (--quick, --problems, --sizes, --rtol, --out).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
exec /usr/bin/python3 scripts/bench-qp.py "$@"
