"""rotgen.simulate against the CLI's own output (bit for bit) and against an exact solution."""

import csv
import math
import os

import numpy as np
import pytest

import rotgen
from conftest import run_cli, source

SCENES = sorted(f for f in os.listdir(source("models", "scenes")) if f.endswith(".yaml"))


def read_csv(path):
    with open(path, newline="") as f:  # after the provenance line ("# rotgen ... form F")
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    return rows[0], rows[1:]


def same_bits(a, b):
    """Equal as doubles, NaN equal to NaN."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.all((a == b) | (np.isnan(a) & np.isnan(b))))


@pytest.mark.parametrize("name", SCENES)
def test_simulate_equals_the_cli_csv_bit_for_bit(name, in_tmp):
    scene = source("models", "scenes", name)
    status, _, err = run_cli("simulate", scene, "-o", "cli.csv", "--quiet")
    assert status == 0, err
    header, rows = read_csv("cli.csv")
    os.remove("cli.csv")
    r = rotgen.simulate(scene)
    assert header == ["t", *r.columns]
    # the CSV has 17 significant digits: every double reads back exactly
    assert same_bits(r.t, [float(row[0]) for row in rows])
    assert same_bits(r.y, [[float(v) for v in row[1:]] for row in rows])
    if os.path.exists("cli.events.csv"):
        eheader, erows = read_csv("cli.events.csv")
        assert eheader == ["event", "t", "phase", *r.columns]
        assert [(e[0], e[2]) for e in r.events] == [(row[0], row[2]) for row in erows]
        assert same_bits([[e[1], *e[3]] for e in r.events],
                         [[float(v) for v in [row[1], *row[3:]]] for row in erows])
    else:
        assert r.events == []
    assert os.listdir(".") == [] or sorted(os.listdir(".")) == ["cli.events.csv"]


def test_nothing_is_written_to_disk(in_tmp):
    r = rotgen.simulate(source("models", "scenes", "falling_top.yaml"))  # a scene with events
    assert len(r.events) == 2  # halfway, then floor (terminal)
    assert r.summary["t_reached"] == r.events[-1][1]  # the terminal event's time
    assert os.listdir(".") == []


def test_free_symmetric_top_against_its_exact_solution(in_tmp):
    # Force-free symmetric top (I1 = I2): omega3 is constant and (omega1, omega2) turns at
    # Omega = (I3 - I1) / I1 * omega3 (Euler's equations 5.87-5.89).
    I1, I3, w10, w3 = 2.0, 0.5, 0.3, 4.0
    scene = rotgen.Scene({
        "model": {"name": "free_symmetric", "parameters": {"I1": I1, "I3": I3},
                  "inertia": ["I1", "I1", "I3"], "potential": "0"},
        "form": "body",
        "initial": {"phi": 0, "theta": 0.4, "psi": 0, "omega1": w10, "omega2": 0, "omega3": w3},
        "time": {"start": 0, "end": 20, "samples": 401},
        "integrator": {"method": "dop853", "rtol": 1e-12, "atol": 1e-14},
        "record": ["omega1", "omega2", "omega3"],
    })
    r = rotgen.simulate(scene)
    omega = (I3 - I1) / I1 * w3
    w1 = w10 * np.cos(omega * r.t)
    w2 = w10 * np.sin(omega * r.t)
    err = max(np.max(np.abs(r["omega1"] - w1)), np.max(np.abs(r["omega2"] - w2)),
              np.max(np.abs(r["omega3"] - w3)))
    assert err < 2e-11  # observed 2.3e-12
    assert r.columns == ["omega1", "omega2", "omega3"]
    assert r.t.shape == (401,) and r.y.shape == (401, 3)


def test_to_pandas_is_indexed_by_t():
    pd = pytest.importorskip("pandas")
    r = rotgen.simulate(source("models", "scenes", "heavy_top_nutation.yaml"))
    df = r.to_pandas()
    assert df.index.name == "t" and list(df.columns) == r.columns
    assert np.array_equal(df.index.to_numpy(), r.t)
    assert np.array_equal(df["theta"].to_numpy(), r["theta"])
    ev = rotgen.simulate(source("models", "scenes", "falling_top.yaml")).events_to_pandas()
    assert list(ev["event"]) == ["halfway", "floor"]
    assert isinstance(ev, pd.DataFrame)


def test_summary_reports_the_run():
    r = rotgen.simulate(source("models", "scenes", "heavy_top_nutation.yaml"))
    s = r.summary
    assert (s["model"], s["form"], s["method"], s["state_size"]) == \
        ("heavy_top", "lagrangian", "dop853", 6)
    assert s["steps"] > 0 and s["rhs_evals"] >= 12 * s["steps"]  # DOP853: 12 stages a step
    assert set(s["drifts"]) == {"energy", "p_phi", "p_psi"}
    # the drift is the CLI's: max |E(t) - E(0)| over the samples
    e = r["energy"]
    assert s["drifts"]["energy"] == np.max(np.abs(e - e[0]))


def test_with_changes_the_scene_and_keeps_the_rest(in_tmp):
    s = rotgen.Scene(source("models", "scenes", "heavy_top_nutation.yaml"))
    s2 = s.with_(initial={"theta": 0.7}, time={"end": 1, "samples": 11})
    assert (s2.t_end, s2.samples, s2.model) == (1.0, 11, "heavy_top")
    r = rotgen.simulate(s2)
    assert r.t[-1] == 1.0 and r["theta"][0] == 0.7
    assert r["phi_dot"][0] == 0.0  # kept from the file
    # the same as the file with those values written in it
    text = open(source("models", "scenes", "heavy_top_nutation.yaml")).read()
    text = text.replace("theta: 0.5", "theta: 0.7").replace("end: 10, samples: 1001",
                                                            "end: 1, samples: 11")
    text = text.replace("model: ../heavy_top.yaml",
                        "model: " + source("models", "heavy_top.yaml"))
    assert same_bits(rotgen.simulate(rotgen.Scene(yaml_text=text)).y, r.y)
    assert os.listdir(".") == []


def test_events_that_act_in_a_scene_dict(in_tmp):
    # a free symmetric top (I1 = I2 = 2, I3 = 0.5) kicked about its axis every 0.5: omega3 steps by
    # kick / I3 at each, and is constant between (Euler's equations 5.87-5.89)
    scene = rotgen.Scene({
        "model": {"name": "kicked_top", "parameters": {"I1": 2, "I3": 0.5, "kick": 0.05},
                  "inertia": ["I1", "I1", "I3"]},
        "form": "body",
        "initial": {"phi": 0, "theta": 0.5, "psi": 0, "omega1": 0.3, "omega2": 0, "omega3": 4},
        "time": {"end": 1.6, "samples": 17},
        "record": ["omega3"],
        "events": [{"name": "pulse", "every": 0.5, "action": {"impulse": [0, 0, "kick"]}}],
    })
    r = rotgen.simulate(scene)
    assert [(e[0], e[2]) for e in r.events] == [("pulse", "before"), ("pulse", "after")] * 3
    assert [e[1] for e in r.events] == pytest.approx([0.5, 0.5, 1.0, 1.0, 1.5, 1.5], abs=1e-15)
    for before, after in zip(r.events[0::2], r.events[1::2]):
        assert after[3][0] - before[3][0] == pytest.approx(0.1, abs=1e-14)  # observed 0 .. 9e-16
    assert list(r.events_to_pandas().columns) == ["event", "t", "phase", "omega3"]
    assert r["omega3"][-1] == pytest.approx(4.3, abs=1e-13)


def test_with_method_auto_runs_the_tuned_choice(in_tmp, monkeypatch):
    # issue 50: Scene.with_(integrator={"method": "auto", ...}) drops the file's rtol and atol, and
    # rotgen.simulate tunes (once, cached by content) and runs the choice, as the CLI does
    monkeypatch.setenv("ROTGEN_CACHE_DIR", str(in_tmp / "cache"))
    s = rotgen.Scene(source("models", "scenes", "heavy_top_nutation.yaml"))
    s2 = s.with_(integrator={"method": "auto", "error": 1e-6}, time={"end": 1, "samples": 51})
    r = rotgen.simulate(s2)
    assert r.summary["method"] != "auto"
    assert r.summary["auto"].startswith((r.summary["method"] + " rtol ", r.summary["method"] + " step "))
    assert "; cached" not in r.summary["auto"]
    again = rotgen.simulate(s2)
    assert again.summary["auto"].endswith("; cached)")
    assert same_bits(again.y, r.y)
    # a sweep chooses for an ensemble (steps under error control), cached apart from the one run's
    rotgen.sweep(s2, vary={"initial.theta": [0.4, 0.6]})
    assert len(list((in_tmp / "cache" / "tune").glob("*.choice"))) == 2
    # and a sweep in SIMD lanes for the methods the lanes run, apart again
    rotgen.sweep(s2, vary={"initial.theta": [0.4, 0.6]}, lanes=2)
    assert len(list((in_tmp / "cache" / "tune").glob("*.choice"))) == 3
    # back to a method of its own: the error key goes
    assert rotgen.simulate(s2.with_(integrator={"method": "dop853"})).summary["auto"] == ""
