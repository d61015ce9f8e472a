"""rotgen.fit: a scene's free keys fitted to measurements, as ``rotgen fit`` fits them."""

import os

import numpy as np

from . import _rotgen
from ._errors import RunError
from ._scene import Scene, source_of


class FitResult:
    """The outcome of :func:`fit` (what ``rotgen fit`` prints and writes).

    Made by :func:`fit` (and held by :class:`RunError`), not by user code.

    Parameters
    ----------
    d : dict
        What the compiled core returns.

    Attributes
    ----------
    keys : list of str
        The free keys, in the order given.
    values, stderr, initial : dict
        Key to its estimate, standard error and initial guess.
    covariance, correlation : ndarray
        Shape (k, k), rows and columns in the order of :attr:`keys`.
    scene : Scene
        The scene with the fitted values written in (``rotgen.simulate(r.scene)`` runs the
        fitted motion).
    residuals : DataFrame
        ``t`` and one column per residual column (model - measured; ``attitude1..3`` the rotation
        vector of q_measured^-1 q_model in radians), one row per data row, NaN where missing.
    converged : bool
        Whether the solver converged (else :func:`fit` raised :class:`RunError` with this result).
    columns, sigma, rms : list
        The residual columns, each one's sigma (given, or its own residual RMS) and RMS residual.
    sigma_given : bool
        Whether ``sigma`` was given (else the covariance is scaled by chi2/dof).
    chi2, dof, iterations, evaluations, stop, condition
        chi2 and its degrees of freedom; the solver's iterations, residual evaluations, why it
        stopped; the condition number of the scaled J^T W J at the solution.
    runs, sensitivities
        The runs the fit made, and whether its Jacobian came from the runs' sensitivities (one
        run per Jacobian) rather than central differences of runs (2k more per Jacobian).
    summary : str
        What ``rotgen fit`` prints.
    """

    def __init__(self, d):
        self.keys = list(d["keys"])
        self.values = dict(zip(self.keys, d["values"]))
        self.stderr = dict(zip(self.keys, d["stderr"]))
        self.initial = dict(zip(self.keys, d["initial"]))
        self.covariance = np.asarray(d["covariance"])
        self.correlation = np.asarray(d["correlation"])
        self.columns = list(d["columns"])
        self.sigma = list(d["sigma"])
        self.rms = list(d["rms"])
        self.sigma_given = d["sigma_given"]
        self.chi2 = d["chi2"]
        self.dof = d["dof"]
        self.iterations = d["iterations"]
        self.evaluations = d["evaluations"]
        self.stop = d["stop"]
        self.condition = d["condition"]
        self.runs = d["runs"]
        self.sensitivities = d["sensitivities"]
        self.converged = d["converged"]
        self.summary = d["summary"]
        self.scene = Scene(yaml_text=d["fitted_yaml"])
        import pandas

        res = np.asarray(d["residuals"])
        frame = {"t": np.asarray(d["t"])}
        for i, c in enumerate(self.columns):
            frame[c] = res[:, i]
        self.residuals = pandas.DataFrame(frame)

    def __repr__(self):
        keys = ", ".join(f"{k}={v:.6g}+-{self.stderr[k]:.2g}" for k, v in self.values.items())
        return f"FitResult({keys}; chi2={self.chi2:.4g}, dof={self.dof}, converged={self.converged})"


def fit(scene, data, free, sigma=None, max_evaluations=0):
    """Fit a scene's free keys to measurements by weighted least squares, as ``rotgen fit``.

    Parameters
    ----------
    scene : Scene, str, os.PathLike or dict
        The scene; its values of the free keys are the initial guess.
    data : pandas.DataFrame, str or os.PathLike
        A ``t`` column and measured recordable columns (``omega1..3``, ``q0..q3`` together, the
        angles, ...); NaN (or an empty CSV field) is a missing measurement.
    free : list of str
        The keys to fit: ``initial.<name>``, ``parameters.<name>``.
    sigma : dict, optional
        Column (``q`` for the attitude) to its standard deviation. Without it, each column is
        weighted by its own residual RMS and the covariance scaled by chi2/dof.
    max_evaluations : int, optional
        Of the residuals; 0: 100 (k + 1).

    Returns
    -------
    FitResult

    Raises
    ------
    InputError
        Bad data or keys, or a combination of keys the data do not determine.
    RunError
        The solver did not converge; ``e.result`` is the last iterate's :class:`FitResult`.
    """
    path, text = source_of(scene)
    sigma_text = ",".join(f"{k}={float(v)!r}" for k, v in (sigma or {}).items())
    if isinstance(data, (str, os.PathLike)):
        d = _rotgen.fit(path, text, os.fspath(data), [], [], list(free), sigma_text,
                        max_evaluations)
    else:
        names = [str(c) for c in data.columns]
        columns = [np.asarray(data[c], dtype=float).tolist() for c in data.columns]
        d = _rotgen.fit(path, text, "", names, columns, list(free), sigma_text, max_evaluations)
    result = FitResult(d)
    if not result.converged:
        raise RunError(f"the fit did not converge ({result.stop})", result)
    return result
