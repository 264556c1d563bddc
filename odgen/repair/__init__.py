"""Repairs of a description, as ruff fixes lint findings: the findings say what is wrong, a repair
changes the model (and says which lines of the file to change) so that it no longer is.

The floor between formats and lint: it takes a model and the findings the reader and the lint
passes reported on it, and returns a new model and the list of repairs; the loaded model is never
changed. Callers lint the new model again (`odgen generate --fix`, `odgen fix`). A repair is safe
when its meaning is certain and unsafe when it guesses or lets the node accept more than the file
says (the catalogue's `repair` text says which); nothing is repaired unless asked, and no repair
looks at a vendor or a file name.
"""

from __future__ import annotations

from .apply import Edit, apply_edits
from .fixes import REPAIRABLE, Repair, blocking_marks, repair_model, would_repair

__all__ = ["REPAIRABLE", "Edit", "Repair", "apply_edits", "blocking_marks", "repair_model", "would_repair"]
