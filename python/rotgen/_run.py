"""rotgen.simulate and rotgen.sweep: runs through the one engine, results as NumPy arrays."""

import io

import numpy as np

from . import _rotgen
from ._errors import RunError
from ._scene import source_of


def _pandas():
    try:
        import pandas
    except ImportError:
        return None
    return pandas


class SimulateResult:
    """The samples of one run (what ``rotgen simulate`` writes to its CSV).

    Made by :func:`simulate` (and held by :class:`RunError`), not by user code.

    Parameters
    ----------
    d : dict
        What the compiled core returns: ``rows``, ``columns``, ``events``, ``summary``, ``ok``,
        ``message``.

    Attributes
    ----------
    t : ndarray
        The sample times, shape (n,).
    y : ndarray
        One row per sample, one column per recorded quantity, in the CSV's order (``columns``),
        shape (n, k). ``t`` and ``y`` are views of one array the engine's rows were copied into
        once.
    columns : list of str
        The names of y's columns (the CSV header after ``t``).
    events : list of tuple
        The scene's events in time order, each a tuple (name, time, phase, the recorded columns
        there as an ndarray); phase is ``"before"`` or ``"after"`` for the two rows of an event
        that acts (impulse, set), ``""`` otherwise.
    summary : dict
        ``model``, ``form``, ``state_size``, ``method``, ``steps`` (accepted), ``rejected``,
        ``rhs_evals``, ``jac_evals``, ``factorisations``, ``drifts`` (invariant name to
        ``max |v(t) - v(t0)|``), ``chart`` (the chart switch, if any), ``integrate_seconds``,
        ``kernels_cached``, ``t_reached`` (the end time, a terminal event's time, or where a
        run that stopped got to: past its last sample when it stopped between samples).
    success : bool
        Whether the run reached the end time (or a terminal event).
    message : str
        Why not (the CLI's line), when not.
    sensitivity_keys : list of str
        The scene's ``sensitivities`` keys in order (``y0.<state>`` for ``all_initial``); empty
        without them.
    sensitivities : ndarray or None
        d(column)/d(key), shape (samples, columns, keys), every recorded column (the attitude
        and the body form's angles, rates and momenta too); None without sensitivities.
    state_sensitivities : ndarray or None
        S = dy/d(key) of the run form's state y, shape (samples, n, keys); None without them.
    stm : ndarray or None
        The state-transition matrix dy(t)/dy(t0), shape (samples, n, n), with
        ``sensitivities: {keys: all_initial}``; else None.
    """

    def __init__(self, d):
        rows = d["rows"]
        self.t = rows[:, 0]
        self.y = rows[:, 1:]
        self.columns = list(d["columns"])
        self.events = [(name, t, phase, values) for name, t, phase, values in d["events"]]
        self.summary = d["summary"]
        self.success = d["ok"]
        self.message = d["message"]
        self.sensitivity_keys = list(d["sensitivity_keys"])
        self._sensitivity_columns = list(d["sensitivity_columns"])
        self._sensitivity_values = d["sensitivity_values"]
        self.sensitivities = None
        self.state_sensitivities = None
        self.stm = None
        if self.sensitivity_keys:
            self._set_sensitivities(d["state_sensitivities"])

    def _set_sensitivities(self, state):
        k = len(self.sensitivity_keys)
        self.sensitivities = np.full((len(self.t), len(self.columns), k), np.nan)
        for m, name in enumerate(self._sensitivity_columns):
            column, key = name[2:].split(")/d(", 1)
            c, j = self.columns.index(column), self.sensitivity_keys.index(key[:-1])
            self.sensitivities[:, c, j] = self._sensitivity_values[:, m]
        self.state_sensitivities = state
        if all(key.startswith("y0.") for key in self.sensitivity_keys) and state.shape[1] == k:
            self.stm = state

    def __getitem__(self, column):
        """The samples of one recorded column, by name (``r["theta"]``).

        Parameters
        ----------
        column : str
            One of :attr:`columns`.

        Returns
        -------
        ndarray
            The column of :attr:`y`, shape (n,) (a view).

        Raises
        ------
        ValueError
            When no column has that name.
        """
        return self.y[:, self.columns.index(column)]

    def to_pandas(self):
        """The samples as a DataFrame (needs pandas).

        Returns
        -------
        pandas.DataFrame
            Indexed by ``t``, one column per recorded quantity (:attr:`columns`), then the
            ``d(<column>)/d(<key>)`` columns of the CSV with sensitivities.

        Raises
        ------
        ImportError
            Without pandas (Debian: python3-pandas).
        """
        pd = _pandas()
        if pd is None:
            raise ImportError("to_pandas() needs pandas (Debian: python3-pandas)")
        frame = pd.DataFrame(self.y, index=pd.Index(self.t, name="t"), columns=self.columns)
        for m, name in enumerate(self._sensitivity_columns):
            frame[name] = self._sensitivity_values[:, m]
        return frame

    def events_to_pandas(self):
        """The events as a DataFrame (needs pandas).

        Returns
        -------
        pandas.DataFrame
            One row per event: ``event``, ``t``, ``phase`` and the recorded columns (the rows of
            ``rotgen simulate``'s events CSV).

        Raises
        ------
        ImportError
            Without pandas (Debian: python3-pandas).
        """
        pd = _pandas()
        if pd is None:
            raise ImportError("events_to_pandas() needs pandas (Debian: python3-pandas)")
        rows = [[name, t, phase, *values] for name, t, phase, values in self.events]
        return pd.DataFrame(rows, columns=["event", "t", "phase", *self.columns])

    def __repr__(self):
        s = self.summary
        state = "ok" if self.success else "stopped: " + self.message
        return (f"<rotgen.SimulateResult {s['model']} ({s['form']} form, {s['method']}): "
                f"{len(self.t)} samples x {len(self.columns)} columns {self.columns}, "
                f"{len(self.events)} events, {s['steps']} steps; {state}>")


def simulate(scene):
    """Integrate a scene, as ``rotgen simulate`` does, and return its samples.

    Nothing is written to disk (but the compiled kernels, to rotgen's cache). The GIL is
    released while the run integrates; Ctrl-C stops it (KeyboardInterrupt).

    Parameters
    ----------
    scene : Scene, str, os.PathLike or dict
        The scene (or its file, or a dict with a scene's keys).

    Returns
    -------
    SimulateResult
        The samples, the events and the run's summary.

    Raises
    ------
    InputError
        The scene is rejected (the CLI's exit status 2).
    RunError
        The run started but could not finish; ``e.result`` holds the samples so far.

    Examples
    --------
    >>> r = rotgen.simulate("models/scenes/heavy_top_nutation.yaml")
    >>> r.t.shape == r["theta"].shape
    True
    """
    path, text = source_of(scene)
    result = SimulateResult(_rotgen.simulate(path, text))
    if not result.success:
        raise RunError(result.message, result)
    return result


def _number(x):
    """As --vary writes it: an int as an int, a float as the shortest text that reads back."""
    if isinstance(x, str):
        return x
    if isinstance(x, int) and not isinstance(x, bool):
        return str(x)
    if hasattr(x, "item"):  # NumPy scalars
        return _number(x.item())
    return repr(float(x))


def _vary_entry(key, value):
    """A ``vary=`` entry as the CLI's ``--vary KEY=...``."""
    if isinstance(value, str):
        return f"{key}={value}"
    if isinstance(value, tuple):
        if len(value) == 3:
            start, stop, count = value
            return f"{key}={_number(start)}:{_number(stop)}:{int(count)}"
        if len(value) == 2:
            return f"{key}={_number(value[0])}:{_number(value[1])}"
        raise ValueError(f"vary[{key!r}]: a tuple is (from, to, count) or, in random mode, "
                         f"(from, to); a list gives the values")
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, list):
        return f"{key}=" + ",".join(_number(v) for v in value)
    return f"{key}={_number(value)}"


def _summary_rows(text):
    """summary.csv as a list of dicts (without pandas): numbers as float (int for member, steps,
    rhs_evals), an empty cell as NaN."""
    import csv

    rows = []
    for row in csv.DictReader(io.StringIO(text)):
        out = {}
        for k, v in row.items():
            if k == "status":
                out[k] = v
            elif k in ("member", "steps", "rhs_evals"):
                out[k] = int(v)
            else:
                out[k] = float(v) if v != "" else float("nan")
        rows.append(out)
    return rows


class SweepResult:
    """The members of an ensemble (what ``rotgen sweep`` writes).

    Made by :func:`sweep`, not by user code.

    Parameters
    ----------
    d : dict
        What the compiled core returns: ``summary_csv``, ``trajectories``, ``columns``, ``keys``,
        ``info``.

    Attributes
    ----------
    summary : pandas.DataFrame or list of dict
        summary.csv's table, its columns in order (``member`` a column, default index): the varied
        keys, ``final.t``, ``final.<column>``, ``event.<name>``, ``drift.<invariant>``, ``steps``,
        ``rhs_evals``, ``status``. A list of dicts when pandas is absent.
    summary_csv : str
        The text of summary.csv, the same bytes as the CLI's.
    trajectories : ndarray or None
        Every member's samples, shape (members, samples, len(columns)): ``t``, the recorded
        columns, then with the scene's sensitivities every ``d(<column>)/d(<key>)`` (as
        trajectories.h5 holds them); NaN past the last sample a member reached. None with
        ``trajectories=False``.
    columns : list of str
        The names along the last axis of ``trajectories`` (``t`` first).
    keys : list of str
        The varied keys, in the plan's order.
    seconds : float
        Wall time running the members (the CLI's "running the members").
    threads : int
        The threads that ran the members.
    lanes : int
        Members per SIMD batch (1: one at a time).
    members : int
        The number of members.
    failed : int
        The members whose status is not ``ok``.
    info : dict
        ``members``, ``failed``, ``in_lanes`` (members that ran in a batch of lanes), ``steps``,
        ``rhs_evals`` (all members'), ``seconds``, ``threads``, ``lanes``, ``arch`` (the lanes'
        SIMD target): the CLI's summary lines.
    """

    def __init__(self, d):
        self.summary_csv = d["summary_csv"]
        pd = _pandas()
        if pd is not None:
            self.summary = pd.read_csv(io.StringIO(self.summary_csv), float_precision="round_trip",
                                       keep_default_na=False, na_values=[""])
            statuses = list(self.summary["status"])
        else:
            self.summary = _summary_rows(self.summary_csv)
            statuses = [row["status"] for row in self.summary]
        self.trajectories = d["trajectories"]
        self.columns = list(d["columns"])
        self.keys = list(d["keys"])
        self.info = d["info"]
        self.seconds = self.info["seconds"]
        self.threads = self.info["threads"]
        self.lanes = self.info["lanes"]
        self.members = len(statuses)
        self.failed = sum(1 for s in statuses if s != "ok")

    def __repr__(self):
        shape = "no trajectories" if self.trajectories is None else \
            f"trajectories {self.trajectories.shape}"
        return (f"<rotgen.SweepResult {self.members} members over {self.keys}, "
                f"{self.failed} failed; {shape}; {self.seconds:.3g} s on {self.threads} threads"
                f"{'' if self.lanes == 1 else f', lanes of {self.lanes}'}>")


def sweep(scene, vary=None, threads=0, lanes=1, trajectories=True):
    """Run an ensemble of members of one scene in this process, as ``rotgen sweep`` does.

    Parameters
    ----------
    scene : Scene, str, os.PathLike or dict
        The scene; without ``vary`` its own ``sweep:`` section gives the members.
    vary : dict, optional
        Keys (``initial.<name>``, ``parameters.<name>``) to values: a tuple
        ``(from, to, count)`` (or ``(from, to)`` in random mode), a list or array of values, or
        the CLI's text (``"0.1:1.5:64"``). Entries add to the scene's ``sweep:`` keys or replace
        them, as ``--vary`` does.
    threads : int
        Threads running members (0: every core).
    lanes : int
        Members per SIMD batch (> 1: ``--lanes``). The scene's method must be ``rk4``,
        ``dop853`` or ``taylor`` (else InputError); each lane watches the scene's events on its
        own state. A member a batch cannot carry (a chart switch, a failure) runs alone, as
        without lanes.
    trajectories : bool
        Keep every member's samples (``.trajectories``).

    Returns
    -------
    SweepResult
        A member that fails does not stop the others: its ``status`` says why (the CLI's exit
        status 3 is ``result.failed > 0``).

    Raises
    ------
    InputError
        The scene or a ``vary`` entry is rejected.
    ValueError
        A ``vary`` tuple of other than two or three entries.

    Examples
    --------
    >>> s = rotgen.sweep("models/scenes/heavy_top_nutation.yaml",
    ...                  vary={"initial.theta": (0.2, 1.2, 8)}, threads=2)
    >>> s.members
    8
    """
    path, text = source_of(scene)
    entries = [_vary_entry(k, v) for k, v in (vary or {}).items()]
    d = _rotgen.sweep(path, text, entries, int(threads or 0), int(lanes), bool(trajectories))
    return SweepResult(d)
