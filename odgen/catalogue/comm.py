"""COM: communication profile (CiA 301) semantics."""

from __future__ import annotations

from .rule import E, INFO, W, define

COM001 = define(
    "COM001", E, "mandatory object missing", ref="CiA 306 table row L3 / CiA 301 mandatory objects",
    why="Every CANopen device has 0x1000 (device type), 0x1001 (error register) and, since CiA 301 "
    "v4, 0x1018 (identity). Masters read them first; Lely's DCF loader refuses a file without them.",
    example="(no [1018] section)",
    fix="Add the object with its CiA 301 definition.",
    blocking="Decided: the C serves the objects the file has, and the runtime needs none of 0x1000/0x1001/0x1018 "
    "(the node keeps its error register itself); a master finds the object missing at its first read "
    "(abort 0x06020000), as it would on the device the file describes, so nothing is silently wrong.")

COM002 = define(
    "COM002", E, "communication entry with the wrong data type",
    ref="CiA 301 communication profile objects",
    why="CiA 301 fixes the data type of every communication object (COB-IDs UNSIGNED32, "
    "transmission types UNSIGNED8, times UNSIGNED16, ...). Masters access them by that size, so a "
    "different DataType breaks SDO transfers and generated code.",
    example="[1017]\nDataType=0x0007  (Producer heartbeat time is UNSIGNED16)",
    fix="Use the CiA 301 data type named in the message.",
    blocks=True,
    blocking="Blocks for an entry the runtime reads (PDO, SDO, SYNC, EMCY, TIME, heartbeat, identity): it would "
    "read it in another size than the C holds. An entry the runtime never reads (0x1008-0x100A, ...) does "
    "not block.",
    no_repair="Which type the device really answers in is unknown.")

COM003 = define(
    "COM003", W, "identity information is writable", ref="CiA 301 communication profile objects",
    why="0x1000, 0x1001, 0x1008-0x100A and 0x1018 describe the device; CiA 301 makes them ro (or "
    "const). A writable entry lets a master overwrite what identifies the device.",
    example="[1000]\nAccessType=rw",
    fix="Write `AccessType=ro` (or const).")

COM004 = define(
    "COM004", W, "default COB-ID not from the predefined connection set",
    ref="CiA 306 table row C6 / CiA 301 predefined connection set",
    why="CiA 301's predefined connection set gives RPDO1-4 `$NODEID+0x200/0x300/0x400/0x500`, "
    "TPDO1-4 `$NODEID+0x180/0x280/0x380/0x480` and EMCY `$NODEID+0x80` (the default SDO server's "
    "`$NODEID+0x600`/`$NODEID+0x580` are COM017). Another base (often RPDO and TPDO "
    "swapped) or a fixed number in an EDS makes the device talk on CAN-IDs masters do not expect. "
    "A bare base (`0x180`) relies on CANopenNode adding the node-id at run time; other tools "
    "take it literally.",
    example="[1800sub1]\nDefaultValue=$NODEID+0x200",
    fix="Write the predefined default, e.g. `DefaultValue=$NODEID+0x180` for TPDO1.")

COM005 = define(
    "COM005", E, "PDO COB-ID uses a restricted or invalid CAN-ID",
    ref="CiA 306 table row C6 / CiA 301 predefined connection set",
    why="A valid PDO (bit 31 clear) must not use the CAN-IDs CiA 301 restricts to NMT, SYNC/EMCY, "
    "TIME, SDO, heartbeat and LSS (0x000-0x07F, 0x101-0x180, 0x581-0x5FF, 0x601-0x67F, 0x6E0-0x6FF, "
    "0x701-0x7FF), and an 11-bit COB-ID (bit 29 clear) has no bits set in 11-28.",
    example="[1800sub1]\nDefaultValue=$NODEID+0x700",
    fix="Use a free CAN-ID, or set bit 31 (0x80000000) to disable the PDO.",
    blocks=True,
    blocking="The node would transmit or receive a PDO on a CAN-ID reserved for another service, disturbing the "
    "bus.",
    no_repair="Which CAN-ID the PDO should use is the system integrator's choice.")

COM006 = define(
    "COM006", W, "identity object without Vendor-ID",
    ref="CiA 306 table row C7 / CiA 301 object 0x1018",
    why="0x1018 is a RECORD whose sub1 (Vendor-ID) is mandatory; masters identify devices and LSS "
    "addresses them by it.",
    example="[1018]\nObjectType=0x9\nSubNumber=1\n[1018sub0]",
    fix="Add `[1018sub1]` Vendor-ID (UNSIGNED32, ro) and set sub0 to the highest sub-index.")

COM007 = define(
    "COM007", W, "no error control object", ref="CiA 306 table row C7 / CiA 301 error control",
    why="A CiA 301 v4 device supports heartbeat (0x1017) or, for older masters, node guarding "
    "(0x100C and 0x100D). Without either a master cannot tell that the node is alive.",
    example="(no [1017], [100C] or [100D])",
    fix="Add 0x1017 Producer heartbeat time (UNSIGNED16, rw).")

COM008 = define(
    "COM008", W, "heartbeat and node guarding both enabled",
    ref="CiA 306 table row C7 / CiA 301 error control",
    why="A device uses heartbeat or node guarding, not both; with both defaults non-zero the behaviour "
    "depends on the stack. Lely's dcfgen refuses such a configuration.",
    example="[1017]\nDefaultValue=1000\n[100C]\nDefaultValue=100\n[100D]\nDefaultValue=3",
    fix="Set the default of 0x1017, or of 0x100C/0x100D, to 0.")

COM009 = define(
    "COM009", INFO, "PDO communication record with an unusual highest sub-index",
    ref="CiA 306 table row C8",
    why="CiA 301 defines RPDO communication parameters up to sub5 and TPDO ones up to sub6, with at "
    "least sub1 (COB-ID) and sub2 (transmission type). Sparse records are legal.",
    example="[1400sub0]\nDefaultValue=6",
    fix="Remove the sub-objects CiA 301 does not define, and set sub0 accordingly.")

COM010 = define(
    "COM010", E, "communication record lacks a required sub-object",
    ref="CiA 306 table row C8 / CiA 301 PDO and SDO parameters",
    why="PDO communication records need sub1 (COB-ID) and sub2 (transmission type); SDO parameter "
    "records need sub1 and sub2 (COB-IDs), SDO client records also sub3 (server node-ID). "
    "Stacks cannot set up the channel without them.",
    example="[1800]\nObjectType=0x9\nSubNumber=2\n[1800sub0]\n[1800sub1]",
    fix="Add the missing sub-object.",
    blocks=True,
    blocking="The runtime cannot set up the PDO or SDO channel without the sub-object, so the node would not talk "
    "as the file says.",
    no_repair="The missing COB-ID or transmission type is unknown.")

COM011 = define(
    "COM011", W, "reserved PDO transmission type", ref="CiA 301 PDO communication parameter",
    why="Transmission types 241-251 are reserved for TPDOs, 241-253 for RPDOs (252/253, RTR, exist "
    "only for TPDOs). Devices refuse them (abort 0x06090030).",
    example="[1400sub2]\nDefaultValue=252",
    fix="Use 0-240 (synchronous) or 254/255 (event-driven).")

COM012 = define(
    "COM012", W, "device type names no profile but profile objects exist",
    ref="CiA 301 object 0x1000",
    why="The low 16 bits of 0x1000 are the device profile number (401 = 0x191, 402 = 0x192, ...). "
    "With 0 (no profile) but objects in 0x6000-0x9FFF, masters and profile tools ignore or "
    "misinterpret the profile part.",
    example="[1000]\nDefaultValue=0\n[6000]\n...",
    fix="Write the profile number (and its additional information) into 0x1000.")

COM013 = define(
    "COM013", W, "device type or Vendor-ID without a value", ref="CiA 301 objects 0x1000, 0x1018",
    why="0x1000 and 0x1018 sub1 are read-only constants masters check during boot-up; without a "
    "DefaultValue the generated device answers 0.",
    example="[1000]\nParameterName=Device type\nDataType=0x0007\nAccessType=ro",
    fix="Add the DefaultValue (e.g. `0x00000191` for a CiA 401 device).")

COM014 = define(
    "COM014", W, "node guarding half configured", ref="CiA 301 objects 0x100C, 0x100D",
    why="Node guarding needs both guard time (0x100C) and life time factor (0x100D); one without the "
    "other cannot be used.",
    example="[100C]\n(no [100D])",
    fix="Add the missing object, or remove both and use heartbeat (0x1017).")

COM015 = define(
    "COM015", W, "invalid heartbeat consumer entry", ref="CiA 301 object 0x1016",
    why="A 0x1016 entry is 0x00NNTTTT: bits 24-31 are reserved (0), NN is a node-id 1..127 when "
    "the time TTTT is not 0, and no node-id may be monitored twice (devices refuse with abort "
    "0x06040043).",
    example="[1016sub1]\nDefaultValue=0x00800064  (node-id 128)",
    fix="Write `0x00NNTTTT` with a node-id 1..127, each at most once.")

COM016 = define(
    "COM016", E, "two enabled objects of one device on one CAN-ID",
    ref="CiA 301 COB-ID usage / predefined connection set",
    why="Each enabled PDO, SDO channel, EMCY, produced SYNC or TIME needs a CAN-ID of its own (a PDO "
    "on the heartbeat's 0x700+node-id is COM005): two TPDOs on one ID collide on the bus, an RPDO on a "
    "TPDO's ID receives the device's own frames. `lint --network` finds collisions between devices "
    "(NET004, NET007); this is the same mistake inside one file.",
    example="[1800sub1]\nDefaultValue=$NODEID+0x180\n[1801sub1]\nDefaultValue=$NODEID+0x180",
    fix="Give each object its own COB-ID, or disable one (bit 31).",
    blocks=True,
    blocking="Decided: two objects of one node on one CAN-ID collide on the bus (two TPDOs), or the node receives "
    "its own frames (an RPDO on a TPDO's ID), so the node would misbehave.",
    repair="unsafe: the later PDO on a shared CAN-ID disabled (COB-ID bit 31 set)")

COM017 = define(
    "COM017", E, "default SDO server COB-ID not the predefined one or writable",
    ref="CiA 301 object 0x1200",
    why="The default SDO server 0x1200 receives on `$NODEID+0x600` and transmits on `$NODEID+0x580`, "
    "and CiA 301 makes both sub-entries read-only: every master reaches a device there. Another "
    "value, or one a master can change, makes the device unreachable by tools that assume the "
    "default.",
    example="[1200sub1]\nAccessType=rw\nDefaultValue=$NODEID+0x600",
    fix="Write `$NODEID+0x600` / `$NODEID+0x580` with AccessType=ro; use 0x1201.. for other channels.",
    blocks=False,
    blocking="Does not block: the runtime serves SDO where 0x1200 says, so a master configured from the "
    "description reaches the node (odgen's round trip and conformance battery do); a master that assumes "
    "the predefined COB-IDs does not, which is why it is an error. A writable 0x1200 does not block either.",
    repair="safe: the COB-ID written as $NODEID+0x600 / $NODEID+0x580, which CiA 301 fixes")

COM018 = define(
    "COM018", W, "pre-defined error field count not writable", ref="CiA 301 object 0x1003",
    why="Sub0 of 0x1003 counts the errors in the history; CiA 301 clears the history when 0 is "
    "written to it, so it is rw. Read-only, a master cannot clear the errors.",
    example="[1003sub0]\nAccessType=ro",
    fix="Set `AccessType=rw` on 0x1003sub0.")

COM019 = define(
    "COM019", E, "TIME COB-ID malformed", ref="CiA 301 object 0x1012",
    why="0x1012 is `consume` (bit 31), `produce` (bit 30), 29-bit frame (bit 29) and the CAN-ID "
    "(bits 0-10, or 0-28 with bit 29). An 11-bit COB-ID with bits 11-28 set, or a CAN-ID CiA 301 "
    "restricts (0x000-0x07F, 0x101-0x180, 0x581-0x5FF, 0x601-0x67F, 0x6E0-0x6FF, 0x701-0x7FF: NMT, "
    "SDO, heartbeat, LSS and reserved ones) for a TIME object in use, makes it collide or be "
    "dropped. TIME is a broadcast to every node (default 0x100), so a `$NODEID` value gives each "
    "node another CAN-ID and no producer reaches them all.",
    example="[1012]\nDefaultValue=0x80000900  (bit 11 set, bit 29 clear)",
    fix="Write `0x80000100` (consume on 0x100) or `0x40000100` (produce), without `$NODEID`.",
    blocking="The runtime sends or accepts TIME only on a well-formed COB-ID; a malformed one leaves TIME unused, "
    "which the file's own bits say.")

COM020 = define(
    "COM020", W, "synchronous window longer than the communication cycle period",
    ref="CiA 301 objects 0x1006, 0x1007",
    why="The window (0x1007, us) after each SYNC is when synchronous PDOs are sent and received; "
    "it must end before the next SYNC (0x1006, us). Longer, the device sends and accepts "
    "synchronous data of one cycle in the next and loses nothing to the window, which is what it "
    "is for.",
    example="[1006]\nDefaultValue=10000\n[1007]\nDefaultValue=20000",
    fix="Make 0x1007 at most 0x1006 (or 0: no window).")

COM021 = define(
    "COM021", W, "LSS supported but the identity is incomplete", ref="CiA 301 object 0x1018 / CiA 305 LSS address",
    why="An LSS master addresses a device by its LSS address: 0x1018 sub1-4 (Vendor-ID, product code, "
    "revision number, serial number). Switch state selective, identify remote slave and fastscan "
    "compare all four, so a device that says `LSS_Supported=1` without them cannot be found.",
    example="LSS_Supported=1\n[1018]\nSubNumber=2  (sub1 only)",
    fix="Add 0x1018 sub2-4 (UNSIGNED32, ro), or write `LSS_Supported=0`.")
