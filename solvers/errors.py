"""Errors the Python layer raises; each message is one line a person can act on."""


class InputError(ValueError):
    """Bad input: unknown case or parameter, non-finite number, a body that cannot exist.

    Raised before anything runs, with a one-line message that names the offending input
    and what is accepted. A subclass of ValueError.

    Parameters
    ----------
    message : str
        What is wrong and what would be accepted.
    option : str or None, default None
        See `option` below.

    Attributes
    ----------
    option : str or None
        The name of the run option that accepts such input anyway (e.g.
        "allow_any_inertia"), for an interface that has it to name in its own words (the
        CLI's --allow-any-inertia); the message itself names no interface's flag, since the
        web page shows it to a reader. None when no option would accept it.

    Examples
    --------
    >>> import solvers
    >>> spec = solvers.cases()["plane/chaplygin-ball"]
    >>> body = {**spec.example, "I3": 5.0}      # I3 > I1 + I2: no rigid body
    >>> try:
    ...     solvers.simulate(spec.id, body, spec.state, t_end=1.0)
    ... except solvers.InputError as e:
    ...     print(e, "|", e.option)
    I3 = 5.0 > I1 + I2 = 3.0: principal moments of a body satisfy the triangle inequality
    | allow_any_inertia
    """

    def __init__(self, message: str = "", option: str | None = None):
        super().__init__(message)
        self.option = option
