"""Two models with two Euler conventions, run at once on two Python threads (issue 46): the
satellite of satellite_zyx.yaml (z-y-x: yaw, pitch, roll) and the heavy top (z-x-z: phi, theta,
psi). The convention is the model's, carried by the scene and the run, so every result is the
same, byte for byte, as the scene's lone run, however the runs interleave.

The interleaving is made certain by the module's test hook ROTGEN_TEST_INTERLEAVE=1
(python/src/bindings.hpp): a simulate or sweep that has read its scene waits until the other
thread has read its own, so each run integrates right after the other model was read. With the
convention a process-wide static (set when a model is read), every run then took the other
model's: the satellite's failed (InputError: the lagrangian form does not give 'yaw')."""

import threading

import numpy as np

import rotgen
from conftest import source

SATELLITE = source("models", "scenes", "satellite_spin.yaml")  # z-y-x
TOP = source("models", "scenes", "heavy_top_nutation.yaml")  # z-x-z
RUNS = 30


def short(path):
    """The scene, 2 time units long with 21 samples (a run well under 0.1 s)."""
    return rotgen.Scene(path).with_(time={"end": 2, "samples": 21})


def on_two_threads(monkeypatch, work):
    """work(name) on a thread per name, with the hook on; {name: results}, and every exception
    a thread met (its text), which the test expects to be none."""
    monkeypatch.setenv("ROTGEN_TEST_INTERLEAVE", "1")
    results = {"satellite": [], "top": []}
    errors = []

    def loop(name):
        try:
            for _ in range(RUNS):
                if errors:  # the other thread failed: no read of its will release this one
                    return
                results[name].append(work(name))
        except Exception as e:  # reported by the assertion below, with the thread's name
            errors.append(f"{name}: {type(e).__name__}: {e}")

    threads = [threading.Thread(target=loop, args=(name,)) for name in results]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    monkeypatch.delenv("ROTGEN_TEST_INTERLEAVE")
    return results, errors


def test_simulate_on_two_threads_equals_each_lone_run(monkeypatch):
    scenes = {"satellite": short(SATELLITE), "top": short(TOP)}
    lone = {name: rotgen.simulate(scene) for name, scene in scenes.items()}
    assert lone["satellite"].columns[:3] == ["yaw", "pitch", "roll"]
    assert lone["top"].columns[:2] == ["theta", "phi"]
    results, errors = on_two_threads(monkeypatch, lambda name: rotgen.simulate(scenes[name]))
    assert errors == []
    for name, runs in results.items():
        assert len(runs) == RUNS
        for r in runs:
            assert r.columns == lone[name].columns
            assert r.t.tobytes() == lone[name].t.tobytes(), name
            assert r.y.tobytes() == lone[name].y.tobytes(), name


def test_sweep_on_two_threads_equals_each_lone_sweep(monkeypatch):
    scenes = {"satellite": short(SATELLITE), "top": short(TOP)}
    vary = {"satellite": {"parameters.n": [0.8, 1.0, 1.2]},
            "top": {"initial.theta": [0.4, 0.5, 0.6]}}

    def sweep(name):
        return rotgen.sweep(scenes[name], vary=vary[name], threads=1)

    lone = {name: sweep(name) for name in scenes}
    assert lone["satellite"].columns[1:4] == ["yaw", "pitch", "roll"]
    assert (lone["satellite"].failed, lone["top"].failed) == (0, 0)
    results, errors = on_two_threads(monkeypatch, sweep)
    assert errors == []
    for name, sweeps in results.items():
        assert len(sweeps) == RUNS
        for s in sweeps:
            assert s.columns == lone[name].columns
            assert s.summary_csv == lone[name].summary_csv, name
            assert s.trajectories.tobytes() == lone[name].trajectories.tobytes(), name
            assert not np.isnan(s.trajectories).any()
