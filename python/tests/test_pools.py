"""jkrbem in process pools: a worker started by fork or by spawn runs a simulation after its
parent has run one, and gives the parent's answer. A hang fails the test (the result is
awaited with a timeout) rather than blocking the suite."""

import multiprocessing

import pytest

import jkrbem

#: A small run (0.1 s on one core).
SMALL = dict(ratio=1, grid=32, backend="cpu", steps=20)

#: How long a worker may take to start and run SMALL (s): far more than it needs.
TIMEOUT_S = 30

pytestmark = pytest.mark.filterwarnings("ignore::jkrbem.JkrbemWarning")


@pytest.mark.parametrize("method", [
    pytest.param("fork", marks=[
        pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(), reason="no fork here"),
    ]),
    "spawn",
])
def test_a_pool_worker_simulates_after_its_parent_did(method):
    parent = jkrbem.simulate(**SMALL)  # the parent's thread pool exists before the workers start
    with multiprocessing.get_context(method).Pool(1) as pool:
        try:
            child = pool.apply_async(jkrbem.simulate, kwds=SMALL).get(timeout=TIMEOUT_S)
        except multiprocessing.TimeoutError:
            pytest.fail(f"a {method} worker did not finish a 0.1 s run in {TIMEOUT_S} s: it hangs")
    assert isinstance(child, jkrbem.Result)
    assert child.adhesive_force == pytest.approx(parent.adhesive_force, rel=1e-9)
    assert len(child.states) == len(parent.states)


@pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(), reason="no fork here")
def test_a_worker_forked_while_its_parent_simulates_in_a_thread_runs_too():
    # The fork copies the parent mid-run (its solver thread and pool threads are not copied):
    # the child builds its own pool and thread and does not wait on them.
    import threading

    started = threading.Event()
    parent = {}

    def watch(event):
        if event["event"] == "state":
            started.set()

    def run():
        parent["result"] = jkrbem.simulate(ratio=1, grid=128, backend="cpu", progress=watch)

    thread = threading.Thread(target=run)
    thread.start()
    try:
        assert started.wait(TIMEOUT_S), "the parent's run did not start"
        with multiprocessing.get_context("fork").Pool(1) as pool:
            try:
                child = pool.apply_async(jkrbem.simulate, kwds=SMALL).get(timeout=TIMEOUT_S)
            except multiprocessing.TimeoutError:
                pytest.fail(f"a worker forked during its parent's run did not finish in {TIMEOUT_S} s")
    finally:
        thread.join()
    assert child.adhesive_force == pytest.approx(jkrbem.simulate(**SMALL).adhesive_force, rel=1e-9)
    assert parent["result"].complete
