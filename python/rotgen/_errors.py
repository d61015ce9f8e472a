"""The exceptions of rotgen: user errors and runs that could not finish."""


class InputError(ValueError):
    r"""A model, scene or argument that rotgen rejects (the CLI's exit status 2).

    ``str(e)`` is the CLI's one-line diagnostic without its ``rotgen: error:`` prefix,
    ``FILE:LINE:COL: problem``. rotgen raises it; user code has no need to.

    Parameters
    ----------
    message : str
        The diagnostic, ``FILE:LINE:COL: problem``.
    file : str, optional
        The file it names (see :attr:`file`).
    line : int or None, optional
        1-based line in that file or text.
    column : int or None, optional
        1-based column in that file or text.

    Attributes
    ----------
    file : str
        The file (or ``<scene>``, ``<model>`` for a scene or model given as a dict or text, or
        ``rotgen sweep --vary ...`` for a ``vary=`` entry).
    line : int or None
        1-based line in that file or text; None where rotgen does not know it.
    column : int or None
        1-based column in that line; None where rotgen does not know it.

    Examples
    --------
    >>> try:
    ...     rotgen.Model(yaml_text="name: top\ninertia: [1, 2]\n")
    ... except rotgen.InputError as e:
    ...     print(e.file, e.line)
    <model> 2
    """

    def __init__(self, message, file="", line=None, column=None):
        super().__init__(message)
        self.file = file
        self.line = line
        self.column = column


class RunError(RuntimeError):
    """A run that started but could not finish (the CLI's exit status 3).

    ``str(e)`` is the CLI's line (``FILE:LINE:COL: the run stopped at t = ... of ...: why``).
    :func:`simulate` raises it; user code has no need to.

    Parameters
    ----------
    message : str
        The CLI's line.
    result : SimulateResult
        The samples computed until the run stopped.

    Attributes
    ----------
    result : SimulateResult
        The samples computed until it stopped (``result.success`` is False).
    """

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result
