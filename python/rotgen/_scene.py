"""rotgen.Scene: a scene file (or a dict with a scene's keys), read and checked when it is made."""

import os
from collections.abc import Mapping

from . import _rotgen

MEMORY_SCENE = "<scene>"


def _plain(value):
    """Dicts, lists, strings and numbers that YAML can write (NumPy scalars and tuples too)."""
    from ._model import Model

    if isinstance(value, Model):
        if value.yaml_text is None:
            return os.fspath(value.path)
        import yaml

        return yaml.safe_load(value.yaml_text)
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, (str, bool, int, float)) or value is None:
        return value
    if hasattr(value, "tolist"):  # NumPy scalars and arrays
        return _plain(value.tolist())
    return str(value)


def _merge(base, changes):
    """`changes` over `base`: mappings merge key by key, None removes a key, other values replace;
    a key "a.b" is the key b of the mapping a."""
    out = dict(base)
    for key, value in changes.items():
        if "." in key:
            head, rest = key.split(".", 1)
            inner = out.get(head)
            out[head] = _merge(inner if isinstance(inner, Mapping) else {}, {rest: value})
        elif value is None:
            out.pop(key, None)
        elif isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = _merge(out[key], value)
        else:
            out[key] = value
    return out


class Scene:
    """A scene: a model, its initial values, the time span, the integrator and what to record.

    Parameters
    ----------
    source : str, os.PathLike or dict
        A scene file, or a dict with the keys of a scene file (``model`` a path relative to the
        current directory, a dict holding the model, or a :class:`Model`).
    yaml_text : str, optional
        The scene's YAML text instead (its ``model`` path relative to the current directory).

    Raises
    ------
    InputError
        When the scene (or its model) is rejected. A scene given as a dict or text is named
        ``<scene>`` in errors; the line and column are those of :attr:`yaml_text`.
    TypeError
        When neither or both of ``source`` and ``yaml_text`` are given.

    Attributes
    ----------
    path : str
        The file, or ``<scene>``.
    yaml_text : str or None
        The YAML text of a scene given as a dict or text (None for a file).
    model : str
        The model's name.
    model_file : str
        The model's file as the scene names it, joined to the scene's directory (``<scene>``
        for a model given inline).
    form : str
        The form the scene runs (``lagrangian``, ``body``, ...).
    method : str
        The integrator's method.
    t_start : float
        The start time.
    t_end : float
        The end time.
    samples : int
        The number of samples.
    record : list of str
        The recorded columns.
    events : list of str
        The names of the scene's events.

    Examples
    --------
    >>> s = rotgen.Scene("models/scenes/heavy_top_nutation.yaml")
    >>> s.model, s.method
    ('heavy_top', 'dop853')
    """

    def __init__(self, source=None, *, yaml_text=None):
        if (source is None) == (yaml_text is None):
            raise TypeError("Scene takes a path, a dict or yaml_text=, one of them")
        if isinstance(source, Mapping):
            import yaml

            yaml_text = yaml.safe_dump(_plain(source), sort_keys=False)
        if yaml_text is not None:
            self.path, self.yaml_text = MEMORY_SCENE, str(yaml_text) or "\n"
        else:
            self.path, self.yaml_text = os.fspath(source), None
        info = _rotgen.scene_info(self.path, self._text())
        for key in ("model", "model_file", "form", "method", "t_start", "t_end", "samples",
                    "record", "events"):
            setattr(self, key, info[key])

    def _text(self):
        return self.yaml_text or ""

    def to_dict(self):
        """The scene's keys as a dict (read with PyYAML).

        Returns
        -------
        dict
            The scene file's keys; a ``model`` path is made relative to the current directory.
        """
        import yaml

        if self.yaml_text is not None:
            return yaml.safe_load(self.yaml_text)
        with open(self.path, encoding="utf-8") as f:
            d = yaml.safe_load(f)
        model = d.get("model")
        if isinstance(model, str) and not os.path.isabs(model):
            d["model"] = os.path.join(os.path.dirname(self.path), model)
        return d

    def with_(self, changes=None, **keys):
        """A new scene: this one with some keys changed.

        Mappings merge key by key (``initial={"theta": 0.7}`` changes theta alone), None removes
        a key, other values replace; a dotted key changes one entry (``{"time.end": 5}``).

        Parameters
        ----------
        changes : dict, optional
            Keys to change (dotted keys allowed).
        **keys
            More keys to change, applied over ``changes``.

        Returns
        -------
        Scene
            The changed scene, read and checked anew (named ``<scene>`` in errors).

        Raises
        ------
        InputError
            When the changed scene is rejected.

        Examples
        --------
        >>> s2 = s.with_(initial={"theta": 0.7}, integrator={"method": "taylor", "rtol": 1e-12})
        >>> s3 = s.with_(integrator={"method": "auto", "error": 1e-8})  # rotgen tune's choice
        """
        change = _merge(dict(changes or {}), keys)
        merged = _merge(self.to_dict(), change)
        ig = merged.get("integrator")
        if isinstance(ig, Mapping) and isinstance(change.get("integrator"), Mapping):
            # method auto takes only its error; another method has no error
            if ig.get("method") == "auto":
                merged["integrator"] = dict(change["integrator"])
            else:
                ig.pop("error", None)
        return Scene(merged)

    def __repr__(self):
        where = "from a dict or text" if self.yaml_text is not None else repr(self.path)
        return (f"<rotgen.Scene {where}: model {self.model}, {self.form} form, {self.method}, "
                f"t {self.t_start:g}..{self.t_end:g} ({self.samples} samples), "
                f"record {self.record}>")


def source_of(scene):
    """(path, text) for the compiled core: a Scene, a path, or a dict."""
    if isinstance(scene, Scene):
        return scene.path, scene._text()
    if isinstance(scene, Mapping):
        s = Scene(scene)
        return s.path, s._text()
    return os.fspath(scene), ""
