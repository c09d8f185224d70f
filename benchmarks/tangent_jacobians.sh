#!/usr/bin/env bash
# Instructions per Jacobian and per max_lyapunov step of the double pendulum: automatic
# differentiation of the closed forms against central differences and against the second
# derivatives of L (`src/bin/tangent_jacobians.rs`). Counts are callgrind's
# (load-independent): (I(2N) - I(N)) / N, so set-up and process start cancel.
#
#   bash benchmarks/tangent_jacobians.sh [N] [CASE...]      (N defaults to 10000)
#
# Uses $CARGO_TARGET_DIR (default ./target).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-10000}
shift || true
target=${CARGO_TARGET_DIR:-target}
cargo build --quiet --release -p physicskit-benchmarks --bin tangent_jacobians
bin="$target/release/tangent_jacobians"
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
    mapfile -t cases < <("$bin" list)
fi
# shellcheck source=benchmarks/instructions.sh
source benchmarks/instructions.sh
printf '| %-22s | %12s |\n' case "instr./rep."
printf '|%s|%s|\n' "------------------------" "-------------:"
for c in "${cases[@]}"; do
    a=$(instructions "$bin" "$c" "$n")
    b=$(instructions "$bin" "$c" $((2 * n)))
    printf '| %-22s | %12s |\n' "$c" $(((b - a) / n))
done
