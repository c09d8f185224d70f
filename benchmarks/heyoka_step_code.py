"""What heyoka's compiled step is made of: its instruction mix, for the comparison's workloads.

Run in heyoka's venv (``benchmarks/heyoka_compare.sh`` makes it), from the repository root:

    /tmp/heyoka-venv/bin/python benchmarks/heyoka_step_code.py

For each workload of ``heyoka_compare.py`` (the same equations: ``systems()`` is imported from
it) and each tolerance, builds heyoka's ``taylor_adaptive`` as the comparison does, takes the
object code LLVM made for it (``llvm_state.object_code``), disassembles its ``step`` function
with ``objdump`` and counts the instructions: all of them, the floating-point ones by kind
(fused multiply-adds, multiplications, additions and subtractions, divisions), and the calls
(``pow`` of the step-size rule). It also says whether heyoka let LLVM contract a
multiplication and an addition into one fused multiply-add (the ``contract`` flag on the
operations of its IR). Its times per step come from ``heyoka_compare.sh``'s table (heyoka's
time over its step count, which equals ours at the same tolerance); our instruction counts from
callgrind (``benchmarks/README.md``).
"""

import collections
import os
import re
import subprocess
import sys
import tempfile

import heyoka as hy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from heyoka_compare import systems  # noqa: E402  (the same equations as the comparison)

TOLERANCES = [1e-6, 1e-10, 1e-14, 1e-16]

KINDS = {
    "fma": re.compile(r"^vf(n?)m(add|sub)\d+[sp]d$"),
    "mul": re.compile(r"^v?mul[sp]d$"),
    "add/sub": re.compile(r"^v?(add|sub)[sp]d$"),
    "div": re.compile(r"^v?div[sp]d$"),
    "call": re.compile(r"^call"),
}


def step_mnemonics(object_code):
    """The mnemonics of the ``step`` function in ``object_code``, in order."""
    with tempfile.NamedTemporaryFile(suffix=".o") as f:
        f.write(object_code)
        f.flush()
        listing = subprocess.run(
            ["objdump", "-d", "--no-show-raw-insn", f.name],
            check=True, capture_output=True, text=True).stdout
    mnemonics, inside = [], False
    for line in listing.splitlines():
        if re.match(r"^[0-9a-f]+ <", line):
            inside = line.rstrip().endswith("<step>:")
            continue
        parts = line.split("\t")
        if inside and len(parts) >= 2 and parts[1].strip():
            mnemonics.append(parts[1].split()[0])
    return mnemonics


def main():
    print(f"heyoka {hy.__version__}")
    print("| workload | tol | order | step instructions | fma | mul | add/sub | div | calls "
          "| IR ops contractible |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---|")
    seen = set()
    for name, (sys_, y0, _) in systems().items():
        if id(sys_) in seen:  # hh-energy: hh-state's equations, the same code
            continue
        seen.add(id(sys_))
        for tol in TOLERANCES:
            ta = hy.taylor_adaptive(sys_, y0, tol=tol)
            state = ta.llvm_state
            ops = step_mnemonics(state.object_code)
            counts = collections.Counter()
            for m in ops:
                for kind, pattern in KINDS.items():
                    if pattern.match(m):
                        counts[kind] += 1
            contract = "yes" if re.search(r"\bcontract\b", state.ir) else "no"
            print(f"| {name} | {tol:.0e} | {ta.order} | {len(ops)} | {counts['fma']} | "
                  f"{counts['mul']} | {counts['add/sub']} | {counts['div']} | "
                  f"{counts['call']} | {contract} |")


if __name__ == "__main__":
    main()
