"""Time to the same accuracy: for each issue-7 workload, the peer's time to its own energy error
against the fastest of our fixed-step methods that reaches that error (issue 13, benchmark c).

    bash benchmarks/compare_peer.sh --same-accuracy [--steps N] [--repeats R] [--cases ...]

The peer runs its workload (its method and step, `--steps` steps, best of `--repeats` after a
warm-up call that compiles it) and reports its max relative energy error E. Ours then tries
every fixed-step method the system accepts on the same span, halving the number of steps from
the workload's while the max relative energy error stays <= E and the final state is no farther
from a reference run (dop853 at rtol 1e-13) than the peer's final state is (relative, max norm,
floored at 1e-11), and times the coarsest passing run (best of `--repeats`). Energy alone is
what the workloads define, but it would crown one huge step of the implicit midpoint rule on a
linear system (its quadratic energy is kept exactly at any step); the final-state condition
keeps the trajectory honest too. Standard library only, like compare_peer.py.
"""

import json
import math
import sys

from compare_peer import call, parse_args


def main():
    args = parse_args()
    cases = args.cases or call(args.ours, "list").split()
    print(f"{'case':<21}{'peer ms':>9}{'peer dE':>10}{'peer err':>10}{'our best':>22}"
          f"{'steps':>8}{'ms':>9}{'dE':>10}{'err':>10}{'ratio':>8}")
    rows = []
    for case in cases:
        peer = json.loads(call(args.peer, "run", case, args.steps, args.repeats))
        peer_s = peer["ns_per_step"] * args.steps * 1e-9
        peer_final = call(args.peer, "final", case, args.steps)
        tried = json.loads(
            call(args.ours, "same", case, args.steps, args.repeats, peer["drift"], peer_final)
        )
        peer_error = tried.pop(0)["final_error"]
        passing = [r for r in tried if r["seconds"] is not None]
        best = min(passing, key=lambda r: r["seconds"])
        row = dict(case=case, peer_s=peer_s, peer_drift=peer["drift"], peer_error=peer_error,
                   best=best, tried=tried, ratio=peer_s / best["seconds"])
        rows.append(row)
        print(f"{case:<21}{peer_s * 1e3:>9.1f}{peer['drift']:>10.1e}{peer_error:>10.1e}"
              f"{best['method']:>22}{best['steps']:>8}{best['seconds'] * 1e3:>9.2f}"
              f"{best['drift']:>10.1e}{best['final_error']:>10.1e}{row['ratio']:>8.0f}",
              flush=True)
    geomean = math.exp(sum(math.log(r["ratio"]) for r in rows) / len(rows))
    print(f"geometric mean: {geomean:.0f}x less time to the peer's own accuracy (energy and final state)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
