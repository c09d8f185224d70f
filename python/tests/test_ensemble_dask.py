"""Ensembles on a Dask LocalCluster: the same bits as the local engine (every output, the chaos
reductions and a SymPy engine's system included), even when a worker is killed mid-run (its
chunks run again elsewhere); the same error as the local engine when members fail during their
runs; the default chunks cover every member once, large ones first."""

import os
import signal

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import physicskit.classical as pc
from physicskit.classical.ensembles import _SMALLEST, _chunks

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


def test_progress_counts_the_members_of_finished_chunks(client):
    calls = []
    _run(client=client, chunk_size=7, progress=lambda done, total: calls.append((done, total)))
    # 144 members in chunks of 7 (the last of 4): each call adds whole chunks, the last all.
    done = [d for d, _ in calls]
    assert {t for _, t in calls} == {144} and done[-1] == 144
    assert done == sorted(done) and len(set(done)) == len(done)
    assert all(d % 7 == 0 or d >= 4 and (d - 4) % 7 == 0 for d in done)


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
    # A hundred times the span of the other test, in 24 chunks of 6 members: the first chunk
    # ends while most others are still queued or running, whatever the machine's speed.
    local = _run(t1=300.0, threads=1)
    pids = client.run(os.getpid)
    killed = []

    def kill_a_busy_worker(done, total):
        # Called in this thread as chunks finish, so the run is still going: kill, once, a
        # worker that holds a chunk now (its chunks are lost and must run again elsewhere).
        if killed or done == total:
            return
        busy = [address for address, keys in client.processing().items() if keys]
        if busy:
            victim = pids[busy[0]]
            os.kill(victim, signal.SIGKILL)
            killed.append(victim)

    out = _run(t1=300.0, client=client, chunk_size=6, progress=kill_a_busy_worker)
    assert killed, "no worker held a chunk when the first chunks finished"
    _same_bits(local, out)
    # The nanny restarted the killed worker as a new process.
    assert killed[0] not in client.run(os.getpid).values()


@given(st.integers(1, 10**7), st.integers(1, 64))
def test_default_chunks_cover_every_member_once_large_first_ending_small(n, cores):
    chunks = _chunks(n, cores, None)
    # Contiguous, in member order, from 0 to n: every member in exactly one chunk.
    assert chunks[0][0] == 0 and chunks[-1][1] == n
    assert all(a[1] == b[0] for a, b in zip(chunks, chunks[1:]))
    sizes = [stop - start for start, stop in chunks]
    assert min(sizes) >= 1 and sizes == sorted(sizes, reverse=True)
    # No chunk above half a core's share (the first batch), the last ones of the smallest
    # size (about 1/_SMALLEST of a share), and a few chunks per core: four batches that halve
    # from 1/2 to 1/16 of a share, then two of the smallest (1/32) take the rest.
    smallest = max(1, -(-n // (_SMALLEST * cores)))
    assert sizes[0] <= -(-n // (2 * cores)) and sizes[-1] <= smallest
    assert len(chunks) <= 6 * cores


def test_a_chunk_size_gives_equal_chunks_and_a_short_last_one():
    assert _chunks(10, 4, 3) == [(0, 3), (3, 6), (6, 9), (9, 10)]
    assert _chunks(10, 4, 20) == [(0, 10)]


def test_members_failing_during_their_runs_raise_the_local_engines_error(client):
    # Member 3 blows up at once, but only after members 0-2 of its chunk (the first) have run
    # 3e6 steps each; members 4-7 (the second chunk, on the other worker) blow up at once. The
    # local engine names the lowest failing member, 3; so must Dask, though the second chunk
    # fails first (by a few tenths of a second at least).
    y = np.array([0.1, -0.1, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0])
    states = np.zeros((8, 4))
    states[:, 1] = y
    states[:, 2] = np.sqrt(2 * 0.1 - y**2 + 2 * y**3 / 3)  # E = 0.1: bound orbits
    states[3:, 2] = 1e200  # x grows by 1e198 in the first step, its force overflows

    def run(**kw):
        return pc.ensemble(pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0]), (0.0, 3e4), 0.01,
                           "yoshida4", states=states, **kw)

    with pytest.raises(ValueError, match="member 3: ") as local:
        run(threads=1)
    with pytest.raises(ValueError, match="member 3: ") as dask:
        run(client=client, chunk_size=4)
    assert str(dask.value) == str(local.value)


def test_tolerances_travel_to_the_workers(client):
    def kepler(**kw):
        return pc.ensemble("kepler", (0.0, 4 * np.pi), np.pi / 32, "taylor",
                           sweep={"e": np.linspace(0.0, 0.8, 9)}, **kw)

    local = kepler(rtol=1e-6, atol=1e-6, threads=1)
    _same_bits(local, kepler(rtol=1e-6, atol=1e-6, client=client, chunk_size=2))
    # The tolerances changed the run: the defaults give other bits.
    assert local.final_state.tobytes() != kepler(threads=1).final_state.tobytes()


def _unaligned(a):
    """A copy of the float64 array ``a`` at an odd address."""
    raw = bytearray(a.nbytes + 1)
    out = np.frombuffer(raw, dtype=np.float64, count=a.size, offset=1).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned
    return out


def test_a_part_runs_from_unaligned_arrays(monkeypatch):
    # Dask's deserialization can hand a worker a part whose sweep sits at an odd byte offset of
    # its message (a worker reading one in place panicked, and the run above hung). The part is
    # handed to the engine as the worker gets it, unaligned: the run gives the aligned bits.
    def kepler():
        return pc.ensemble("kepler", (0.0, 4 * np.pi), np.pi / 32, "taylor",
                           sweep={"e": np.linspace(0.0, 0.8, 9)}, threads=1)

    aligned = kepler()
    run = pc.ensembles._Job.__call__

    def as_a_worker_gets_it(job, **extra):
        job.sweeps = [(k, _unaligned(v)) for k, v in job.sweeps]
        return run(job, **extra)

    monkeypatch.setattr(pc.ensembles._Job, "__call__", as_a_worker_gets_it)
    assert kepler().final_state.tobytes() == aligned.final_state.tobytes()


def _within(seconds, run):
    """``run()``'s outcome (its value or its exception), or a failure when it has not returned
    within ``seconds``: a run that waits forever fails the test instead of hanging it."""
    import threading

    box = {}

    def target():
        try:
            box["value"] = run()
        except BaseException as e:  # noqa: BLE001 (what is checked is what reaches the client)
            box["error"] = e

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), f"the client still waits after {seconds} s"
    return box


def _small_kepler(**kw):
    return pc.ensemble("kepler", (0.0, 1.0), 0.1, "rk4", sweep={"e": np.linspace(0.0, 0.8, 4)},
                       **kw)


class PanicException(BaseException):
    """Stands for the engine's panic: a BaseException that is not an Exception."""


def test_a_part_failing_with_a_base_exception_raises_in_the_client(monkeypatch):
    # A Dask worker reports only an Exception to the client; after any other BaseException
    # (the engine's PanicException) its task never finishes, and the client waited forever.
    run = pc.ensembles._Job.__call__

    def panics(job, **extra):
        if extra.get("check_only"):
            return run(job, **extra)  # the client's check of every member, before the parts
        raise PanicException("the pointer must be aligned")

    monkeypatch.setattr(pc.ensembles._Job, "__call__", panics)
    # One worker thread in this process, where the patched class is the one the part runs.
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=":0", silence_logs=50) as cluster:
        with distributed.Client(cluster) as c:
            # Seconds: the run itself takes milliseconds; a minute leaves room for a busy host.
            box = _within(60, lambda: _small_kepler(client=c, chunk_size=2))
    error = box.get("error")
    assert isinstance(error, RuntimeError), box
    assert "PanicException: the pointer must be aligned" in str(error)
    assert "failed on its Dask worker" in str(error)


def test_a_part_whose_worker_dies_raises_in_the_client():
    # Every worker that takes a part dies (the nanny restarts it, and Dask tries the part
    # again); after Dask's allowed failures the client raises instead of waiting.
    class Dies(distributed.WorkerPlugin):
        """Installed on every worker, restarted ones included: a part ends its process, as a
        crash or the OOM killer would. Defined here so that it travels by value."""

        def setup(self, worker):
            import physicskit.classical.ensembles as ensembles

            def dies(job, **extra):
                os._exit(3)

            ensembles._Job.__call__ = dies

    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=":0", silence_logs=50) as cluster:
        with distributed.Client(cluster) as c:
            c.register_plugin(Dies())
            # Four deaths and restarts of a worker process: a few seconds; two minutes for a
            # busy host.
            box = _within(120, lambda: _small_kepler(client=c))
    error = box.get("error")
    assert isinstance(error, distributed.KilledWorker), box
    assert "workers died while running it" in str(error)
