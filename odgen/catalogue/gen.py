"""GEN: findings of the generator (options file, placement, C names)."""

from __future__ import annotations

from .rule import E, INFO, W, define

GEN001 = define(
    "GEN001", E, "invalid options file", ref="odgen options",
    why="The options file decides placement, hooks and capacities; a key or value odgen does not "
    "understand would silently change the generated dictionary.",
    example='[[entry]]\nmatch = "0x2000"\nstorag = "rom"',
    fix="Use the keys match, storage, hooks, function, capacity (see docs/generate.md).",
    blocks=True,
    blocking="The options file says how to build the C; an invalid one leaves that unknown.",
    no_repair="The options file is the user's own choice, not the description's.")

GEN002 = define(
    "GEN002", W, "options pattern matches nothing", ref="odgen options",
    why="A pattern that selects no entry is usually a typo or a stale line after the description changed.",
    example='[[entry]]\nmatch = "0x2100"   # the file has no 0x2100\nstorage = "ram"',
    fix="Correct the index/sub pattern or remove the entry.")

GEN003 = define(
    "GEN003", E, "impossible storage class", ref="odgen placement",
    why="A `rom` value lives in FLASH and can never change: it cannot be writable, $NODEID-relative "
    "(resolved at run time) or refreshed by a pre-read hook.",
    example='AccessType=rw\n# options: storage = "rom"',
    fix="Use ram or persist for the entry, or make it const/ro without hooks.",
    blocks=True,
    blocking="The C cannot hold the entry in the storage class asked for.",
    no_repair="The storage class is the user's choice in the options file.")

GEN004 = define(
    "GEN004", E, "C identifier collision", ref="odgen names",
    why="A C name odgen would emit twice does not compile or silently shadows another: entry names are "
    "made unique by their index and sub-index, but a hook function named in the options file can clash "
    "with a generated symbol or the odg_ runtime prefix.",
    example='[[entry]]\nmatch = "0x6200sub1"\nhooks = ["post_write"]\nfunction = "io_node_reset"',
    fix="Name the hook function outside the dictionary's prefix and outside odg_.",
    blocks=True,
    blocking="Two C identifiers would clash, so the C would not compile.",
    no_repair="The C names come from the file's names or the options; the user chooses another.")

GEN005 = define(
    "GEN005", E, "entry cannot be generated", ref="odgen generate",
    why="The generated runtime handles the CiA 301 basic types 0x0001-0x001B; other data types "
    "(DEFSTRUCT records used as a type, vendor types) have no defined memory layout.",
    example="DataType=0x0040",
    fix="Describe the entry with a basic data type, or exclude it with an options entry.",
    blocks=True,
    blocking="The entry cannot be expressed in C.",
    no_repair="What the entry should be in C is unknown.")

GEN006 = define(
    "GEN006", INFO, "object not generated", ref="odgen generate",
    why="Data type definition objects (0x0001-0x025F) describe types, not values; they are not "
    "placed in the generated dictionary.",
    example="[0020]\nParameterName=PDO_COMMUNICATION_PARAMETER\nObjectType=0x6",
    fix="Nothing to do; this is a note.")

GEN007 = define(
    "GEN007", E, "value block too large", ref="odgen generate",
    why="Sub-entry descriptors are 8 bytes with a 16-bit offset into their storage class's value "
    "block (FLASH, RAM, or one persistence group), so one block holds at most 65535 bytes; C "
    "generated beyond that would not compile.",
    example="16000 RAM objects with long string defaults",
    fix="Spread the values over storage classes with an options file (constant entries to rom, "
    "parameters into persistence groups, each its own block), shorten string or domain "
    "capacities, or split the device.",
    blocks=True,
    blocking="The C value block would exceed what the runtime can address.",
    no_repair="Which values should move elsewhere is the user's choice.")

GEN008 = define(
    "GEN008", E, "dictionary name clashes with the runtime or the C library", ref="odgen names",
    why="The dictionary's name is the stem of its files (NAME.h, NAME.c) and the prefix of its symbols. "
    "`odg` or `odg_init` collide with the runtime, `main`, `memcpy` or `size_t` with the C library, "
    "and `stdint` or `string` make the generated header shadow the standard one: the C does not "
    "compile. A name taken from the file name is prefixed `od_` instead (`main.eds` gives `od_main`).",
    example="odgen generate main.eds -o gen --name main",
    fix="Choose another --name, e.g. prefixed with the product: `--name pump_od`.",
    blocks=True,
    blocking="The C would clash with the runtime or the C library and not compile.",
    no_repair="The dictionary name is the user's choice (--name).")

GEN009 = define(
    "GEN009", E, "nothing to generate", ref="odgen generate",
    why="An ARRAY or RECORD without any sub-object, not even sub 0, has nothing a client could read or "
    "write, and the runtime's table check (odg_verify) refuses an entry without sub-entries. A "
    "description without any object from 0x1000 on would give empty tables, which C99 does not allow.",
    example="[1018]\nParameterName=Identity\nObjectType=0x9\nSubNumber=2\n# and no [1018sub0], [1018sub1]",
    fix="Describe the sub-objects SubNumber announces (OBJ009 counts them), and at least the mandatory "
    "objects 0x1000, 0x1001 and 0x1018 (COM001 names those missing).",
    blocks=True,
    blocking="There would be no dictionary to compile.",
    no_repair="There is no dictionary to repair.")

GEN010 = define(
    "GEN010", E, "the node's limits leave part of the description out", ref="odgen options",
    why="The node layer serves as many PDOs, mapping entries and heartbeat consumers as NAME_config.h "
    "says (ODG_NODE_MAX_TPDO, ..._MAX_RPDO, ..._MAX_MAP, ..._MAX_HB): the dictionary sets them, an "
    "options file may lower them to a firmware's budget. A PDO, mapping entry or heartbeat entry "
    "beyond a lowered limit would be in the dictionary, and promised to every configuration tool "
    "that reads the description, but never sent, received or watched.",
    example="[node]\ntpdo = 4   # the description has TPDOs 0x1800-0x1807",
    fix="Raise the [node] key to what the description needs, or remove the objects beyond it from the "
    "description.",
    blocks=True,
    blocking="The node would silently leave out what the description promises on the bus.",
    no_repair="The options file chose the limit; which of the two to change is the user's decision.")
