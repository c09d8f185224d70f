#!/usr/bin/env bash
# Instructions per step of Lagrangians that go through the automatic-differentiation engine,
# with the engine's kernels on the hand-written array duals (default build) and on num-dual's
# vector duals (`--features num-dual-kernels`). Counts are callgrind's (load-independent):
# (I(2N steps) - I(N steps)) / N, so set-up and process start cancel.
#
#   bash benchmarks/lagrangian_ad.sh [N] [CASE...]      (N defaults to 10000)
#
# Uses $CARGO_TARGET_DIR (default ./target); leaves the two binaries in it as
# lagrangian_ad-custom and lagrangian_ad-num-dual.
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-10000}
shift || true
target=${CARGO_TARGET_DIR:-target}
build() {
    cargo build --quiet --release -p physicskit-benchmarks --bin lagrangian_ad "$@"
}
build
cp "$target/release/lagrangian_ad" "$target/release/lagrangian_ad-custom"
build --features num-dual-kernels
cp "$target/release/lagrangian_ad" "$target/release/lagrangian_ad-num-dual"
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
    mapfile -t cases < <("$target/release/lagrangian_ad-custom" list)
fi
# shellcheck source=benchmarks/instructions.sh
source benchmarks/instructions.sh
per_step() {
    local a b
    a=$(instructions "$@" "$n")
    b=$(instructions "$@" $((2 * n)))
    echo $(((b - a) / n))
}
printf '| %-22s | %-17s | %12s | %12s | %7s |\n' case method custom num-dual saving
printf '|%s|%s|%s|%s|%s|\n' "------------------------" "-------------------" "-------------:" "-------------:" "--------:"
for c in "${cases[@]}"; do
    for m in implicit_midpoint rk4; do
        custom=$(per_step "$target/release/lagrangian_ad-custom" "$c" "$m")
        numdual=$(per_step "$target/release/lagrangian_ad-num-dual" "$c" "$m")
        saving=$(awk -v a="$custom" -v b="$numdual" 'BEGIN { printf "%.0f%%", 100 * (b - a) / b }')
        printf '| %-22s | %-17s | %12s | %12s | %7s |\n' "$c" "$m" "$custom" "$numdual" "$saving"
    done
done
