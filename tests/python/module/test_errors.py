"""Errors: rotgen.InputError carries the CLI's line and its place; rotgen.RunError the partial
run; Ctrl-C stops a long run."""

import _thread
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import rotgen
from conftest import run_cli, source

BAD_MODEL = """name: bad_top
parameters:
  I1: 1.0
  I3: 0.5
inertia: [I1, I1, I3]
potential: 2*cos(thta)
"""


def cli_line(stderr):
    line = stderr.strip().splitlines()[-1]
    assert line.startswith("rotgen: error: ")
    return line[len("rotgen: error: "):]


def test_a_bad_model_file_gives_the_cli_line_and_its_place(in_tmp):
    with open("bad.yaml", "w") as f:
        f.write(BAD_MODEL)
    status, _, err = run_cli("inspect", "bad.yaml")
    assert status == 2
    with pytest.raises(rotgen.InputError) as info:
        rotgen.Model("bad.yaml")
    e = info.value
    assert isinstance(e, ValueError)
    assert str(e) == cli_line(err)
    # 'thta' is on line 6, column 18 (1-based)
    assert (e.file, e.line, e.column) == ("bad.yaml", 6, 18)
    assert "unknown symbol 'thta'" in str(e)


def test_a_bad_model_text_is_located_in_the_text():
    with pytest.raises(rotgen.InputError) as info:
        rotgen.Model(yaml_text=BAD_MODEL)
    e = info.value
    assert (e.file, e.line, e.column) == ("<model>", 6, 18)
    assert str(e).startswith("<model>:6:18: unknown symbol 'thta'")


def test_a_bad_scene_dict_is_located_in_its_yaml_text():
    with pytest.raises(rotgen.InputError) as info:
        rotgen.Scene({"model": source("models", "heavy_top.yaml"),
                      "initial": {"phi": 0, "theta": 0.5, "psi": 0, "phi_dot": 0,
                                  "theta_dot": 0, "psi_dot": 1},
                      "time": {"start": 0, "end": 1, "samples": 11},
                      "integrator": {"method": "dop854"}})
    e = info.value
    assert e.file == "<scene>" and e.line is not None
    assert "dop854" in str(e)


def test_a_bad_vary_entry_gives_the_cli_line(in_tmp):
    scene = source("models", "scenes", "heavy_top_nutation.yaml")
    status, _, err = run_cli("sweep", scene, "-o", "out", "--vary", "initial.thta=0:1:3")
    assert status == 2
    with pytest.raises(rotgen.InputError) as info:
        rotgen.sweep(scene, vary={"initial.thta": (0, 1, 3)})
    assert str(info.value) == cli_line(err)
    assert os.listdir(".") == []


def test_a_run_that_stops_raises_run_error_with_the_partial_result(in_tmp):
    scene = rotgen.Scene(source("models", "scenes", "heavy_top_nutation.yaml")).with_(
        integrator={"max_steps": 50})
    with open("scene.yaml", "w") as f:
        f.write(scene.yaml_text)
    status, _, err = run_cli("simulate", "scene.yaml", "-o", "cli.csv", "--quiet")
    assert status == 3
    with pytest.raises(rotgen.RunError) as info:
        rotgen.simulate(scene)
    e = info.value
    # the CLI's line up to where it names its partial file (`<scene>` is scene.yaml there)
    expected = cli_line(err).split("; the ")[0].replace("scene.yaml", "<scene>", 1)
    assert str(e) == expected
    # the summary's t_reached is the time the message names (format_double round-trips), past
    # the last partial sample: the run stopped between samples
    t_named = float(expected.split("stopped at t = ")[1].split(" of ")[0])
    assert e.result.summary["t_reached"] == t_named > e.result.t[-1]
    rows = np.loadtxt("cli.partial.csv", delimiter=",", skiprows=2, ndmin=2)  # provenance, header
    assert not e.result.success and len(e.result.t) == len(rows) > 0
    assert np.array_equal(e.result.t, rows[:, 0]) and np.array_equal(e.result.y, rows[:, 1:])


def long_scene():
    """The nutating top for 10^5 time units: minutes of integration."""
    return rotgen.Scene(source("models", "scenes", "heavy_top_nutation.yaml")).with_(
        time={"end": 1e5, "samples": 100001}, integrator={"rtol": 1e-13, "atol": 1e-14})


def interrupted_after(seconds, call):
    """Ctrl-C (as _thread.interrupt_main delivers it) `seconds` into `call`: the time it took to
    stop, or None if it was not interrupted."""
    timer = threading.Timer(seconds, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        call()
    except KeyboardInterrupt:
        return time.monotonic() - start
    finally:
        timer.cancel()
    return None


def test_ctrl_c_stops_a_long_simulate(in_tmp):
    scene = long_scene()
    rotgen.simulate(scene.with_(time={"end": 1, "samples": 11}))  # kernels compiled before
    took = interrupted_after(0.5, lambda: rotgen.simulate(scene))
    assert took is not None
    # observed 0.002 to 0.013 s after the signal (a sample every ~2 ms, the GIL taken every
    # 5 ms); the bound leaves room for a loaded machine. The whole run takes minutes.
    assert took - 0.5 < 0.25
    assert os.listdir(".") == []


def test_ctrl_c_stops_a_long_sweep(in_tmp):
    scene = long_scene().with_(time={"end": 2000, "samples": 101})
    took = interrupted_after(
        0.5, lambda: rotgen.sweep(scene, vary={"initial.theta": (0.2, 1.2, 64)}, threads=2))
    assert took is not None
    # the members running finish first (one takes 0.23 s): observed 0.11 to 0.26 s after the
    # signal; all 64 take about 8 s on 2 threads
    assert took - 0.5 < 2.5
    assert os.listdir(".") == []


SIGNALS = """
import signal, sys
def caught():  # the signals this process has a handler for (the kernel's view)
    for line in open("/proc/self/status"):
        if line.startswith("SigCgt:"):
            return line.split()[1]
import threading  # a thread first: glibc's own handler for its threads (signal 33) comes then
worker = threading.Thread(target=lambda: None)
worker.start()
worker.join()
before, handler = caught(), signal.getsignal(signal.SIGINT)
import rotgen
scene = sys.argv[1]
rotgen.simulate(scene)
rotgen.sweep(scene, vary={"initial.theta": (0.2, 0.4, 4)}, threads=2)
print(before, caught(), signal.getsignal(signal.SIGINT) is handler)
"""


def test_the_module_installs_no_signal_handler(in_tmp):
    scene = rotgen.Scene(source("models", "scenes", "heavy_top_nutation.yaml")).with_(
        time={"end": 1, "samples": 11})
    with open("scene.yaml", "w") as f:
        f.write(scene.yaml_text)
    p = subprocess.run([sys.executable, "-c", SIGNALS, "scene.yaml"], capture_output=True,
                       text=True, check=True)
    before, after, same_handler = p.stdout.split()
    assert before == after and same_handler == "True"
