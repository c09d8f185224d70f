#!/usr/bin/env bash
# Build and test the Python package `physicskit` (python/).
#
#   bash python/dev.sh env    create/refresh <repo>/.venv, install maturin numpy pytest sympy
#                             hypothesis, mypy, scipy (reference integrations in tests), matplotlib,
#                             pillow, nbclient nbformat ipykernel, distributed (Dask, for the
#                             ensemble tests), tqdm (progress bars), build the extension in the
#                             cargo profile PHYSICSKIT_PROFILE (default release) and install it
#                             (editable)
#   bash python/dev.sh test   run pytest on python/tests (warnings are errors)
#   bash python/dev.sh stubs  check the type stubs against the installed modules (mypy's
#                             stubtest; python/stubtest-allowlist.txt lists what it cannot know)
#
# Needs only python3 (>= 3.10, with venv and pip) and cargo. Idempotent.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
venv="${PHYSICSKIT_VENV:-$repo/.venv}"
py="$venv/bin/python"
export CARGO_BUILD_JOBS="${CARGO_BUILD_JOBS:-2}"
# The cargo profile of the extension and of the Rust programs the tests run (the bit-identity
# reference, the CLI): release unless told otherwise. scripts/test sets `ci` (Cargo.toml), in
# which its `cargo test` has just built the workspace, so CI does not compile it a second time
# with LTO; the tests read the same variable.
profile="${PHYSICSKIT_PROFILE:-release}"

need_venv() {
    if [ ! -x "$py" ]; then
        echo "dev.sh: no virtual environment at $venv; run 'bash python/dev.sh env' first" >&2
        exit 1
    fi
}

case "${1:-}" in
env)
    if [ ! -x "$py" ]; then
        python3 -m venv "$venv"
    fi
    "$py" -m pip install --quiet --disable-pip-version-check --upgrade pip
    "$py" -m pip install --quiet --disable-pip-version-check \
        "maturin>=1.7,<2" "numpy>=1.24" "pytest>=7" "sympy>=1.12" "hypothesis>=6.100,<7" \
        "mypy>=1.18,<2" "scipy>=1.10,<2" "distributed>=2024.1"
    # The optional plotting extra (physicskit[plot]), which tests/test_plotting.py exercises.
    "$py" -m pip install --quiet --disable-pip-version-check \
        "matplotlib>=3.7,<4" "pillow>=9.5,<13"
    # The optional progress extra (physicskit[progress]), whose bar tests/test_progress.py draws.
    "$py" -m pip install --quiet --disable-pip-version-check "tqdm>=4.66,<5"
    # What tests/test_notebooks.py runs the example notebooks with.
    "$py" -m pip install --quiet --disable-pip-version-check \
        "nbclient>=0.10,<0.12" "nbformat>=5.9,<6" "ipykernel>=6.29,<8"
    # maturin develop builds the cdylib in $profile and installs the package in the venv
    # (the pure-Python part is linked, so edits under python/physicskit need no rebuild).
    # The grep only trims maturin's chatter; maturin's own exit status decides (a failed build
    # must not leave an older installed build looking current).
    (cd "$here" && VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" \
        "$venv/bin/maturin" develop --profile "$profile" --quiet 2>&1 \
        | { grep -v -E '^(📦|🔗|🐍|⚠️  Warning: You.re building a library without activating)' || true; }
        exit "${PIPESTATUS[0]}")
    # The pure-Rust reference program of tests/test_bit_identity.py, built now so that
    # `test` does not compile.
    (cd "$repo" && cargo build --quiet --profile "$profile" -p physicskit-python \
        --example reference_run && cargo build --quiet --profile "$profile" -p physicskit-cli)
    "$py" -c "import physicskit.classical as pc; print('physicskit', pc.__version__, 'installed in', '$venv ($profile build)')"
    ;;
test)
    need_venv
    shift
    cd "$here"
    "$py" -m pytest -q "$@" tests
    ;;
stubs)
    need_venv
    cd "$here"
    # stubtest imports the module and compares every name, parameter (name, kind, default),
    # class, property and default value with the stub. PyO3 exposes no parameter types at run
    # time, so it cannot compare those: tests/test_stubs.py calls every function with values of
    # the stub's parameter types instead.
    # physicskit.classical has inline types: stubtest type-checks it (mypy) and compares them
    # with the running code too.
    "$py" -m mypy.stubtest --mypy-config-file pyproject.toml \
        --allowlist stubtest-allowlist.txt physicskit._core physicskit.classical
    ;;
*)
    echo "usage: bash python/dev.sh {env|test [pytest args]|stubs}" >&2
    exit 2
    ;;
esac
