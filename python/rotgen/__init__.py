"""rotgen from Python: rigid-body rotational dynamics, derived symbolically, run as compiled code.

The module calls the stages the ``rotgen`` command calls (no second engine):

- :class:`Model` -- a model file: ``.parameters``, ``.equations(format=)``, ``.inertia()``;
- :class:`Scene` -- a scene file or dict: ``.with_(...)`` for a changed copy;
- :func:`simulate` -- one run, a :class:`SimulateResult`: ``.t``, ``.y``, ``.columns``,
  ``.to_pandas()``, ``.events``, ``.summary``;
- :func:`sweep` -- an ensemble on threads and SIMD lanes, a :class:`SweepResult`: ``.summary``
  (summary.csv as a DataFrame), ``.trajectories``;
- :func:`emit` -- the generated C++ header, as ``rotgen emit``;
- :func:`fit` -- a scene's keys fitted to measurements, a :class:`FitResult`: ``.values``,
  ``.stderr``, ``.covariance``, ``.correlation``, ``.scene``, ``.residuals``, ``.converged``;
- :class:`InputError` (a ValueError with ``file``, ``line``, ``column``) and :class:`RunError`
  (with the partial ``result``);
- ``__version__`` -- the version of the compiled core (the CLI's).
"""

from ._errors import InputError, RunError
from ._fit import FitResult, fit
from ._model import Model, emit
from ._run import SimulateResult, SweepResult, simulate, sweep
from ._scene import Scene
from ._rotgen import version as __version__

__all__ = ["InputError", "RunError", "Model", "Scene", "SimulateResult", "SweepResult",
           "FitResult", "emit", "fit", "simulate", "sweep", "__version__"]
