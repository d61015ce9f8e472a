"""rotgen.simulate with the scene's `sensitivities`: r.sensitivity_keys, r.sensitivities
(samples x columns x keys), r.state_sensitivities, r.stm and the d(...) columns of to_pandas(),
against the CLI's CSV bit for bit and the state-transition matrix's own properties."""

import csv
import os

import numpy as np
import pytest

import rotgen
from conftest import run_cli, source

SCENE = """model: {model}
form: {form}
initial: {{phi: 0, theta: 0.5, psi: 0, phi_dot: 0.3, theta_dot: 0.1, psi_dot: 5}}
time: {{start: 0, end: 3, samples: 7}}
integrator: {{method: dop853, rtol: 1e-12, atol: 1e-14}}
record: [theta, phi, energy]
switch_chart: false
sensitivities: {sensitivities}
"""


def write_scene(form, sensitivities):
    text = SCENE.format(model=source("models", "heavy_top.yaml"), form=form,
                        sensitivities=sensitivities)
    with open("scene.yaml", "w") as f:
        f.write(text)
    return "scene.yaml"


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    return rows[0], np.array([[float(v) for v in row] for row in rows[1:]])


def test_sensitivities_equal_the_cli_columns_bit_for_bit(in_tmp):
    scene = write_scene("lagrangian", "[initial.theta, parameters.h]")
    status, _, err = run_cli("simulate", scene, "-o", "cli.csv", "--quiet")
    assert status == 0, err
    header, rows = read_csv("cli.csv")
    r = rotgen.simulate(scene)
    assert r.sensitivity_keys == ["initial.theta", "parameters.h"]
    assert r.sensitivities.shape == (7, 3, 2)
    for c, column in enumerate(r.columns):
        for k, key in enumerate(r.sensitivity_keys):
            at = header.index(f"d({column})/d({key})")
            assert np.array_equal(r.sensitivities[:, c, k], rows[:, at])
    assert r.sensitivities[0, 0, 0] == 1.0 and r.sensitivities[0, 0, 1] == 0.0  # d theta0
    assert r.state_sensitivities.shape == (7, 6, 2)
    assert r.stm is None
    pd = pytest.importorskip("pandas")
    df = r.to_pandas()
    assert list(df.columns) == header[1:]
    assert np.array_equal(df["d(energy)/d(parameters.h)"].to_numpy(),
                          rows[:, header.index("d(energy)/d(parameters.h)")])


def test_stm_of_all_initial_is_symplectic_in_the_hamiltonian_form(in_tmp):
    r = rotgen.simulate(write_scene("hamiltonian", "{keys: all_initial}"))
    assert r.sensitivity_keys[:3] == ["y0.phi", "y0.theta", "y0.psi"]
    assert r.stm.shape == (7, 6, 6)
    assert np.array_equal(r.stm[0], np.eye(6))
    J = np.block([[np.zeros((3, 3)), np.eye(3)], [-np.eye(3), np.zeros((3, 3))]])
    for phi in r.stm:
        assert np.linalg.norm(phi.T @ J @ phi - J) / max(1, np.linalg.norm(phi) ** 2) < 1e-9


def test_without_sensitivities_the_attributes_are_empty():
    r = rotgen.simulate(source("models", "scenes", "heavy_top_nutation.yaml"))
    assert r.sensitivity_keys == [] and r.sensitivities is None and r.stm is None
    assert r.state_sensitivities is None
