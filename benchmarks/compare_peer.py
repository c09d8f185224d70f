"""Runs every peer workload (peer/workloads.json) through physicskit and through the Numba peer
and prints a table.

    bash benchmarks/compare_peer.sh          # sets up both environments, then runs this
    bash benchmarks/compare_peer.sh --baseline /path/to/venv/bin/python   # ours before/after

Each case runs in a fresh process per implementation, ours and the peer's back to back, so each
ratio is taken in the same minute of a shared, noisy machine. Per-step figures are the best of
`--repeats` runs of `--steps` steps after a warm-up call (which is where the peer's Numba JIT
compiles); the first-call column is a fresh process doing import + construct + 1e3 steps.
`--baseline` names the python of a second build of ours (an earlier commit, in its own venv):
each case then also runs there, right after ours, and the table gains its ns/step and
ours/baseline (time after / time before; the geometric mean over the cases at the end);
`--peer none` then leaves the peer out (its Numba compilation costs minutes per case on a
loaded machine).
Standard library only: it runs under any python3.
"""

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
SCRIPT = HERE / "peer" / "workloads.py"


def call(python, *args):
    out = subprocess.run(
        [python, str(SCRIPT), *map(str, args)], check=True, capture_output=True, text=True
    )
    return out.stdout.strip().splitlines()[-1]


def parse_args(baseline=False):
    """The options shared with same_accuracy.py (`--baseline`: this script's only)."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--ours", required=True, help="python of the physicskit venv")
    peer_help = "python of the peer venv" + (" (or `none`)" if baseline else "")
    parser.add_argument("--peer", required=True, help=peer_help)
    parser.add_argument("--steps", type=int, default=100_000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cases", nargs="*")
    parser.add_argument("--json", help="also write the rows here")
    if baseline:
        parser.add_argument("--baseline", help="python of a venv with another build of ours")
    return parser.parse_args()


def main():
    args = parse_args(baseline=True)
    if args.peer == "none" and not args.baseline:
        sys.exit("--peer none needs --baseline: there would be nothing to compare")
    peer_too = args.peer != "none"

    cases = args.cases or call(args.ours, "list").split()
    header = f"{'case':<21}{'ours ns/step':>13}"
    if args.baseline:
        header += f"{'base ns/step':>13}{'ours/base':>10}"
    if peer_too:
        header += (
            f"{'peer ns/step':>13}{'ratio':>8}"
            f"{'ours 1st s':>11}{'peer 1st s':>11}{'ours drift':>12}{'peer drift':>12}"
        )
    print(header)
    rows = []
    for case in cases:
        ours = json.loads(call(args.ours, "run", case, args.steps, args.repeats))
        row = dict(case=case, ours_ns=ours["ns_per_step"], ours_drift=ours["drift"])
        line = f"{case:<21}{row['ours_ns']:>13.1f}"
        if args.baseline:
            base = json.loads(call(args.baseline, "run", case, args.steps, args.repeats))
            row.update(base_ns=base["ns_per_step"], base_drift=base["drift"],
                       ours_over_base=ours["ns_per_step"] / base["ns_per_step"])
            line += f"{row['base_ns']:>13.1f}{row['ours_over_base']:>10.3f}"
        if peer_too:
            peer = json.loads(call(args.peer, "run", case, args.steps, args.repeats))
            ours_first = json.loads(call(args.ours, "first", case))["first_call_s"]
            peer_first = json.loads(call(args.peer, "first", case))["first_call_s"]
            row.update(
                peer_ns=peer["ns_per_step"],
                ratio=peer["ns_per_step"] / ours["ns_per_step"],
                ours_first_s=ours_first,
                peer_first_s=peer_first,
                peer_drift=peer["drift"],
            )
            line += (
                f"{row['peer_ns']:>13.1f}{row['ratio']:>8.1f}"
                f"{ours_first:>11.3f}{peer_first:>11.2f}{row['ours_drift']:>12.2e}"
                f"{row['peer_drift']:>12.2e}"
            )
        rows.append(row)
        print(line, flush=True)
    if peer_too:
        geomean = math.exp(sum(math.log(r["ratio"]) for r in rows) / len(rows))
        print(f"geometric mean speed-up: {geomean:.1f}x; slowest case: "
              f"{min(rows, key=lambda r: r['ratio'])['case']} "
              f"({min(r['ratio'] for r in rows):.1f}x)")
    if args.baseline:
        change = math.exp(sum(math.log(r["ours_over_base"]) for r in rows) / len(rows))
        worst = max(rows, key=lambda r: r["ours_over_base"])
        print(f"geometric mean ours/baseline (time, < 1 is faster): {change:.3f}; "
              f"largest: {worst['case']} ({worst['ours_over_base']:.3f})")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    sys.exit(main())
