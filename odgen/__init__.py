"""odgen: CANopen device descriptions (EDS/DCF/XDD/XDC) to lint findings and C."""

__version__ = "0.1.0"
