"""The rule catalogue: every finding odgen reports names one of these rules.

The ground floor of the package: readers (odgen.formats), rule checks
(odgen.lint.passes), the generator and the reporters import it; it imports nothing
of odgen. Rules are module constants (`from odgen.catalogue.pdo import PDO001`),
so a misspelt id fails at import. `RULES` maps ids to rules for the reporters;
`lookup` and `is_selector` serve the command line.
"""

from __future__ import annotations

from types import ModuleType

from . import comm, gen, header, lists, network, objects, pdo, syntax, xml
from .rule import CAP, Rule, Severity

FAMILIES: dict[str, tuple[str, ModuleType]] = {
    "SYN": ("File syntax and value notation (reported while reading EDS/DCF)", syntax),
    "XML": ("XDD/XDC reading (CiA 311)", xml),
    "HDR": ("Header sections: [FileInfo], [DeviceInfo], [DummyUsage], [Comments]", header),
    "LST": ("Object lists and index ranges", lists),
    "OBJ": ("Objects and sub-objects", objects),
    "PDO": ("PDO mapping", pdo),
    "COM": ("Communication profile (CiA 301) semantics", comm),
    "GEN": ("Generation: options file, placement, C names (odgen generate)", gen),
    "NET": ("Network of nodes: PDO producers, consumers and COB-IDs (odgen lint --network)", network),
}


def _collect() -> dict[str, Rule]:
    rules: dict[str, Rule] = {}
    for prefix, (_, module) in FAMILIES.items():
        for name, value in vars(module).items():
            if isinstance(value, Rule):
                if name != value.id or not value.id.startswith(prefix) or value.id in rules:
                    raise ValueError(f"rule {value.id} defined as {module.__name__}.{name}")
                rules[value.id] = value
    return dict(sorted(rules.items()))


RULES: dict[str, Rule] = _collect()


def lookup(rule_id: str) -> Rule:
    """The rule with this id; KeyError names the id when there is none."""
    return RULES[rule_id.strip().upper()]


def is_selector(text: str) -> bool:
    """Whether `text` is a rule id or an id prefix (`PDO`, `SYN01`) that names at least one rule."""
    key = text.strip().upper()
    return bool(key) and any(rule_id.startswith(key) for rule_id in RULES)


def family(rule: Rule) -> str:
    return rule.id.rstrip("0123456789")


__all__ = ["CAP", "FAMILIES", "RULES", "Rule", "Severity", "family", "is_selector", "lookup"]
