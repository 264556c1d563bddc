"""What every lint pass takes: the options of a lint run, and the shape of a pass."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ...diagnostics import Diagnostics
from ...model import ObjectDictionary


@dataclass(frozen=True)
class LintOptions:
    node_id: int | None = None  # check $NODEID values for this node-id only
    can_fd: bool = False  # PDO payload up to 512 bits instead of 64


LintPass = Callable[[ObjectDictionary, Diagnostics, LintOptions], None]
