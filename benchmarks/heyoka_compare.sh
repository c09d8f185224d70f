#!/usr/bin/env bash
# Time to accuracy against heyoka (benchmarks/heyoka_compare.py): makes heyoka's venv under
# /tmp from PyPI (once), builds our side (the heyoka_taylor binary, and heyoka_batch for the
# batch workload: 1000 Hénon–Heiles orbits against heyoka's batch mode) in release and runs
# both. Time it on an idle machine: both sides are timed in rounds, the least over the rounds
# counting (heyoka_compare.py says how many and why; HEYOKA_ROUNDS=N sets them).
#   bash benchmarks/heyoka_compare.sh           every workload, then the batch
#   bash benchmarks/heyoka_compare.sh --batch   the batch workload alone
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${HEYOKA_VENV:-/tmp/heyoka-venv}
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import heyoka' 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q heyoka numpy
fi
rounds=()
if [ -n "${HEYOKA_ROUNDS:-}" ]; then
    rounds=(--rounds "$HEYOKA_ROUNDS")
fi
if [ "${1:-}" = "--batch" ]; then
    cargo build --release -p physicskit-benchmarks --bin heyoka_batch
    "$venv/bin/python" benchmarks/heyoka_compare.py "${rounds[@]}" --batch-only \
        target/release/heyoka_batch
else
    cargo build --release -p physicskit-benchmarks --bin heyoka_taylor --bin heyoka_batch
    "$venv/bin/python" benchmarks/heyoka_compare.py "${rounds[@]}" target/release/heyoka_taylor \
        target/release/heyoka_batch
fi
