"""rotgen.fit: against SciPy's least_squares (finite-difference Jacobian, the model through
rotgen.simulate) on the same synthetic problem, and its errors and results."""

import numpy as np
import pandas as pd
import pytest
import scipy.optimize

import rotgen
from conftest import source

SCENE = source("tests", "fit", "free_body_fit.yaml")
SIGMA = 1e-3


def synthetic(seed=3):
    """The free body's omega at its 101 sample times with gyro noise (truth I1 = 1, I2 = 2)."""
    truth = rotgen.simulate(SCENE)
    rng = np.random.default_rng(seed)
    data = pd.DataFrame({"t": truth.t, **{c: truth[c].copy() for c in
                                          ("omega1", "omega2", "omega3")}})
    for c in ("omega1", "omega2", "omega3"):
        data[c] += SIGMA * rng.standard_normal(len(data))
    return data


def test_fit_agrees_with_scipy_least_squares(in_tmp):
    data = synthetic()
    start = rotgen.Scene(SCENE).with_({"parameters.I1": 1.2, "parameters.I2": 1.6})
    sigma = {"omega1": SIGMA, "omega2": SIGMA, "omega3": SIGMA}
    r = rotgen.fit(start, data, free=["parameters.I1", "parameters.I2"], sigma=sigma)
    assert r.converged

    measured = data[["omega1", "omega2", "omega3"]].to_numpy()

    def residuals(x):
        s = start.with_({"parameters.I1": float(x[0]), "parameters.I2": float(x[1])})
        run = rotgen.simulate(s)
        model = np.column_stack([run["omega1"], run["omega2"], run["omega3"]])
        return ((model - measured) / SIGMA).ravel()

    s = scipy.optimize.least_squares(residuals, [1.2, 1.6], method="lm", x_scale="jac")
    for i, key in enumerate(["parameters.I1", "parameters.I2"]):
        # the same estimate to well within its standard error (observed: ~1e-4 of it)
        assert abs(r.values[key] - s.x[i]) < 0.1 * r.stderr[key]
    assert r.chi2 == pytest.approx(float(np.sum(s.fun ** 2)), rel=1e-6)
    # the truth within 3 standard errors
    assert abs(r.values["parameters.I1"] - 1.0) < 3 * r.stderr["parameters.I1"]
    assert abs(r.values["parameters.I2"] - 2.0) < 3 * r.stderr["parameters.I2"]


def test_fit_result_holds_the_fitted_scene_and_residuals(in_tmp):
    data = synthetic()
    start = rotgen.Scene(SCENE).with_({"parameters.I1": 1.2})
    r = rotgen.fit(start, data, free=["parameters.I1"])
    assert not r.sigma_given
    assert list(r.residuals.columns) == ["t", "omega1", "omega2", "omega3"]
    assert len(r.residuals) == len(data)
    assert r.covariance.shape == (1, 1) and r.correlation[0, 0] == pytest.approx(1)
    # the fitted scene runs the fitted motion: its residuals are the fit's
    run = rotgen.simulate(r.scene)
    np.testing.assert_allclose(run["omega1"] - data["omega1"].to_numpy(), r.residuals["omega1"],
                               atol=1e-9)


def test_fit_refuses_bad_data_with_its_place(in_tmp):
    data = synthetic()
    data.loc[4, "t"] = 99.0
    with pytest.raises(rotgen.InputError) as e:
        rotgen.fit(SCENE, data, free=["parameters.I1"])
    assert e.value.line == 6 and "outside the scene's span" in str(e.value)


def test_fit_that_does_not_converge_raises_run_error_with_the_last_iterate(in_tmp):
    data = synthetic()
    start = rotgen.Scene(SCENE).with_({"parameters.I1": 1.2, "parameters.I2": 1.6})
    with pytest.raises(rotgen.RunError) as e:
        rotgen.fit(start, data, free=["parameters.I1", "parameters.I2"], max_evaluations=2)
    assert not e.value.result.converged
    assert "evaluations ran out" in e.value.result.stop
