"""LST: object lists and index ranges."""

from __future__ import annotations

from .rule import E, W, define

LST001 = define(
    "LST001", E, "SupportedObjects missing or not a number", ref="CiA 306 table row L1",
    why="Each object list starts with `SupportedObjects=N`, the number of entries 1..N that follow. "
    "Without it readers do not know how many entries to read (Vector: \"SupportedObjects can not be "
    "found\").",
    example="[OptionalObjects]\n1=0x1017",
    fix="Add `SupportedObjects=<number of entries>`.",
    blocking="The C is built from the object sections, not from the object lists.")

LST002 = define(
    "LST002", E, "object list entry missing", ref="CiA 306 table row L1",
    why="An object list with SupportedObjects=N has the keys 1..N. Readers that loop over 1..N "
    "stop at the first gap or fail (Lely: \"entry missing\").",
    example="[OptionalObjects]\nSupportedObjects=3\n1=0x1008\n2=0x1017",
    fix="Add the missing entries or lower SupportedObjects.",
    blocking="The C is built from the object sections, not from the object lists.")

LST003 = define(
    "LST003", E, "object list entry beyond SupportedObjects", ref="CiA 306 table row L1",
    why="Keys other than 1..SupportedObjects are not read by tools that loop over 1..N, so the "
    "object is invisible to them (Lely: \"too many entries\").",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x1008\n2=0x1017",
    fix="Raise SupportedObjects to the number of entries, or renumber them 1..N.",
    blocking="The C is built from the object sections, not from the object lists.")

LST004 = define(
    "LST004", E, "object list entry is not an index", ref="CiA 306 table row L2",
    why="Each entry names an object index as a number (`0x1017`); other text cannot be resolved.",
    example="[OptionalObjects]\nSupportedObjects=1\n1=Heartbeat",
    fix="Write the index as a hex number, e.g. `1=0x1017`.",
    blocking="The C is built from the object sections, not from the object lists.")

LST005 = define(
    "LST005", E, "listed object has no section", ref="CiA 306 table row L2",
    why="Every index in an object list needs its `[XXXX]` section; Lely stops with \"object not "
    "found\", other tools silently drop it.",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x1017\n(no [1017] section)",
    fix="Add the object section, or remove the entry.",
    blocking="The C is built from the object sections, not from the object lists; a listed object without a section"
    " is not in it, as the file describes no value for it.")

LST006 = define(
    "LST006", E, "object listed more than once", ref="CiA 306 table row L2",
    why="Each object appears in exactly one object list, once. Repeats inflate SupportedObjects and "
    "make tools create the object twice.",
    example="[OptionalObjects]\nSupportedObjects=2\n1=0x1017\n2=0x1017",
    fix="Remove the repeated entry and renumber the list.",
    blocking="The C is built from the object sections, not from the object lists.")

LST007 = define(
    "LST007", E, "object section not listed", ref="CiA 306 table row L2",
    why="Tools that read objects through the lists (python canopen, CANopenEditor, Lely) never see an "
    "object that has a section but no list entry.",
    example="[2000]\nParameterName=Speed\n(0x2000 in no [...Objects] list)",
    fix="Add the index to [ManufacturerObjects] (0x2000-0x5FFF) or [OptionalObjects], and update "
    "SupportedObjects.",
    blocking="The C is built from the object sections, not from the object lists.")

LST008 = define(
    "LST008", E, "object in the wrong list", ref="CiA 306 table row L3",
    why="[MandatoryObjects] holds 0x1000, 0x1001 and 0x1018; [ManufacturerObjects] holds exactly "
    "the manufacturer range 0x2000-0x5FFF; [OptionalObjects] everything else. Lely refuses other "
    "placements.",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x2000",
    fix="Move the entry to the list for its index range.",
    blocking="The C is built from the object sections, not from the object lists.")

LST009 = define(
    "LST009", W, "mandatory object listed as optional", ref="CiA 306 table row L3",
    why="CiA 301 v4 makes 0x1000, 0x1001 and 0x1018 mandatory; files written for older versions "
    "list 0x1018 under [OptionalObjects].",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x1018",
    fix="Move the entry to [MandatoryObjects].")

LST010 = define(
    "LST010", W, "SupportedObjects or entry key not decimal", ref="CiA 306 table row L1",
    why="Object list counts and keys are decimal numbers. Lely's dcfchk refuses `SupportedObjects=0x03` "
    "(the Lely-ready copies of vendor files in the wild have it rewritten in decimal).",
    example="[MandatoryObjects]\nSupportedObjects=0x03",
    fix="Write the number in decimal: `SupportedObjects=3`.")

LST011 = define(
    "LST011", E, "object index in a reserved range",
    ref="CiA 306 table row L4 / CiA 301 index ranges",
    why="CiA 301 reserves index 0x0000 and 0x0260-0x0FFF; no device may define objects there. "
    "(0x0001-0x025F data types, 0x1000-0x1FFF communication, 0x2000-0x5FFF manufacturer, "
    "0x6000-0x9FFF device profile, 0xA000-0xBFFF interface profile.)",
    example="[0800]\nParameterName=Misplaced",
    fix="Move the object to the manufacturer range 0x2000-0x5FFF.",
    blocking="The C serves the object at the index the file gives; only the index range is reserved.")

LST012 = define(
    "LST012", E, "object index in the reserved range 0xC000-0xFFFF",
    ref="CiA 306 table row L4 / CiA 301 index ranges",
    why="CiA 301 reserves 0xC000-0xFFFF; no device may define objects there (CANopenNode's and Lely's "
    "tools refuse them), and they may collide with later profiles. The object itself is well "
    "defined, so generation goes on.",
    example="[C000]\nParameterName=Vendor block",
    fix="Move the object to the manufacturer range 0x2000-0x5FFF.",
    blocking="The C serves the object at the index the file gives; only the index range is reserved.")
