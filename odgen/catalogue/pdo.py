"""PDO: mapping objects and their pairing with communication objects."""

from __future__ import annotations

from .rule import E, W, define

# The mapping rules' exemption (PDO001-PDO005): a mapping the runtime cannot serve, of a PDO the file starts disabled.
DISABLED = ("A PDO that starts disabled (COB-ID bit 31) does not block: the node leaves it unused, as the file "
            "starts it, and refuses to enable it with that mapping (abort 0x06040043), so a master remaps it first.")

PDO001 = define(
    "PDO001", E, "mapped entry does not exist",
    ref="CiA 306 table row C1 / CiA 301 PDO mapping parameter",
    why="Each mapping entry 1..sub0 of 0x1600-0x17FF/0x1A00-0x1BFF names index, sub-index and length "
    "(0xIIIISSLL) of an existing entry, or of a data type index 0x0001-0x001B enabled as a dummy in "
    "[DummyUsage]. Devices refuse such a mapping at start-up (abort 0x06020000), leaving the PDO dead.",
    example="[1A00sub1]\nDefaultValue=0x60000108\n(no [6000] section)",
    fix="Map an existing entry, add the object, or enable the dummy with `DummyXXXX=1`.",
    blocks=True,
    blocking="The runtime refuses a mapping of a missing entry at start-up, so the PDO would be dead on the bus. "
    + DISABLED,
    repair="unsafe: the mapping entry removed (later entries move up, sub0 counts one less)")

PDO002 = define(
    "PDO002", E, "mapped entry is not PDO-mappable", ref="CiA 306 table row C2",
    why="Only entries with `PDOMapping=1` may be mapped; devices refuse the mapping with SDO abort "
    "0x06040041 and CANopenEditor reports a \"not mappable OD entry\".",
    example="[6000sub1]\nPDOMapping=0\n[1A00sub1]\nDefaultValue=0x60000108",
    fix="Set `PDOMapping=1` on the entry, or map another one.",
    blocks=True,
    blocking="Blocks only for an entry no PDO carries (a string, a DOMAIN). The file's own mapping is the more "
    "specific statement (a device serves its default mapping), so the C makes a number it maps mappable in that "
    "mapping's direction and the PDO works as described. " + DISABLED,
    repair="unsafe: a mapped number made PDO-mappable (PDOMapping=1), as the file's own mapping uses it",
    no_repair="No PDO carries a string or a DOMAIN: which entry the mapping meant is unknown.")

PDO003 = define(
    "PDO003", E, "mapping length differs from the entry's size", ref="CiA 306 table row C3",
    why="The low byte of a mapping entry is the length in bits and must equal the mapped entry's "
    "size (0x08 for UNSIGNED8, 0x20 for UNSIGNED32; BOOLEAN 1 or 8). A longer mapping makes the receiver "
    "decode every later field at the wrong offset. A shorter one CiA 301 does not define; CANopenNode "
    "accepts it and sends the low-order bytes. The odg runtime does the same for a 64-bit integer "
    "(INTEGER64, UNSIGNED64) mapped with 32 bits (`roscanopen__Elmo.dcf:827`): a TPDO carries its "
    "low-order four bytes (the first four of its little-endian encoding), an RPDO writes them and keeps "
    "the high-order ones. That case is a warning; other short mappings it refuses (abort 0x06040041).",
    example="[6000sub1]\nDataType=0x0005\n[1A00sub1]\nDefaultValue=0x60000110",
    fix="Write the entry's bit size in the low byte (`0x60000108`), or map an object of the intended size.",
    blocks=True,
    blocking="A mapping longer than its entry shifts every later field, and other short ones the odg runtime "
    "refuses at start-up: the PDO would not carry what the file says. A 64-bit integer mapped with 32 bits "
    "the runtime serves as CANopenNode does, so that one is a warning and does not block. " + DISABLED,
    repair="unsafe: a mapping longer than its entry shortened to the entry's size (later fields of the frame "
    "move)",
    no_repair="A mapping shorter than its entry (other than the 64-bit case): which length is right is unknown.")

PDO004 = define(
    "PDO004", E, "mapped entry cannot be accessed in the PDO's direction",
    ref="CiA 306 table row C2",
    why="An RPDO writes its entries, so they must be writable (wo, rw, rww); a TPDO reads them, so "
    "they must be readable (ro, const, rw, rwr). CANopenEditor and Lely's dcfgen refuse the mapping.",
    example="[6000sub1]\nAccessType=ro\n[1600sub1]\nDefaultValue=0x60000108",
    fix="Map the entry in the other PDO direction, or correct its AccessType.",
    blocks=True,
    blocking="The runtime refuses a mapping against the entry's access at start-up, so the PDO would be dead on the"
    " bus. " + DISABLED,
    repair="unsafe: the mapping entry removed (later entries move up, sub0 counts one less)")

PDO005 = define(
    "PDO005", E, "PDO maps more than a frame carries", ref="CiA 306 table row C4",
    why="A CAN frame carries 64 bits of data (CAN FD: 512, with --can-fd). A longer mapping is "
    "refused by the device (abort 0x06040042); Lely's dcfgen reports \"mapping exceeds 64 bits\".",
    example="[1A00sub0]\nDefaultValue=3\n3 entries of 32 bits",
    fix="Move entries to another PDO.",
    blocks=True,
    blocking="The runtime refuses a mapping longer than a frame at start-up, so the PDO would be dead on the bus. "
    + DISABLED,
    no_repair="Which entries the frame should carry is unknown.")

PDO006 = define(
    "PDO006", E, "more than 64 mapping entries", ref="CiA 301 PDO mapping parameter",
    why="A mapping object has at most 64 entries (sub-index 1..0x40); sub0 cannot count more.",
    example="[1A00sub0]\nDefaultValue=65",
    fix="Map at most 64 entries.",
    blocks=True,
    blocking="sub0 of a mapping cannot count more than 64 entries, so the C could not hold the mapping.",
    no_repair="Which entries the PDO should carry is unknown.")

PDO007 = define(
    "PDO007", E, "mapping offset not a multiple of Granularity", ref="CiA 306 table row H5",
    why="[DeviceInfo] Granularity is the bit granularity the device can map at: with 8, every "
    "entry must start on a byte boundary. A BOOLEAN mapped with length 1 shifts everything "
    "after it. (Granularity=0 means the mapping is fixed and is not checked.)",
    example="Granularity=8\n[1A00sub1]\nDefaultValue=0x20000101\n[1A00sub2]\nDefaultValue=0x20010108",
    fix="Map entries whose lengths keep later entries aligned, or pad with a dummy entry.",
    blocking="The mapping is served as written; only the device's stated granularity is not kept.")

PDO008 = define(
    "PDO008", E, "PDO communication and mapping objects not paired", ref="CiA 306 table row C5",
    why="RPDO n is 0x1400+n with mapping 0x1600+n, TPDO n 0x1800+n with mapping 0x1A00+n; one "
    "without the other is a PDO that cannot be configured or has no data. (With CompactPDO the "
    "missing objects up to NrOfRXPDO/NrOfTXPDO are implied.)",
    example="[1800]\n(no [1A00] section)",
    fix="Add the missing object, or remove the half PDO.",
    blocking="The runtime runs a PDO only when both halves exist and the mapping maps something (odg_pdo.c); "
    "a lone half stays a plain entry, which is all the file describes, so the node does what the file says.")

PDO009 = define(
    "PDO009", W, "NrOfRXPDO/NrOfTXPDO differs from the PDOs present", ref="CiA 306 table row H6",
    why="NrOfRXPDO and NrOfTXPDO in [DeviceInfo] count the RPDOs (0x1400-0x15FF) and TPDOs "
    "(0x1800-0x19FF) the file defines. Masters size their configuration by them. With CompactPDO "
    "the PDOs may be implied, so only more PDOs than declared are reported. Objects CANopenEditor "
    "marks `CO_disabled` are not counted.",
    example="NrOfTXPDO=4\n(only [1800] and [1801])",
    fix="Set the counts to the number of PDOs defined.")

PDO010 = define(
    "PDO010", W, "mapped entry declared for the other PDO direction", ref="CiA 306 table row O8",
    why="`rwr` marks process input (sent by TPDO), `rww` process output (received by RPDO). An "
    "RPDO mapping an rwr entry, or a TPDO mapping an rww one, works but contradicts the "
    "declaration; Vector's checker warns.",
    example="[6000sub1]\nAccessType=rwr\n[1600sub1]\nDefaultValue=0x60000108",
    fix="Map the entry in the declared direction, or correct its AccessType.")

PDO011 = define(
    "PDO011", W, "mapping entry counted by sub0 maps nothing", ref="CiA 301 PDO mapping parameter",
    why="An entry 0x00000000 within the count of sub0 maps no data. Generators write sub0 as the highest "
    "sub-index over all-zero entries; CANopenNode, Lely and python canopen read it as an empty entry "
    "(0 bits), and so does odgen, but a device may refuse the mapping (abort 0x06040041) when written.",
    example="[1A00sub0]\nDefaultValue=2\n[1A00sub2]\nDefaultValue=0x00000000",
    fix="Set sub0 to the number of entries that map something.")
