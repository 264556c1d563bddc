"""NET: a network of nodes (odgen lint --network)."""

from __future__ import annotations

from .rule import E, W, define

NET001 = define(
    "NET001", E, "network file is not a list of nodes",
    why="NET.toml lists the nodes as `[[node]]` tables, each with `file` (relative to NET.toml) "
    "and `node_id`; anything else cannot be checked.",
    example='[[node]]\nfile = "slave.eds"\n(no node_id)',
    fix="Give every [[node]] a `file` string and a `node_id` integer, and nothing else.",
    blocking="Network findings come from `odgen lint --network`; `generate` reads one file and never reports them.")

NET002 = define(
    "NET002", E, "node-id outside 1..127 or used twice",
    why="Every node of a CANopen network has its own node-id 1..127; the fixed COB-IDs (SDO, EMCY, "
    "heartbeat) and every `$NODEID` value derive from it, so two nodes with one id collide on all of them.",
    example='[[node]]\nfile = "a.eds"\nnode_id = 2\n[[node]]\nfile = "b.eds"\nnode_id = 2',
    fix="Give each node a distinct node-id in 1..127.",
    blocking="Network findings come from `odgen lint --network`; `generate` reads one file and never reports them.")

NET003 = define(
    "NET003", E, "node's file is missing or unreadable",
    why="A node whose description cannot be read cannot be checked against the others.",
    example='[[node]]\nfile = "missing.eds"\nnode_id = 2',
    fix="Correct the path (relative to NET.toml) or add the file.",
    blocking="Network findings come from `odgen lint --network`; `generate` reads one file and never reports them.")

NET004 = define(
    "NET004", E, "two TPDOs transmit the same COB-ID",
    why="A COB-ID has exactly one producer; two nodes transmitting the same identifier with different "
    "data cause bus errors (same identifier, different bits) or frames that consumers misread.",
    example="node 2: [1800sub1] DefaultValue=0x182\nnode 4: [1800sub1] DefaultValue=0x182",
    fix="Give one of the TPDOs another COB-ID, or disable it (bit 31).",
    blocking="Network findings come from `odgen lint --network`; `generate` reads one file and never reports them.")

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
    blocking="Network findings come from `odgen lint --network`; `generate` reads one file and never reports them.")

NET007 = define(
    "NET007", E, "PDO COB-ID collides with another node's fixed COB-ID",
    why="SDO (0x580+id, 0x600+id), EMCY (0x80+id) and heartbeat (0x700+id) of each node are fixed by "
    "its node-id; a PDO on one of them is taken for that service, or disturbs it.",
    example="node 2: [1800sub1] DefaultValue=0x83\nnode 3 in the network (EMCY 0x83)",
    fix="Move the PDO to a COB-ID that no node's fixed services use.",
    blocking="Network findings come from `odgen lint --network`; `generate` reads one file and never reports them.")
