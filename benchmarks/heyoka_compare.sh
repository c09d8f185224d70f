#!/usr/bin/env bash
# Time to accuracy against heyoka (benchmarks/heyoka_compare.py): makes heyoka's venv under
# /tmp from PyPI (once), builds our side (the heyoka_taylor binary) in release and runs both.
# Time it on an idle machine: both sides are timed as the best of five.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${HEYOKA_VENV:-/tmp/heyoka-venv}
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import heyoka' 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q heyoka numpy
fi
cargo build --release -p physicskit-benchmarks --bin heyoka_taylor
"$venv/bin/python" benchmarks/heyoka_compare.py target/release/heyoka_taylor
