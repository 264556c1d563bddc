"""Cyclic garbage collection paused while odgen builds its long-lived objects.

Reading, linting and generating allocate many objects that live until the command ends and
form no reference cycles; full collections would only traverse them again and again (a third
of the time of a 16000-object generation, and growing faster than the input).
"""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def no_cyclic_gc() -> Iterator[None]:
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            _promote()
            gc.enable()


def _promote() -> None:
    """Move every tracked object to the oldest generation without traversing it (gc.freeze, then
    gc.unfreeze): otherwise the collection that resumes would traverse all that the pause allocated
    at once, and again when it moves on (10 ms at 4000 objects), and find nothing to free. Not when
    objects are frozen already: whoever froze them meant them to stay so."""
    if gc.get_freeze_count() == 0:
        gc.freeze()
        gc.unfreeze()
