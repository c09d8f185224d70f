#!/usr/bin/env bash
# Instructions per yoshida4 step of Hénon–Heiles as a built-in system and as an expression
# (`ExprHamiltonian`, the path of a SymPy `HamiltonianEngine`), from callgrind (load-
# independent): (I(2N steps) - I(N steps)) / N, so set-up and process start cancel.
#
#   bash benchmarks/expr_engines.sh [N]      (N defaults to 10000)
#
# Uses $CARGO_TARGET_DIR (default ./target).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-10000}
target=${CARGO_TARGET_DIR:-target}
cargo build --quiet --release -p physicskit-benchmarks --bin expr_engines
bin="$target/release/expr_engines"
# shellcheck source=benchmarks/instructions.sh
source benchmarks/instructions.sh
printf '| %-22s | %12s |\n' case "instr./step"
printf '|%s|%s|\n' "------------------------" "-------------:"
for c in builtin-henon-heiles expr-henon-heiles; do
    a=$(instructions "$bin" "$c" "$n")
    b=$(instructions "$bin" "$c" $((2 * n)))
    printf '| %-22s | %12s |\n' "$c" $(((b - a) / n))
done
