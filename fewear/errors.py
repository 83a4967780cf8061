"""Errors that the command line reports as a message (no traceback, exit status 2)."""


class FewearInputError(ValueError):
    """Bad input from the user: a config value, a data file, an argument or an output folder.

    The message names the bad value and says what is allowed.
    """
