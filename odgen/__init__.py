"""odgen: CANopen device descriptions (EDS/DCF/XDD/XDC) to lint findings and C."""

# The one place the version is written: pyproject.toml reads it from here (tool.setuptools.dynamic),
# and CHANGELOG.md names each released one (docs/compatibility.md says what a number promises).
__version__ = "0.1.0"
