"""`odgen network NET.toml -o DIR`: every slave's DCF and concise DCF, and the master's dictionary.

The network is linted first (`odgen lint --network`: every node's description, then the NET rules
on the network as configured); an error there writes nothing. Then, per slave, the DCF holds its
configured values as ParameterValues and the concise DCF the same values as the master writes them
(`odgen.formats.concise`); the master's model gets the CiA 302-2 objects (`master.py`) and goes
through the pipeline as a model built in memory, as `odgen generate` would run on a file.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path

from ..catalogue.objects import OBJ021
from ..cnames import identifier
from ..diagnostics import Diagnostic, Severity
from ..errors import OdgenError
from ..formats.concise import encode, is_pdo_parameter, ordered, communication_of
from ..formats.eds_writer import write_eds
from ..lint.driver import RuleFilter
from ..lint.netconfig import NodeModel
from ..lint.network import lint_network_nodes
from ..lint.passes import LintOptions
from ..model import ObjectDictionary
from ..model.od import Section
from ..pipeline import Request, Result, generate
from .master import master_model


@dataclass
class NetworkOutput:
    findings: list[Diagnostic]  # the network lint's and the master generation's, errors and warnings
    files: dict[str, str | bytes] = field(default_factory=dict)  # file name -> content; empty when refused
    refused: bool = False


def build(path: Path, lookup: str = "hash") -> NetworkOutput:
    """Every output file of the network at `path`, or the findings that refuse it; nothing is written here."""
    linted = lint_network_nodes(path, LintOptions(), RuleFilter())
    findings = [d for r in linted.results for d in r.diagnostics if d.severity >= Severity.WARNING]
    if linted.unreadable or any(d.severity >= Severity.ERROR and (d.rule.startswith("NET") or d.blocks)
                                for d in findings):
        return NetworkOutput(findings, refused=True)
    master = next((n for n in linted.nodes if n.spec.master), None)
    if master is None:
        raise OdgenError(f"{path}: odgen network needs a [master] table (docs/network.md)")
    slaves = [n for n in linted.nodes if not n.spec.master]
    files: dict[str, str | bytes] = {}
    concise: dict[int, bytes] = {}
    for slave in slaves:
        concise[slave.node_id] = concise_dcf(slave)
        files[f"{slave.spec.name}.bin"] = concise[slave.node_id]
        files[f"{slave.spec.name}.dcf"] = write_eds(as_dcf(slave))
    name = identifier(master.spec.name, "master")
    model = master_model(master, slaves, concise, {s.node_id: f"{s.spec.name}.bin" for s in slaves})
    files[f"{master.spec.name}.dcf"] = write_eds(model)
    # OBJ021 (a DOMAIN with a DefaultValue) is how the concise DCFs travel in the model; the master's
    # own description was linted above, so its OBJ021 findings are already reported.
    result = generate(Request(Path(f"{master.spec.name}.dcf"), name=name, node_id=master.node_id, lookup=lookup,
                              model=model, rule_filter=RuleFilter(ignore=(OBJ021.id,))))
    seen = {(d.rule, d.index, d.sub, d.message) for d in findings}
    findings += [d for d in result.diags.sorted() if d.severity >= Severity.WARNING and d.rule != OBJ021.id
                 and (d.rule, d.index, d.sub, d.message) not in seen]
    if not result.files:
        return NetworkOutput(findings + _refused(result), refused=True)
    files.update(result.files)
    return NetworkOutput(findings, files)


def _refused(result: Result) -> list[Diagnostic]:
    return [d for d in result.refused if d.severity < Severity.WARNING]


def concise_dcf(node: NodeModel) -> bytes:
    """The node's configured values as the master writes them (CiA 306 concise DCF)."""
    values = {key: node.data(*key) for key in node.values}
    pdos = {communication_of(i) for i, _ in values if is_pdo_parameter(i)}
    cob_ids = {comm: node.in_force(comm, 1) or 0 for comm in pdos}
    return encode(ordered(values, cob_ids))


def as_dcf(node: NodeModel) -> ObjectDictionary:
    """The node's description as a DCF: configured values as ParameterValues, its node-id commissioned."""
    od = node.configured_od()
    od.sections = dict(od.sections)
    section = copy.deepcopy(od.sections.get("devicecomissioning"))
    section = section if section is not None else Section("DeviceComissioning")
    section.set("NodeID", f"0x{node.node_id:02X}")
    od.sections["devicecomissioning"] = section
    return od
