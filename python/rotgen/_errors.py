"""The exceptions of rotgen: user errors and runs that could not finish."""


class InputError(ValueError):
    """A model, scene or argument that rotgen rejects (the CLI's exit status 2).

    ``str(e)`` is the CLI's one-line diagnostic without its ``rotgen: error: `` prefix,
    ``FILE:LINE:COL: problem``.

    Attributes
    ----------
    file : str
        The file (or ``<scene>``, ``<model>`` for a scene or model given as a dict or text, or
        ``rotgen sweep --vary ...`` for a ``vary=`` entry).
    line, column : int or None
        1-based position in that file or text; None where rotgen does not know it.
    """

    def __init__(self, message, file="", line=None, column=None):
        super().__init__(message)
        self.file = file
        self.line = line
        self.column = column


class RunError(RuntimeError):
    """A run that started but could not finish (the CLI's exit status 3).

    ``str(e)`` is the CLI's line (``FILE:LINE:COL: the run stopped at t = ... of ...: why``).

    Attributes
    ----------
    result : SimulateResult
        The samples computed until it stopped (``result.success`` is False).
    """

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result
