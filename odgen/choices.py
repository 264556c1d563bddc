"""The choices the command line offers, defined once.

They live here, on the ground floor, rather than in the modules that act on them, so that
`odgen --help` and the parser of one command start without importing jinja2, lxml or
canopen (a pre-commit hook pays the start-up on every commit). The modules that implement
each choice import their list from here.
"""

from __future__ import annotations

LOOKUPS = ("switch", "bsearch", "hash")  # index lookups of the generated dictionary
REPORT_FORMATS = ("github", "json", "sarif", "text")  # lint reports
INPUT_FORMATS = ("eds", "dcf", "xdd", "xdc")  # --input-format
DIFF_FORMATS = ("json", "sarif", "text")  # odgen diff reports
PAGE_FORMATS = ("html", "md")  # odgen report pages
DIFF_FAIL_ON = ("breaking", "stored", "compatible", "none")  # odgen diff --fail-on, most severe first
# CiA 401 profile limits: digital channels in bits, analog channels, analog widths in bits
DS401_MAX_DIGITAL, DS401_MAX_ANALOG, DS401_WIDTHS, DS401_NAME = 2032, 254, (8, 16, 32), "DS401 I/O module"
