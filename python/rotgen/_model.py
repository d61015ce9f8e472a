"""rotgen.Model and rotgen.emit: a model file, its derived equations and its generated header."""

import json
import os
import re

from . import _rotgen

MEMORY_MODEL = "<model>"


class Model:
    """A rigid-body model (a model file), read and checked when it is made.

    Parameters
    ----------
    path : str or os.PathLike, optional
        The model file (YAML, as ``rotgen inspect`` reads it).
    yaml_text : str, optional
        The model's YAML text instead of a file; errors then name the file ``<model>``.

    Raises
    ------
    InputError
        When the model is rejected (the CLI's message, file, line and column).
    TypeError
        When neither or both of ``path`` and ``yaml_text`` are given.

    Attributes
    ----------
    path : str
        The model file, or ``<model>`` for a model given as text.
    yaml_text : str or None
        The YAML text of a model given as text (None for a file).
    name : str
        The model's ``name``.
    rotor : bool
        Whether the model is a linear rotor (a body on a line: one principal moment
        zero, the other two equal; two angles), found from its inertia.
    parameters : dict
        The parameters (str) and their values (float), in the file's order.
    descriptions : dict
        The parameters' descriptions (str), for those that have one.

    Examples
    --------
    >>> m = rotgen.Model("models/heavy_top.yaml")
    >>> m.parameters
    {'I1': 1.0, 'I3': 0.5, 'M': 1.0, 'g': 9.81, 'h': 0.1}
    """

    def __init__(self, path=None, *, yaml_text=None):
        if (path is None) == (yaml_text is None):
            raise TypeError("Model takes a path or yaml_text=, one of the two")
        if yaml_text is not None:
            # an empty text is read as such (not as a missing file): "expected a YAML mapping"
            self.path, self.yaml_text = MEMORY_MODEL, str(yaml_text) or "\n"
        else:
            self.path, self.yaml_text = os.fspath(path), None
        info = _rotgen.model_info(self.path, self._text())
        self.name = info["name"]
        self.rotor = info["rotor"]
        self.parameters = {name: value for name, value, _ in info["parameters"]}
        self.descriptions = {name: text for name, _, text in info["parameters"] if text}
        self._equations = {}

    def _text(self):
        return self.yaml_text or ""

    def equations(self, format="json"):
        """The derived equations, as ``rotgen inspect --format FORMAT`` prints them.

        Parameters
        ----------
        format : {'json', 'text', 'latex'}
            ``'json'`` (the default) returns the parsed object; ``'text'`` and ``'latex'`` return
            the text.

        Returns
        -------
        dict or str
            For ``'json'`` a dict (``lagrangian``, ``momenta``, ``mass_matrix``,
            ``euler_lagrange``, ``hamiltonian``, ...; expressions are strings SymPy can parse),
            else the text. Derived once per format and kept.

        Raises
        ------
        ValueError
            An unknown format.
        """
        if format not in self._equations:
            self._equations[format] = _rotgen.inspect(self.path, self._text(), format, False)
        text = self._equations[format]
        return json.loads(text) if format == "json" else text

    def inertia(self):
        """The inertia report of ``rotgen inspect --inertia --format json``.

        Returns
        -------
        dict
            Keys: ``tensor`` (3x3), ``principal_moments`` (3), ``principal_axes`` (3x3, rows),
            ``class`` (spherical, symmetric, asymmetric, rotor) and ``stability`` (one entry per
            principal axis: ``axis``, ``stable``, ``rate`` per unit spin), and more (see the
            README).
        """
        text = _rotgen.inspect(self.path, self._text(), "json", True)
        return json.loads(text)["inertia"]

    def __repr__(self):
        where = "yaml_text" if self.yaml_text is not None else repr(self.path)
        return f"<rotgen.Model {self.name} ({where}), parameters {self.parameters}>"


def emit(model, directory, form=None, outputs=None, specialise=None, name=None, strategy=None):
    """Write the model's kernels as a C++ header, as ``rotgen emit`` does (the same bytes).

    Parameters
    ----------
    model : Model or str
        The model (or its file).
    directory : str or os.PathLike
        Where the header goes (created if missing).
    form : str, optional
        ``lagrangian`` (default), ``hamiltonian``, ``reduced``, ``body`` or ``rotor``.
    outputs : list of str, optional
        ``rhs``, ``jacobian``, ``energy``, ``momenta``, ... (default: all the form gives but
        ``taylor``).
    specialise : bool or list of str, optional
        Fold parameter values into the code: all of them (``True``) or those named.
    name : str, optional
        The unit's name (file ``NAME.hpp``).
    strategy : {'explicit', 'solve'}, optional
        Lagrangian form: explicit accelerations, or M and f solved inline.

    Returns
    -------
    str
        The path of the header written.

    Raises
    ------
    InputError
        The model or an option is rejected (the CLI's message).

    Examples
    --------
    >>> rotgen.emit("models/heavy_top.yaml", "out", outputs=["rhs", "energy"])
    'out/heavy_top.hpp'
    """
    if not isinstance(model, Model):
        model = Model(model)
    args = [model.path, "-o", os.fspath(directory)]
    if form is not None:
        args += ["--form", form]
    if outputs is not None:
        args += ["--outputs", ",".join(outputs)]
    if specialise is True:
        args.append("--specialise")
    elif specialise:
        args.append("--specialise=" + ",".join(specialise))
    if name is not None:
        args += ["--name", name]
    if strategy is not None:
        args += ["--strategy", strategy]
    printed = _rotgen.emit(args, model.path, model._text())
    found = re.match(r"rotgen: wrote (.*) \(operations", printed)
    return found.group(1) if found else printed.strip()
