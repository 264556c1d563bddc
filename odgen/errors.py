"""The tool's own error type: anything raised as OdgenError is a user-facing message."""


class OdgenError(Exception):
    """A problem the user can fix (bad arguments, unreadable file); exit code 2."""

    exit_code = 2
