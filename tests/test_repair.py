"""Repairs of descriptions (odgen/repair) and the readers' fixes they came with: each from a minimal fixture."""

from __future__ import annotations

from .conftest import FIXTURES, expectations, lint, rendered

REPAIR = FIXTURES / "repair"


def test_sub0_is_checked_on_the_value_in_force() -> None:
    """A DCF's ParameterValue, not a stale DefaultValue, is what OBJ011 compares with the sub-indices."""
    fixture = REPAIR / "sub0-in-force.dcf"
    assert rendered(lint(fixture)) == expectations(fixture)
    assert expectations(fixture)
