"""NET: a network of nodes (odgen lint --network)."""

from __future__ import annotations

from .rule import E, W, define

NET001 = define(
    "NET001", E, "network file is not a list of nodes",
    why="NET.toml lists the nodes as `[[node]]` tables (and the master as `[master]`), each with `file` "
    "(relative to NET.toml) and `node_id`, and the PDO wiring as `[[pdo]]` tables (docs/network.md); "
    "a table, key or value outside that cannot be checked.",
    example='[[node]]\nfile = "slave.eds"\n(no node_id)',
    fix="Write the tables and keys docs/network.md lists, with values of the types it gives.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET002 = define(
    "NET002", E, "node-id outside 1..127 or used twice",
    why="Every node of a CANopen network has its own node-id 1..127; the fixed COB-IDs (SDO, EMCY, "
    "heartbeat) and every `$NODEID` value derive from it, so two nodes with one id collide on all of them.",
    example='[[node]]\nfile = "a.eds"\nnode_id = 2\n[[node]]\nfile = "b.eds"\nnode_id = 2',
    fix="Give each node a distinct node-id in 1..127.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET003 = define(
    "NET003", E, "node's file is missing or unreadable",
    why="A node whose description cannot be read cannot be checked against the others.",
    example='[[node]]\nfile = "missing.eds"\nnode_id = 2',
    fix="Correct the path (relative to NET.toml) or add the file.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET004 = define(
    "NET004", E, "two TPDOs transmit the same COB-ID",
    why="A COB-ID has exactly one producer; two nodes transmitting the same identifier with different "
    "data cause bus errors (same identifier, different bits) or frames that consumers misread.",
    example="node 2: [1800sub1] DefaultValue=0x182\nnode 4: [1800sub1] DefaultValue=0x182",
    fix="Give one of the TPDOs another COB-ID, or disable it (bit 31).",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET005 = define(
    "NET005", W, "RPDO COB-ID that no node transmits",
    why="An enabled RPDO waits for a frame no node of the network sends: its entries never change. "
    "Often a node-id or COB-ID typo.",
    example="node 1: [1401sub1] DefaultValue=0x183\n(no node 3 in NET.toml)",
    fix="Set the COB-ID of the producing TPDO, add the producer to NET.toml, or disable the RPDO (bit 31).")

NET006 = define(
    "NET006", E, "RPDO mapping does not match the producing TPDO",
    why="A consumer decodes a frame by its own mapping: unless it has the same number of entries with "
    "the same lengths in the same order as the producer's, every field after the first difference "
    "is read at the wrong bit offset.",
    example="TPDO [1A00] maps 8 bit, 8 bit\nRPDO [1600] maps 16 bit",
    fix="Make the RPDO mapping's lengths follow the TPDO's (pad with dummy entries where needed).",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET007 = define(
    "NET007", E, "PDO COB-ID collides with another node's fixed COB-ID",
    why="SDO (0x580+id, 0x600+id), EMCY (0x80+id) and heartbeat (0x700+id) of each node are fixed by "
    "its node-id; a PDO on one of them is taken for that service, or disturbs it.",
    example="node 2: [1800sub1] DefaultValue=0x83\nnode 3 in the network (EMCY 0x83)",
    fix="Move the PDO to a COB-ID that no node's fixed services use.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET008 = define(
    "NET008", E, "entry name matches no entry or several",
    why="The network file names entries to configure and to wire by name; a name must pick exactly one "
    "entry of the node's description, or the master would write a value where nobody meant it.",
    example='[node.values]\n"Input 1" = 1   # 0x6000sub1 and 0x6200sub1 are both named "Input 1"',
    fix="Write the object's name and the sub-entry's (`object/sub`), or the address (`0x6000sub1`).",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET009 = define(
    "NET009", E, "configured entry is read-only or absent in the slave's description",
    why="The master writes each configured value by SDO at boot; a slave refuses a write to an entry its "
    "description declares ro or const (abort 0x06010002) or does not have (0x06020000), and the boot fails. "
    "A PDO mapping is changed between invalidating and validating the PDO's COB-ID (CiA 301), so a "
    "configured mapping needs its PDO's communication object with a COB-ID.",
    example='[node.values]\n"0x1000" = 0x191   # device type, ro',
    fix="Configure only entries the slave's description declares writable (wo, rw, rwr, rww).",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET010 = define(
    "NET010", E, "configured value outside the entry's type or limits",
    why="A slave refuses a value outside the entry's LowLimit/HighLimit (abort 0x06090030-32) or one that is "
    "not of the entry's type; the master's configuration download stops there.",
    example='[node.values]\n"0x1017" = 70000   # UNSIGNED16',
    fix="Give a value of the entry's type, within the limits its description declares.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET011 = define(
    "NET011", E, "identity the master checks cannot match the slave's description",
    why="At boot the master compares the slave's 0x1000 and 0x1018 with what it expects (0x1F84-0x1F88) and "
    "does not start a slave that differs (CiA 302-2 error C, D, M, N, O); an expected value that the "
    "description contradicts, or that it has no entry for, stops the slave for good.",
    example='[[node]]\nfile = "io.eds"   # 0x1018sub1 = 0x1234\nvendor_id = 0x4321',
    fix="Expect the values of the description (leave vendor_id, product_code, revision out), or correct "
    "the description.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET012 = define(
    "NET012", E, "PDO wiring that cannot work",
    why="A `[[pdo]]` table maps entries of the producer into a TPDO and of the consumer into an RPDO: "
    "each pair must be mappable (PDOMapping=1, readable for a TPDO, writable for an RPDO) and of one data "
    "type, the whole must fit a CAN frame (64 bit), both nodes must have that PDO with enough mapping "
    "entries, and two tables must not set one PDO two ways.",
    example='[[pdo]]\nentries = [["Input 1", "Setpoint"]]   # UNSIGNED8 -> INTEGER16',
    fix="Wire entries of the same type, mappable in the PDO's direction, at most 64 bit per PDO.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET013 = define(
    "NET013", E, "heartbeat consumer time not longer than the producer's",
    why="The master watches each slave's heartbeat for `heartbeat` ms (0x1016); a slave that sends one only "
    "every 0x1017 ms, as long or longer, or never (0), is declared lost while healthy (CiA 301 7.2.8.3.2.3).",
    example='[[node]]\nheartbeat = 100\n[node.values]\n"0x1017" = 100',
    fix="Make `heartbeat` longer than the slave's producer heartbeat time (1.5x or more is usual), and "
    "configure 0x1017 when the description's value is 0.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET014 = define(
    "NET014", E, "master's description cannot hold the network",
    why="`odgen network` adds the CiA 302-2 objects and the slave boot status object 0x5F81 to the master's "
    "description; a master description that uses 0x5F81 for something else would lose it.",
    example='[master]\nfile = "master.eds"   # declares [5F81] for its own data',
    fix="Move the description's object away from 0x5F81.",
    blocking="Network findings come from `odgen lint --network` and `odgen network`; `generate` reads one file "
    "and never reports them.")

NET015 = define(
    "NET015", W, "synchronous PDO in a network where no node produces SYNC",
    why="A PDO of transmission type 0..240 (or 252) is sent, or applied, at SYNC (CiA 301 7.2.2.2); a TPDO of "
    "such a type never transmits and an RPDO never takes over what it receives unless a node sends SYNC, "
    "which one does when its 0x1005 has bit 30 (generate) set and its 0x1006 (communication cycle period) "
    "is not 0. The wiring then moves no data, unless a tool on the bus sends SYNC.",
    example='[[pdo]]\nfrom = "master"\ntransmission = 1\n(no node with 0x1005 bit 30 and 0x1006 > 0)',
    fix='Make one node, usually the master, the SYNC producer: `[master.values]` "0x1005" = 0x40000080 and '
    '"0x1006" = the period in µs; or wire the PDO event-driven (`transmission = 254` or 255).')
