"""The progress callback: called with (stage, fraction, message), cancels on False or an
exception, and the GIL is free while the library computes."""

import threading

import pytest

import capmesh
from conftest import OPEN_MESH

STAGES = {"validate", "flatten", "radius search", "transport", "project", "remesh", "harmonics"}


def test_reports_stages_and_fractions():
    v, f = capmesh.read_mesh(OPEN_MESH)
    calls = []
    capmesh.remesh(v, f, faces_target=500, progress=lambda *a: calls.append(a))
    assert calls, "no progress report"
    assert {c[0] for c in calls} <= STAGES
    assert {"transport", "remesh"} <= {c[0] for c in calls}
    assert all(0.0 <= c[1] <= 1.0 and isinstance(c[2], str) for c in calls)


def test_false_cancels():
    v, f = capmesh.read_mesh(OPEN_MESH)
    calls = []

    def stop_at_transport(stage, fraction, message):
        calls.append(stage)
        return stage != "transport"

    with pytest.raises(capmesh.Cancelled, match="cancelled"):
        capmesh.parameterize(v, f, progress=stop_at_transport)
    assert calls[-1] == "transport"


def test_exception_cancels_and_propagates():
    v, f = capmesh.read_mesh(OPEN_MESH)

    class Stop(Exception):
        pass

    def boom(stage, fraction, message):
        raise Stop(stage)

    with pytest.raises(Stop):
        capmesh.remesh(v, f, progress=boom)


def test_gil_released_during_compute():
    v, f = capmesh.read_mesh(OPEN_MESH)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.005)

    t = threading.Thread(target=tick)
    t.start()
    try:
        # No callback: the library never takes the GIL back on this path except to check
        # signals at each report, so the other thread must run meanwhile.
        capmesh.remesh(v, f, faces_target=2000)
    finally:
        done.set()
        t.join()
    assert len(ticks) > 10
