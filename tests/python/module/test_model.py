"""rotgen.Model and rotgen.emit against `rotgen inspect` and `rotgen emit`."""

import json
import os

import rotgen
from conftest import run_cli, source

HEAVY = source("models", "heavy_top.yaml")


def test_parameters_and_equations_are_inspect_json():
    m = rotgen.Model(HEAVY)
    status, out, err = run_cli("inspect", HEAVY, "--format", "json")
    assert status == 0, err
    expected = json.loads(out)
    assert m.name == "heavy_top"
    assert m.parameters == expected["parameters"]
    assert m.equations(format="json") == expected
    assert m.equations(format="text") == run_cli("inspect", HEAVY)[1]
    assert m.equations(format="latex") == run_cli("inspect", HEAVY, "--format", "latex")[1]


def test_inertia_is_inspect_inertia():
    path = source("models", "full_tensor_top.yaml")
    status, out, err = run_cli("inspect", path, "--inertia", "--format", "json")
    assert status == 0, err
    got = rotgen.Model(path).inertia()
    assert got == json.loads(out)["inertia"]
    assert set(got) >= {"tensor", "principal_moments", "principal_axes", "class", "stability"}


def test_model_from_text_is_the_model_from_its_file():
    text = open(HEAVY).read()
    m = rotgen.Model(yaml_text=text)
    assert m.path == "<model>"
    assert m.equations() == rotgen.Model(HEAVY).equations()


def test_emit_writes_the_cli_header(in_tmp):
    status, _, err = run_cli("emit", HEAVY, "-o", "cli", "--form", "body")
    assert status == 0, err
    path = rotgen.emit(rotgen.Model(HEAVY), "py", form="body")
    assert path == os.path.join("py", "heavy_top_body.hpp")
    cli = open(os.path.join("cli", "heavy_top_body.hpp")).read()
    # the header's comment names the command that regenerates it, with its -o
    assert open(path).read() == cli.replace(" -o cli ", " -o py ")


def test_inertia_from_parameters_reads_as_in_the_cli():
    # Regression: inside the module a model whose inertia uses its parameters was refused
    # ("inertia is not a finite real number with the parameters' defaults") while the CLI read it:
    # the module kept its own copy of GiNaC's realsymbol typeinfo (hidden visibility), so a
    # parameter symbol hashed two ways and was not found in its substitution map.
    heavy = rotgen.Model(HEAVY)  # inertia: [I1, I1, I3]
    assert heavy.parameters["I1"] == 1.0
    assert heavy.inertia()["principal_moments"] == ["I1", "I1", "I3"]
    path = source("models", "cube_on_corner.yaml")  # the tensor from a part: a box of mass M
    status, out, err = run_cli("inspect", path, "--inertia", "--format", "json")
    assert status == 0, err
    got = rotgen.Model(path).inertia()
    assert got == json.loads(out)["inertia"]
    # (5.69): about the corner, 1/6 M L^2 along the diagonal and 11/12 M L^2 twice, exactly
    assert got["principal_moments"] == ["L**2*M/6", "11*L**2*M/12", "11*L**2*M/12"]
    values = got["principal_moment_values"]  # M = 1, L = 0.2
    expected = [0.04 / 6, 0.04 * 11 / 12, 0.04 * 11 / 12]
    assert max(abs(a - b) for a, b in zip(values, expected)) < 1e-16  # observed 6.9e-18
