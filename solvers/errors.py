"""Errors the Python layer raises; each message is one line a person can act on."""


class InputError(ValueError):
    """Bad input: unknown case or parameter, non-finite number, a body that cannot exist."""
