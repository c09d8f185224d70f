"""Ensembles on a Dask LocalCluster: the same bits as the local engine (every output, the chaos
reductions and a SymPy engine's system included), even when a worker is killed mid-run (its
chunks run again elsewhere)."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import physicskit.classical as pc

distributed = pytest.importorskip("distributed")

THETA = np.linspace(-3.0, 3.0, 12)


def _run(t1=3.0, **kw):
    return pc.ensemble(
        pc.DoublePendulum([0.0, 0.0], [0.0, 0.0]), (0.0, t1), 0.01, "rk4",
        grid={"theta0[0]": THETA, "theta0[1]": THETA},
        events={"flip": pc.abs_above(1, np.pi)}, energy_error=True, stride=100, **kw)


def _same_bits(a, b):
    for name in ("final_state", "trajectory", "energy_error", "t", "steps", "max_lyapunov",
                 "sali"):
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None and y is None) or x.tobytes() == y.tobytes(), name
    assert a.events.keys() == b.events.keys()
    for name in a.events:
        assert a.events[name].tobytes() == b.events[name].tobytes(), name
    assert a.shape == b.shape and a.method == b.method


@pytest.fixture(scope="module")
def client():
    # Two worker processes of one thread each, with nannies that restart a killed worker.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=50) as cluster:
        with distributed.Client(cluster) as c:
            yield c


def test_local_cluster_gives_the_local_bits(client):
    local = _run(threads=1)
    _same_bits(local, _run(client=client))
    # Any chunking: one member per chunk at the edge of a chunk, and uneven chunks.
    _same_bits(local, _run(client=client, chunk_size=7))


def test_chaos_reductions_and_a_sympy_engine_system_give_the_local_bits(client):
    # Small runs (a fraction of a second each): what is checked is the shipping of the outputs
    # and of an engine's system (its compiled expressions) to the workers.
    short = dict(t1=2.0, max_lyapunov=True, sali=True, renormalize_every=5)
    _same_bits(_run(threads=1, **short), _run(client=client, chunk_size=25, **short))
    sp = pytest.importorskip("sympy")
    from physicskit.classical.utils import ODEEngine

    x, y, z, s, r, b = sp.symbols("x y z sigma rho beta")
    lorenz = ODEEngine([x, y, z], [s * (y - x), x * (r - z) - y, x * y - b * z],
                       params={"sigma": 10.0, "rho": 28.0, "beta": 8.0 / 3.0}).system([1, 1, 1])
    run = dict(grid={"rho": np.linspace(0.5, 30.0, 9), "sigma": [8.0, 10.0]}, stride=50,
               max_lyapunov=True)
    local = pc.ensemble(lorenz, (0.0, 5.0), 0.01, "rk4", threads=1, **run)
    _same_bits(local, pc.ensemble(lorenz, (0.0, 5.0), 0.01, "rk4", client=client, chunk_size=4,
                                  **run))


def test_a_worker_killed_mid_run_costs_only_its_chunk(client):
    # A hundred times the span of the other test: on an idle machine a tenfold one ends in
    # 0.3 s, before the kill at 0.5 s (dispatch dominates); this one takes seconds.
    local = _run(t1=300.0, threads=1)
    pids = client.run(os.getpid)
    victim = sorted(pids.values())[0]
    killed = threading.Event()

    def kill_soon():
        # Into the run: the chunks (24 of 6 members each) are under way by then.
        time.sleep(0.5)
        os.kill(victim, signal.SIGKILL)
        killed.set()

    killer = threading.Thread(target=kill_soon)
    killer.start()
    start = time.monotonic()
    out = _run(t1=300.0, client=client, chunk_size=6)
    elapsed = time.monotonic() - start
    killer.join()
    assert killed.is_set()
    # The run was still going when the worker died, so some of its chunks were lost and run
    # again (the nanny restarts the worker; the scheduler reschedules its tasks).
    assert elapsed > 0.5, f"the run ended in {elapsed:.2f} s, before the kill"
    _same_bits(local, out)
    assert victim not in client.run(os.getpid).values()
