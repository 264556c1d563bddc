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
            gc.enable()
