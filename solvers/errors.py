"""Errors the Python layer raises; each message is one line a person can act on."""


class InputError(ValueError):
    """Bad input: unknown case or parameter, non-finite number, a body that cannot exist.

    `option`: the name of the run option that accepts such input anyway (e.g.
    "allow_any_inertia"), for an interface that has it to name in its own words (the CLI's
    --allow-any-inertia); the message itself names no interface's flag, since the web page
    shows it to a reader."""

    def __init__(self, message: str = "", option: str | None = None):
        super().__init__(message)
        self.option = option
