"""OBJ: objects and sub-objects."""

from __future__ import annotations

from .rule import E, INFO, W, define

# OBJ015/OBJ017 on a read-only entry (model.capacity.served_limits)
UNCHECKED = ("On a read-only entry no write is ever checked (the SDO server refuses it, RPDOs map writable entries "
             "only, the application's own writes skip limits), so the C leaves out limits that could not hold: a "
             "warning.")

OBJ001 = define(
    "OBJ001", E, "ParameterName missing", ref="CiA 306 table row O1",
    why="Every object and sub-object section needs a `ParameterName`. Lely and CANopenEditor refuse "
    "the file without it, and generated code has nothing to name the entry after.",
    example="[2000]\nObjectType=0x7\nDataType=0x0007\nAccessType=rw",
    fix="Add `ParameterName=<name>`.",
    blocking="The C names an unnamed entry after its index, so it stays correct.")

OBJ002 = define(
    "OBJ002", E, "invalid ObjectType", ref="CiA 306 table row O2 / CiA 301 object codes",
    why="ObjectType is a CiA 301 object code: 0x2 DOMAIN, 0x5 DEFTYPE, 0x6 DEFSTRUCT, 0x7 VAR, "
    "0x8 ARRAY, 0x9 RECORD (absent means VAR). A sub-object is always a VAR (0x7), or a DOMAIN (0x2).",
    example="[2000]\nObjectType=0x3",
    fix="Write the object code of the entry (`0x7` for a single value, `0x8`/`0x9` for sub-objects).",
    blocks=True,
    blocking="Without an object code the C cannot tell a value from a container.",
    no_repair="Which object code was meant is unknown.")

OBJ003 = define(
    "OBJ003", E, "DataType missing", ref="CiA 306 table row O3",
    why="A VAR or DEFTYPE object, a sub-object and a CompactSubObj header need a `DataType`; without "
    "it the value has no size or range. Lely and CANopenEditor refuse the file.",
    example="[2000]\nParameterName=Speed\nObjectType=0x7\nAccessType=rw",
    fix="Add `DataType=0x....` (e.g. 0x0007 for UNSIGNED32).",
    blocks=True,
    blocking="Without a data type the C cannot size or encode the value.",
    no_repair="The size and encoding of the value are unknown.")

OBJ004 = define(
    "OBJ004", E, "AccessType missing", ref="CiA 306 table row O3",
    why="A VAR, DOMAIN or DEFTYPE object, a sub-object and a CompactSubObj header need an "
    "`AccessType`; without it nobody knows whether the entry may be read or written.",
    example="[2000]\nParameterName=Speed\nDataType=0x0007",
    fix="Add `AccessType=ro|wo|rw|rwr|rww|const`.",
    blocks=True,
    blocking="Without an access type the C cannot decide whether masters may read or write the entry.",
    no_repair="Whether masters may write the entry is the device maker's decision, not a guess.")

OBJ005 = define(
    "OBJ005", E, "invalid AccessType", ref="CiA 306 table row O7",
    why="AccessType is one of ro, wo, rw, rwr (read/write, TPDO-mappable), rww (read/write, "
    "RPDO-mappable) or const. Other values are refused by Lely, CANopenEditor and objdictgen.",
    example="AccessType=readonly",
    fix="Use one of `ro`, `wo`, `rw`, `rwr`, `rww`, `const`.",
    blocks=True,
    blocking="The C cannot decide whether masters may read or write the entry.",
    no_repair="Whether masters may write the entry is the device maker's decision, not a guess.")

OBJ006 = define(
    "OBJ006", E, "ARRAY/RECORD needs exactly one of SubNumber and CompactSubObj",
    ref="CiA 306 table row O3",
    why="An ARRAY, RECORD or DEFSTRUCT object says how many sub-objects it has either with `SubNumber` "
    "(followed by `[XXXXsubY]` sections) or with `CompactSubObj` (sub-objects implied). With neither, "
    "or both, readers disagree on its sub-objects.",
    example="[1003]\nParameterName=Pre-defined error field\nObjectType=0x8\n(no SubNumber)",
    fix="Add `SubNumber=<count of sub-object sections>`, or keep only one of the two keywords.",
    blocks=True,
    blocking="Blocks when the container's sub-objects are unknown (neither keyword and no sub-object sections, or "
    "both keywords); with neither keyword, the sub-object sections present are the container, as every "
    "reader takes them, and it does not block.",
    repair="safe: SubNumber added, counting the sub-object sections present; unsafe: a header without "
    "sub-objects that carries DataType and AccessType read as the VAR it describes (ObjectType=0x7)",
    no_repair="With both keywords, or neither and no sub-object sections nor a value's keywords, which "
    "sub-objects the device has is unknown.")

OBJ007 = define(
    "OBJ007", E, "SubNumber or CompactSubObj on a single-value object", ref="CiA 306 table row O3",
    why="`SubNumber` and `CompactSubObj` belong to ARRAY/RECORD objects. On a VAR, DOMAIN or DEFTYPE "
    "they contradict the object type; CANopenEditor refuses the file.",
    example="[2000]\nObjectType=0x7\nSubNumber=2",
    fix="Remove the keyword, or make the object an ARRAY (0x8) or RECORD (0x9) with sub-objects.",
    blocks=True,
    blocking="Whether the object is one value or a container is unclear, so the C would match one reading only.",
    no_repair="Which of the two the device has is unknown.")

OBJ008 = define(
    "OBJ008", E, "value keywords on an ARRAY/RECORD header", ref="CiA 306 table row O3",
    why="Without CompactSubObj, DataType, AccessType, DefaultValue, limits and PDOMapping belong to the "
    "`[XXXXsubY]` sections; on the `[XXXX]` header they are ignored. Lely refuses AccessType there. "
    "Since every reader (odgen, CANopenNode, python canopen) ignores them, the dictionary does not "
    "change and generation goes on (`roscanopen__Schunk_0_63.dcf:1809`).",
    example="[2000]\nObjectType=0x9\nSubNumber=2\nAccessType=rw",
    fix="Move the keywords into the sub-object sections.",
    blocking="Every reader ignores these keywords, so the C is the same without them.")

OBJ009 = define(
    "OBJ009", E, "SubNumber differs from the sub-objects present", ref="CiA 306 table row O4",
    why="`SubNumber` is the number of `[XXXXsubY]` sections that follow (gaps in sub-indices allowed), "
    "not the highest sub-index. Lely reports missing or extra sub-objects; other tools silently drop them.",
    example="[2000]\nObjectType=0x8\nSubNumber=4\n[2000sub0] [2000sub1] [2000sub2]",
    fix="Set SubNumber to the number of sub-object sections, or add the missing ones.",
    blocking="The C holds the sub-objects present, as every reader does; SubNumber itself is not part of the "
    "dictionary.")

OBJ010 = define(
    "OBJ010", E, "sub0 of an ARRAY/RECORD missing or not UNSIGNED8",
    ref="CiA 306 table row O5 / CiA 301 ARRAY/RECORD sub0",
    why="Sub-index 0 of an ARRAY or RECORD holds its highest sub-index as UNSIGNED8. Without it, or "
    "with another type, masters cannot enumerate the object; Lely refuses the file.",
    example="[2000sub0]\nDataType=0x0007",
    fix="Add `[XXXXsub0]` with `DataType=0x0005`, `AccessType=ro` and the highest sub-index as DefaultValue.",
    blocks=True,
    blocking="Blocks for a sub0 that is writable in another type (a master writes the count as one byte, "
    "which the runtime refuses as too short) or that is no unsigned number (REAL32, a string: no count). A "
    "read-only sub0 of a wider unsigned type the C serves as written, an upload stating its size, and a "
    "missing sub0 leaves the C serving the sub-objects the file has: neither blocks.",
    repair="safe: a missing sub0 added (UNSIGNED8, ro, the highest sub-index); unsafe: sub0 of another type made "
    "UNSIGNED8 when its value fits")

OBJ011 = define(
    "OBJ011", E, "sub0 differs from the highest sub-index",
    ref="CiA 306 table row O5 / CiA 301 ARRAY/RECORD sub0",
    why="The DefaultValue of sub0 is the highest sub-index the object supports. A smaller value hides "
    "sub-objects from masters, a larger one announces sub-objects that do not exist. "
    "(0x1003 counts errors and PDO mapping objects count mapped entries instead; they are not checked here. "
    "Nor is a writable sub0 below the highest sub-index: it counts the valid entries as 0x1003 does, a "
    "pattern vendors use for other objects, e.g. `kacanopen__CL4-E-2-12.eds:6267`, and that CANopenNode "
    "and python canopen accept.)",
    example="[2000sub0]\nAccessType=ro\nDefaultValue=2\n[2000sub3]",
    fix="Set sub0's DefaultValue to the highest sub-index present.",
    blocking="The C serves sub0 and every sub-object as the file gives them, as the device the file describes does;"
    " a master that trusts sub0 sees what it would see on that device.",
    repair="safe: sub0 set to the highest sub-index where the sub-objects are written as sections")

OBJ012 = define(
    "OBJ012", E, "undefined DataType", ref="CiA 306 table row O9",
    why="DataType must be a CiA 301 basic type (0x0001-0x001B, not the reserved 0x000E/0x0017), or a "
    "type defined in the file by a DEFTYPE/DEFSTRUCT object at that index. Python canopen turns "
    "unknown types into DOMAIN; generated code cannot size the value.",
    example="DataType=0x0040 (no [0040] section)",
    fix="Use a basic type, or add the DEFTYPE/DEFSTRUCT definition.",
    blocks=True,
    blocking="The C cannot size or encode a value of an unknown type.",
    repair="unsafe: an undefined data type read as DOMAIN, as python canopen reads it")

OBJ013 = define(
    "OBJ013", E, "limits on a non-numeric entry", ref="CiA 306 table row O10",
    why="LowLimit/HighLimit restrict numeric values; on strings, DOMAIN or time types they mean "
    "nothing and Lely refuses them.",
    example="DataType=0x0009\nLowLimit=0",
    fix="Remove LowLimit/HighLimit from the entry.",
    blocking="The C keeps no limits for a non-numeric entry, so they change nothing.")

OBJ014 = define(
    "OBJ014", E, "limit outside the data type's range", ref="CiA 306 table row O10",
    why="A LowLimit or HighLimit the data type cannot hold is a typo or a wrong DataType; Lely reports "
    "it as overflow. `$NODEID+v` limits are checked for node-ids 1..127 (or the given node-id).",
    example="DataType=0x0006\nHighLimit=65536",
    fix="Use a limit within the type (UNSIGNED16: 0..65535) or a wider DataType.",
    blocks=True,
    blocking="Blocks when the limit lies beyond the other end of the type (a HighLimit below the minimum, a "
    "LowLimit above the maximum): the entry could take no value. A limit beyond the end it bounds restricts "
    "nothing, and the C (limits compared as 64-bit numbers) restricts nothing there either: no block.",
    repair="safe: a limit beyond the end of the type's range (HighLimit above the maximum, LowLimit below the "
    "minimum) removed, as it restricts nothing; unsafe: a limit beyond the other end removed")

OBJ015 = define(
    "OBJ015", E, "LowLimit above HighLimit", ref="CiA 306 table row O10",
    why="No value satisfies LowLimit > HighLimit, so every write is refused.",
    example="LowLimit=100\nHighLimit=10",
    fix="Swap or correct the limits.",
    blocks=True,
    blocking="Blocks on a writable entry: the runtime refuses reversed limits when it checks its tables "
    "(odg_verify), so the node would not start. " + UNCHECKED,
    repair="unsafe: limits written as bit patterns of a signed type that read reversed removed; other reversed "
    "limits swapped")

OBJ016 = define(
    "OBJ016", E, "value outside the data type's range", ref="CiA 306 table row O11",
    why="A DefaultValue or ParameterValue the data type cannot hold is truncated differently by every "
    "tool. `$NODEID+v` values are checked for node-ids 1..127 (or the node-id given to odgen).",
    example="DataType=0x0005\nDefaultValue=300",
    fix="Correct the value, or widen the DataType.",
    blocks=True,
    blocking="The C holds the value in the data type, so a value outside it would be another number.",
    no_repair="Whether the value or the data type is wrong is unknown.")

OBJ017 = define(
    "OBJ017", E, "value outside LowLimit..HighLimit", ref="CiA 306 table row O11",
    why="The device would refuse to be written its own default: a DefaultValue or ParameterValue must "
    "lie within [LowLimit, HighLimit].",
    example="LowLimit=1\nHighLimit=10\nDefaultValue=0",
    fix="Correct the value or the limits.",
    blocks=True,
    blocking="Blocks on a writable entry: the runtime checks its value against its limits when it checks its "
    "tables (odg_verify), so the node would not start, and a master writing back what it read would be refused. "
    + UNCHECKED,
    repair="unsafe: a value outside its limits clamped to them; a $NODEID value, which cannot be clamped for every "
    "node-id, has the limit it crosses removed")

OBJ018 = define(
    "OBJ018", INFO, "PDO-mappable rw entry without a direction", ref="CiA 306 table row O8",
    why="CiA 306 marks the PDO direction of a mappable read/write entry with `rwr` (TPDO, process "
    "input) or `rww` (RPDO, process output). Plain `rw` is legal and may be mapped either way, but "
    "tools must guess the intent; Vector's checker warns. Information only (a third of real files "
    "do this), reported once per object.",
    example="AccessType=rw\nPDOMapping=1",
    fix="Write `rww` for entries the device receives, `rwr` for entries it sends.")

OBJ019 = define(
    "OBJ019", W, "PDO-mappable entry of a type that cannot be mapped",
    ref="CiA 306 table row O8 / CiA 301 PDO mapping",
    why="A PDO carries at most 64 bits (CAN FD: 512) of fixed-size data. DOMAIN entries have no fixed "
    "size and cannot be mapped.",
    example="DataType=0x000F\nPDOMapping=1",
    fix="Set `PDOMapping=0`.")

OBJ020 = define(
    "OBJ020", W, "VISIBLE_STRING value with invisible characters",
    ref="CiA 306 table row O12 / CiA 301 VISIBLE_STRING",
    why="VISIBLE_STRING holds printable ASCII (0x20-0x7E). Other characters are encoded differently "
    "by every tool (Windows-1252, UTF-8) and may not reach the device as written.",
    example="DataType=0x0009\nDefaultValue=Température",
    fix="Use ASCII text, or UNICODE_STRING (0x000B).")

OBJ021 = define(
    "OBJ021", W, "DOMAIN with a DefaultValue", ref="CiA 306 table row O12 (verify)",
    why="A DOMAIN's content is not written in the description: CiA 306 uses UploadFile/DownloadFile. "
    "Tools read a DOMAIN DefaultValue as text, as hex bytes or not at all. `DefaultValue=0`, which "
    "editors write for \"no content\", is not reported. (Row marked verify: warning until checked "
    "against the CiA 306 text.)",
    example="DataType=0x000F\nDefaultValue=0x1234",
    fix="Remove the DefaultValue, or use OCTET_STRING (0x000A) for fixed bytes.")

OBJ022 = define(
    "OBJ022", W, "UploadFile/DownloadFile with the wrong AccessType", ref="CiA 306 table row O12",
    why="An UploadFile is read from the device, so the entry is `ro` or `const`; a DownloadFile is "
    "written to it, so the entry is `wo`. Lely's DCF loader refuses other combinations.",
    example="AccessType=rw\nUploadFile=log.bin",
    fix="Correct the AccessType or remove the file keyword.")

OBJ023 = define(
    "OBJ023", W, "ObjFlags with undefined bits", ref="CiA 306 table row O13",
    why="ObjFlags is UNSIGNED32 with bit 0 (refuse read on scan) and bit 1 (refuse write on download) "
    "defined; other bits are reserved.",
    example="ObjFlags=0x10",
    fix="Use a value 0..3.")

OBJ024 = define(
    "OBJ024", W, "DCF-only content in an EDS", ref="CiA 306 table row O15",
    why="ParameterValue, Denotation, ParamRefd and [DeviceComissioning] describe one configured node "
    "and belong to a DCF. In an EDS they are ignored by most tools or mistaken for defaults.",
    example="(dev.eds)\n[2000]\nParameterValue=5",
    fix="Put the value into DefaultValue, or move the configuration into a DCF.")

OBJ025 = define(
    "OBJ025", W, "unknown keyword in an object section",
    ref="CiA 306 object section keywords (as Lely's dcfchk checks them)",
    why="The keyword is not one CiA 306 defines for object sections; odgen keeps it but no tool "
    "interprets it, and Lely rejects it.",
    example="[2000]\nUnit=rpm",
    fix="Remove the keyword or write it as a `;` comment.")

OBJ026 = define(
    "OBJ026", W, "ARRAY elements of different data types", ref="CiA 301 object code ARRAY",
    why="All sub-objects 1..n of an ARRAY share one data type; with mixed types the object is a RECORD. "
    "CanFestival writes its PDO communication parameters 0x1400/0x1800 as ARRAYs of UNSIGNED32, "
    "UNSIGNED8 and UNSIGNED16, which CiA 301 defines as RECORDs. Lely's dcfchk, objdictgen, "
    "CANopenEditor and python canopen accept such files (each element keeps its own type), so odgen "
    "generates the object as the RECORD it is and warns.",
    example="[2000]\nObjectType=0x8\n[2000sub1] DataType=0x0007\n[2000sub2] DataType=0x0006",
    fix="Give every element the same DataType, or change ObjectType to 0x9 (RECORD).")

OBJ027 = define(
    "OBJ027", W, "ARRAY element without a name", ref="CiA 306 table row O1",
    why="CANopenEditor writes ARRAY elements with an empty `ParameterName`. The element's place in the "
    "array names it well enough: odgen names it after the ARRAY and its sub-index in generated code, "
    "as CANopenNode does, and warns so that the file can be completed.",
    example="[2000sub1]\nParameterName=\nDataType=0x0007",
    fix="Give each element a `ParameterName`.")

OBJ028 = define(
    "OBJ028", E, "sub-object that is not a VAR", ref="CiA 306 table row O2 / CiA 301 object codes",
    why="A sub-object is a single value: CiA 306 gives every `[XXXXsubY]` section ObjectType=0x7 (VAR), "
    "and a DOMAIN's data is said by DataType=0x000F on a VAR. Tools that check the code refuse another "
    "one (Lely's dcfchk). Readers, odgen's included, take the sub-object as a value of its DataType "
    "whatever its code, so the dictionary is clear and generation goes on "
    "(`kacanopen__epos2_347717.eds:3647` writes a DOMAIN sub-object as ObjectType=0x2).",
    example="[2000sub1]\nObjectType=0x2\nDataType=0x000F",
    fix="Write `ObjectType=0x7`, with `DataType=0x000F` for a DOMAIN value.",
    blocking="Every reader takes the sub-object as a value of its DataType, so the C matches the file.")

OBJ029 = define(
    "OBJ029", E, "VISIBLE_STRING value with a NUL character", ref="CiA 301 VISIBLE_STRING",
    why="VISIBLE_STRING holds the printable characters 0x20-0x7E. A NUL in its value ends the string "
    "for the C runtime, which then serves a shorter value than the file describes (odgen check's "
    "self-test fails on it), and masters disagree on the length.",
    example="[1008]\nDataType=0x0009\nDefaultValue=Pump\\0A",
    fix="Remove the NUL, or describe the value as an OCTET_STRING (0x000A).",
    blocks=True,
    blocking="The C string ends at the NUL, so the node would serve a shorter value than the file has.",
    no_repair="Whether the text after the NUL matters is unknown.")

OBJ030 = define(
    "OBJ030", W, "const entry with a $NODEID-relative value", ref="CiA 306 AccessType / CiA 301 0x1200",
    why="`const` says the value is the same for the device's whole life, and generators (odgen, "
    "CANopenNode) place it in FLASH. A `$NODEID+v` value is worked out at start-up from the node-id, "
    "so it is read-only rather than constant: CiA 301 gives the default SDO server's COB-IDs "
    "(0x1200sub1/sub2) as `ro`. odgen places such a value in RAM, as a read-only one (GEN003 when the options "
    "ask for rom); masters see no difference between the two, both refuse a write.",
    example="[1200sub1]\nAccessType=const\nDefaultValue=$NODEID+0x600",
    fix="Write `AccessType=ro`.",
    repair="safe: AccessType const -> ro (masters see the same read-only entry)")
