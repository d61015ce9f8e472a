"""rotgen.sweep against the CLI's summary.csv, and its trajectories against rotgen.simulate."""

import io
import os

import numpy as np
import pytest

import rotgen
from conftest import run_cli, source

NUTATION = source("models", "scenes", "heavy_top_nutation.yaml")


def short(scene_path):
    """The scene, 2 time units long (a sweep of 8 members takes well under a second)."""
    return rotgen.Scene(scene_path).with_(time={"end": 2, "samples": 201})


@pytest.mark.parametrize("threads,lanes", [(1, 1), (2, 1), (2, 4)])
def test_summary_equals_the_cli_summary_csv(threads, lanes, in_tmp):
    scene = short(NUTATION)
    with open("scene.yaml", "w") as f:  # the same scene, as a file, for the CLI
        f.write(scene.yaml_text)
    args = ["sweep", "scene.yaml", "-o", "out", "--vary", "initial.theta=0.1:1.5:8",
            "--vary", "parameters.h=0.05,0.1", "-j", str(threads), "--quiet"]
    if lanes > 1:
        args += ["--lanes", str(lanes)]
    status, _, err = run_cli(*args)
    assert status == 0, err
    cli = open("out/summary.csv").read()
    sw = rotgen.sweep(scene, vary={"initial.theta": (0.1, 1.5, 8), "parameters.h": [0.05, 0.1]},
                      threads=threads, lanes=lanes)
    assert sw.summary_csv == cli
    assert (sw.members, sw.failed, sw.keys) == (16, 0, ["initial.theta", "parameters.h"])
    pd = pytest.importorskip("pandas")
    expected = pd.read_csv(io.StringIO(cli), float_precision="round_trip")
    assert list(sw.summary.columns) == list(expected.columns)
    assert list(sw.summary.columns)[:3] == ["member", "initial.theta", "parameters.h"]
    pd.testing.assert_frame_equal(sw.summary, expected, check_exact=True)
    assert sorted(os.listdir(".")) == ["out", "scene.yaml"]


def test_trajectories_are_the_members_runs(in_tmp):
    scene = short(NUTATION)
    thetas = [0.2, 0.6, 1.1]
    sw = rotgen.sweep(scene, vary={"initial.theta": thetas}, threads=2)
    assert sw.trajectories.shape == (3, 201, len(sw.columns))
    assert sw.columns[0] == "t"
    for m, theta in enumerate(thetas):
        r = rotgen.simulate(scene.with_(initial={"theta": theta}))
        assert sw.columns[1:] == r.columns
        assert np.array_equal(sw.trajectories[m, :, 0], r.t)
        assert np.array_equal(sw.trajectories[m, :, 1:], r.y)
    assert rotgen.sweep(scene, vary={"initial.theta": thetas}, trajectories=False).trajectories \
        is None


def test_trajectories_carry_the_sensitivities(in_tmp):
    scene = short(NUTATION).with_(sensitivities=["initial.theta", "parameters.h"])
    thetas = [0.2, 0.6]
    sw = rotgen.sweep(scene, vary={"initial.theta": thetas}, threads=2)
    r = rotgen.simulate(scene.with_(initial={"theta": thetas[1]}))
    d = [f"d({c})/d({k})" for c in r.columns for k in r.sensitivity_keys]
    assert sw.columns == ["t"] + r.columns + d
    assert sw.trajectories.shape == (2, 201, 1 + len(r.columns) + len(d))
    # the member's own run: its d(...) columns, samples x columns x keys, in record then key order
    got = sw.trajectories[1, :, 1 + len(r.columns):]
    assert np.array_equal(got, r.sensitivities.reshape(201, -1), equal_nan=True)
    assert np.abs(got).max() > 1e-3


def test_the_scene_sweep_section_is_used_without_vary(in_tmp):
    d = short(NUTATION).to_dict()
    d["sweep"] = {"mode": "zip", "vary": {"initial.theta": {"values": [0.3, 0.4]},
                                          "parameters.M": {"values": [1.0, 2.0]}}}
    sw = rotgen.sweep(d)
    assert sw.keys == ["initial.theta", "parameters.M"]
    assert sw.members == 2


def test_summary_without_pandas_is_a_list_of_dicts(monkeypatch, in_tmp):
    import rotgen._run as run

    monkeypatch.setattr(run, "_pandas", lambda: None)
    sw = rotgen.sweep(short(NUTATION), vary={"initial.theta": (0.2, 0.4, 3)}, threads=1)
    assert isinstance(sw.summary, list) and len(sw.summary) == 3
    assert [row["member"] for row in sw.summary] == [0, 1, 2]
    assert [row["initial.theta"] for row in sw.summary] == [0.2, 0.30000000000000004, 0.4]
    assert all(row["status"] == "ok" for row in sw.summary)
    assert list(sw.summary[0])[:2] == ["member", "initial.theta"]
