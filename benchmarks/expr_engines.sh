#!/usr/bin/env bash
# Instructions per step of Hénon–Heiles (yoshida4) and the Lorenz system (rk4), each as a
# hand-written system and as an expression (`ExprHamiltonian`, `ExprOde`: the paths of a SymPy
# `HamiltonianEngine` and `ODEEngine`) compiled to machine code and interpreted, from
# callgrind (load-independent): (I(2N steps) - I(N steps)) / N, so set-up, process start and
# compilation cancel.
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
printf '| %-30s | %12s | %6s |\n' case "instr./step" ratio
printf '|%s|%s|%s|\n' "--------------------------------" "-------------:" "-------:"
for family in henon-heiles lorenz; do
    base=
    for c in "builtin-$family" "expr-$family" "expr-$family-interpreted"; do
        a=$(instructions "$bin" "$c" "$n")
        b=$(instructions "$bin" "$c" $((2 * n)))
        per=$(((b - a) / n))
        base=${base:-$per}
        printf '| %-30s | %12s | %6s |\n' "$c" "$per" "$(awk "BEGIN {printf \"%.2f\", $per / $base}")"
    done
done
