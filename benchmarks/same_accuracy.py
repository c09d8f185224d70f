"""Time to the same accuracy: for each issue-7 workload, the peer's time to its own energy error
against the fastest of our fixed-step methods that reaches that error (issue 13, benchmark c).

    bash benchmarks/compare_peer.sh --same-accuracy [--steps N] [--repeats R] [--cases ...]

The peer runs its workload (its method and step, `--steps` steps, best of `--repeats` after a
warm-up call that compiles it) and reports its max relative energy error E. Ours then tries
every fixed-step method the system accepts on the same span, in N = `--steps`, N // 2, N // 4,
... equal steps (each count half the last, rounded down, so the step is the workload's times
1, 2, 4, ... only while the halved counts stay whole), for as long as the max relative energy
error stays <= E and the final state is no farther from a reference run (dop853 at rtol 1e-13)
than the peer's final state is (relative, max norm, floored at 1e-11), and times the coarsest
passing run (best of `--repeats`). A case where no method passes even at N steps is reported
as such and left out of the geometric mean. Energy alone is
what the workloads define, but it would crown one huge step of the implicit midpoint rule on a
linear system (its quadratic energy is kept exactly at any step); the final-state condition
keeps the trajectory honest too. Standard library only, like compare_peer.py.
"""

import json
import math
import sys

from compare_peer import call, parse_args


def fastest(methods):
    """The passing row (one per method, `seconds` None where it did not pass) that took the
    least time, or None when no method reached the peer's accuracy."""
    passing = [r for r in methods if r["seconds"] is not None]
    return min(passing, key=lambda r: r["seconds"]) if passing else None


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
        ours = json.loads(
            call(args.ours, "same", case, args.steps, args.repeats, peer["drift"], peer_final)
        )
        best = fastest(ours["methods"])
        row = dict(case=case, peer_s=peer_s, peer_drift=peer["drift"],
                   peer_error=ours["peer_final_error"], best=best, tried=ours["methods"],
                   ratio=None if best is None else peer_s / best["seconds"])
        rows.append(row)
        peer_cols = (f"{case:<21}{peer_s * 1e3:>9.1f}{peer['drift']:>10.1e}"
                     f"{row['peer_error']:>10.1e}")
        if best is None:
            print(f"{peer_cols}  no method reached it, even in {args.steps} steps", flush=True)
            continue
        print(f"{peer_cols}{best['method']:>22}{best['steps']:>8}{best['seconds'] * 1e3:>9.2f}"
              f"{best['drift']:>10.1e}{best['final_error']:>10.1e}{row['ratio']:>8.0f}",
              flush=True)
    ratios = [r["ratio"] for r in rows if r["ratio"] is not None]
    if ratios:
        geomean = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
        print(f"geometric mean over {len(ratios)} of {len(rows)} cases: {geomean:.0f}x less "
              "time to the peer's own accuracy (energy and final state)")
    else:
        print("no case where a method reached the peer's accuracy: no geometric mean")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
