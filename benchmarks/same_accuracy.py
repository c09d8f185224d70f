"""Time to the same accuracy: for each issue-7 workload, the peer's time to its own energy error
against the fastest of our fixed-step methods that reaches that error (issue 13, benchmark c).

    bash benchmarks/compare_peer.sh --same-accuracy [--steps N] [--repeats R] [--cases ...]

The peer runs its workload (its method and step, `--steps` steps, best of `--repeats` after a
warm-up call that compiles it) and reports its max relative energy error E. Ours then tries
every fixed-step method the system accepts on the same span, halving the number of steps from
the workload's while the max relative energy error stays <= E, and times the coarsest passing
run (best of `--repeats`). Energy error is the accuracy measure because it is the one the
workloads define; for the chaotic double pendulum it says nothing about the phase, which the
work-precision page measures instead. Standard library only, like compare_peer.py.
"""

import json
import math
import sys

from compare_peer import call, parse_args


def main():
    args = parse_args()
    cases = args.cases or call(args.ours, "list").split()
    print(f"{'case':<21}{'peer ms':>9}{'peer dE':>10}{'our best':>22}{'steps':>8}{'ms':>9}"
          f"{'dE':>10}{'ratio':>8}")
    rows = []
    for case in cases:
        peer = json.loads(call(args.peer, "run", case, args.steps, args.repeats))
        peer_s = peer["ns_per_step"] * args.steps * 1e-9
        tried = json.loads(call(args.ours, "same", case, args.steps, args.repeats, peer["drift"]))
        passing = [r for r in tried if r["seconds"] is not None]
        best = min(passing, key=lambda r: r["seconds"])
        row = dict(case=case, peer_s=peer_s, peer_drift=peer["drift"], best=best, tried=tried,
                   ratio=peer_s / best["seconds"])
        rows.append(row)
        print(f"{case:<21}{peer_s * 1e3:>9.1f}{peer['drift']:>10.1e}{best['method']:>22}"
              f"{best['steps']:>8}{best['seconds'] * 1e3:>9.2f}{best['drift']:>10.1e}"
              f"{row['ratio']:>8.0f}", flush=True)
    geomean = math.exp(sum(math.log(r["ratio"]) for r in rows) / len(rows))
    print(f"geometric mean: {geomean:.0f}x less time to the peer's own energy error")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
