#!/usr/bin/env bash
# Compares physicskit with the Numba peer (physicskit 0.4.0 from PyPI) on its canonical workloads.
#
#   bash benchmarks/compare_peer.sh [--steps N] [--repeats R] [--cases A B ...]
#   bash benchmarks/compare_peer.sh --same-accuracy [...]   # time to the peer's own accuracy
#   bash benchmarks/compare_peer.sh --baseline PYTHON [...]  # also ours at another commit
#       (PYTHON: a venv's python holding that commit's release build; see benchmarks/README.md,
#       "Before and after")
#
# Builds our package into <repo>/.venv (python/dev.sh env) and installs the peer into
# benchmarks/.venv-peer (git-ignored): the two packages share the name `physicskit`, so each
# lives in its own environment.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
bash "$repo/python/dev.sh" env >/dev/null
peer="$here/.venv-peer"
if [ ! -x "$peer/bin/python" ]; then
    python3 -m venv "$peer"
    "$peer/bin/python" -m pip install --quiet --disable-pip-version-check "physicskit==0.4.0"
fi
script="$here/compare_peer.py"
if [ "${1:-}" = "--same-accuracy" ]; then
    script="$here/same_accuracy.py"
    shift
fi
exec python3 "$script" --ours "$repo/.venv/bin/python" --peer "$peer/bin/python" "$@"
