"""Runs every peer workload (peer/workloads.json) through physicskit and through the Numba peer
and prints a table.

    bash benchmarks/compare_peer.sh          # sets up both environments, then runs this

Each case runs in a fresh process per implementation, ours and the peer's back to back, so each
ratio is taken in the same minute of a shared, noisy machine. Per-step figures are the best of
`--repeats` runs of `--steps` steps after a warm-up call (which is where the peer's Numba JIT
compiles); the first-call column is a fresh process doing import + construct + 1e3 steps.
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


def parse_args():
    """The options shared with same_accuracy.py."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--ours", required=True, help="python of the physicskit venv")
    parser.add_argument("--peer", required=True, help="python of the peer venv")
    parser.add_argument("--steps", type=int, default=100_000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cases", nargs="*")
    parser.add_argument("--json", help="also write the rows here")
    return parser.parse_args()


def main():
    args = parse_args()

    cases = args.cases or call(args.ours, "list").split()
    header = (
        f"{'case':<21}{'ours ns/step':>13}{'peer ns/step':>13}{'ratio':>8}"
        f"{'ours 1st s':>11}{'peer 1st s':>11}{'ours drift':>12}{'peer drift':>12}"
    )
    print(header)
    rows = []
    for case in cases:
        ours = json.loads(call(args.ours, "run", case, args.steps, args.repeats))
        peer = json.loads(call(args.peer, "run", case, args.steps, args.repeats))
        ours_first = json.loads(call(args.ours, "first", case))["first_call_s"]
        peer_first = json.loads(call(args.peer, "first", case))["first_call_s"]
        ratio = peer["ns_per_step"] / ours["ns_per_step"]
        row = dict(
            case=case,
            ours_ns=ours["ns_per_step"],
            peer_ns=peer["ns_per_step"],
            ratio=ratio,
            ours_first_s=ours_first,
            peer_first_s=peer_first,
            ours_drift=ours["drift"],
            peer_drift=peer["drift"],
        )
        rows.append(row)
        print(
            f"{case:<21}{row['ours_ns']:>13.1f}{row['peer_ns']:>13.1f}{ratio:>8.1f}"
            f"{ours_first:>11.3f}{peer_first:>11.2f}{row['ours_drift']:>12.2e}"
            f"{row['peer_drift']:>12.2e}",
            flush=True,
        )
    geomean = math.exp(sum(math.log(r["ratio"]) for r in rows) / len(rows))
    print(f"geometric mean speed-up: {geomean:.1f}x; slowest case: "
          f"{min(rows, key=lambda r: r['ratio'])['case']} "
          f"({min(r['ratio'] for r in rows):.1f}x)")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    sys.exit(main())
