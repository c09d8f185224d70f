#!/usr/bin/env bash
# Instructions per step of the splitting methods on SciML's Hénon–Heiles case and the
# 1000-pendulum swarm (benchmarks/README.md). Counts are callgrind's
# (load-independent): (I(2N steps) - I(N steps)) / N, so set-up and process start cancel.
#
#   bash benchmarks/step_cost.sh [N] [METHOD...]   (N defaults to 10000; methods default to
#                                                  verlet yoshida4 kahan_li8)
#
# The swarm runs N/10 steps (a step is ~500x a Hénon–Heiles step). Uses $CARGO_TARGET_DIR
# (default ./target).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-10000}
shift || true
methods=("$@")
if [ ${#methods[@]} -eq 0 ]; then
    methods=(verlet yoshida4 kahan_li8)
fi
target=${CARGO_TARGET_DIR:-target}
cargo build --quiet --release -p physicskit-benchmarks --bin step_cost
# shellcheck source=benchmarks/instructions.sh
source benchmarks/instructions.sh
per_step() {
    local steps=$1 a b
    shift
    a=$(instructions "$target/release/step_cost" "$@" "$steps")
    b=$(instructions "$target/release/step_cost" "$@" $((2 * steps)))
    awk -v a="$a" -v b="$b" -v n="$steps" 'BEGIN { printf "%.1f", (b - a) / n }'
}
printf '| %-12s | %-20s | %18s |\n' case method instructions/step
printf '|%s|%s|%s|\n' "--------------" "----------------------" "-------------------:"
for m in "${methods[@]}"; do
    printf '| %-12s | %-20s | %18s |\n' henon-heiles "$m" "$(per_step "$n" henon-heiles "$m")"
    printf '| %-12s | %-20s | %18s |\n' swarm-1000 "$m" "$(per_step $((n / 10)) swarm-1000 "$m")"
done
