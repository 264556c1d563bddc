"""The runtime compiled to what a dictionary uses: the ODG_CFG_* switches of NAME_config.h.

Each switch turns a feature of runtime/odg.c on when the dictionary has something that needs it;
the rest is left out of the build (64-bit arithmetic on a 32-bit core, string and domain
handling, hooks, limit checks, persistence groups, the 0x1010/0x1011 commands, the lookup modes
the dictionary does not use, and in runtime/odg_persist.c the migration of strings and domains
the "ODG1" path of groups without migration, and the boot migration when no group migrates).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the view-model calls runtime_config() to finish a view
    from .viewmodel import DictView

WIDE = {0x0C, 0x0D, 0x11, 0x12, 0x13, 0x14, 0x15, 0x18, 0x19, 0x1A, 0x1B}  # wider than 32 bits
STRINGS = {0x09, 0x0A}
UNICODE = 0x0B
DOMAIN = 0x0F
STREAMS = {*STRINGS, UNICODE, DOMAIN}
REALS = {0x08, 0x11}


@dataclass
class Switch:
    macro: str
    what: str
    on: bool
    why: str  # the first entry that needs it, or ""


def _first(view: DictView, positions: list[int]) -> str:
    """'0xIIIIsubS' of the first sub-entry position."""
    if not positions:
        return ""
    pos = min(positions)
    entry = next(e for e in view.entries if e.first <= pos < e.first + e.count)
    return f"0x{entry.index:04X}sub{view.subs[pos].sub}"


def runtime_config(view: DictView) -> list[Switch]:
    subs = list(enumerate(view.subs))
    limited = {lim.sub_pos for lim in view.limits}
    persisted = [p for p, s in subs if "ODG_S_PERSIST" in s.storage]
    migration = view.persist is not None and view.persist.migration
    needs = [
        ("ODG_CFG_INT64", "types wider than 32 bits", [p for p, s in subs if s.type in WIDE]),
        ("ODG_CFG_STRINGS", "VISIBLE_STRING / OCTET_STRING", [p for p, s in subs if s.type in STRINGS]),
        ("ODG_CFG_UNICODE", "UNICODE_STRING", [p for p, s in subs if s.type == UNICODE]),
        ("ODG_CFG_DOMAINS", "DOMAIN", [p for p, s in subs if s.type == DOMAIN]),
        ("ODG_CFG_HOOKS", "hooks", [h.sub_pos for h in view.hooks]),
        ("ODG_CFG_LIMITS", "limits on integers", [p for p in limited if view.subs[p].type not in REALS]),
        ("ODG_CFG_REAL_LIMITS", "limits on REAL32 / REAL64", [p for p in limited if view.subs[p].type in REALS]),
        ("ODG_CFG_GROUPS", "persistence groups", [p for p, s in subs if "ODG_S_PERSIST" in s.storage]),
        ("ODG_CFG_STORE", "0x1010 / 0x1011 commands", [p for p, s in subs if "ODG_S_STORE" in s.storage]),
        ("ODG_CFG_PACKED", "ARRAYs and RECORDs whose elements share one descriptor",
         [e.first + 1 for e in view.entries if "ODG_E_PACKED" in e.code]),
        ("ODG_CFG_PERSIST_STREAMS", "strings or domains in a migrated persistence group",
         [p for p in persisted if view.subs[p].type in STREAMS] if migration else []),
        ("ODG_CFG_PERSIST_STATUS", "boot status object",
         [p for e in view.entries if view.persist is not None and e.index == view.persist.status_object
          for p in range(e.first, e.first + e.count)]),
        ("ODG_CFG_PERSIST_ODG1", "persistence groups without migration", persisted[:1] if not migration else []),
        ("ODG_CFG_PERSIST_MIGRATION", "persistence groups migrated at boot", persisted[:1] if migration else []),
    ]
    switches = [Switch(macro, what, bool(where), _first(view, where)) for macro, what, where in needs]
    for switch in switches:  # a packed descriptor's sub is the last element's: name them all
        if switch.macro == "ODG_CFG_PACKED" and switch.on:
            entry = next(e for e in view.entries if "ODG_E_PACKED" in e.code)
            switch.why = f"0x{entry.index:04X}sub1..{view.subs[entry.first + 1].sub}"
    hashed = view.lookup == "hash"
    return switches + [Switch("ODG_CFG_HASH", "lookup by perfect hash", hashed, "--lookup hash" if hashed else ""),
                       Switch("ODG_CFG_UNHASHED", "lookup by generated find or binary search", not hashed,
                              f"--lookup {view.lookup}" if not hashed else "")]
