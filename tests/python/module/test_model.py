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
