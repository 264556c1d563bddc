"""XML: XDD/XDC reading (CiA 311), reported by the XML reader."""

from __future__ import annotations

from .rule import E, W, define

XML001 = define(
    "XML001", E, "not well-formed XML", ref="XML 1.0",
    why="The file breaks the XML syntax (unclosed tag, bad character, wrong encoding), so no XML "
    "tool can read it; odgen stops at the first such error.",
    example='<CANopenObject index="1000" name="Device type"',
    fix="Correct the syntax at the reported line; save the file in the encoding its XML "
    "declaration names (normally UTF-8).",
    blocks=True,
    blocking="Nothing can be read from a file that is not XML.",
    no_repair="There is no dictionary to repair.")

XML002 = define(
    "XML002", E, "not a CiA 311 device description", ref="CiA 311 (ISO 15745 container)",
    why="An XDD/XDC starts with `ISO15745ProfileContainer` in the CANopen namespace "
    "`http://www.canopen.org/xml/1.1` (or `/1.0`). Another root, such as a PROFINET GSDML "
    "profile, is a different format and is not read.",
    example='<ISO15745Profile xmlns="http://www.profibus.com/GSDML/2003/11/DeviceProfile">',
    fix='Write the file as CiA 311: `<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1">` '
    "holding the device and communication network profiles, or convert it to an EDS.",
    blocks=True,
    blocking="The file describes no CANopen device.",
    no_repair="There is no dictionary to repair.")

XML003 = define(
    "XML003", E, "document type declaration refused", ref="CiA 311; XML security",
    why="CiA 311 files have no DOCTYPE. A DTD can declare entities that read local files (XXE) or "
    "expand to gigabytes (billion laughs); odgen does not expand them and does not read such files.",
    example='<!DOCTYPE x [<!ENTITY e SYSTEM "file:///etc/passwd">]>',
    fix="Remove the DOCTYPE declaration and write the text in place of each entity reference.",
    blocks=True,
    blocking="The file is refused before it is read, for safety.",
    no_repair="A document type declaration is refused for safety, never guessed around.")

XML004 = define(
    "XML004", E, "does not match the CiA 311 schema", ref="CiA 311 schema; schemas/cia311-odgen.xsd",
    why="An element or attribute is missing, misplaced, unknown or of the wrong form. Other tools "
    "(CANopenEditor, vendor configurators) validate against the CiA schema and refuse such files "
    "or drop the part.",
    example='<CANopenSubObject subIndex="01" objectType="7" PDOmapping="no"/>  (no name)',
    fix="Add, move or correct the element or attribute as the message says.",
    blocking="The reader reads every value it uses itself and reports one it cannot read as XML005-XML011 (which "
    "block); a deviation it does not read, such as a header time or element order, leaves the dictionary "
    "as written.")

XML005 = define(
    "XML005", E, "attribute value cannot be read", ref="CiA 311 CANopenObjectList",
    why="odgen needs this attribute to place or type the entry: an object without a readable "
    "`index`, or a sub-object without a readable `subIndex`, is skipped; an unreadable `dataType`, "
    "`objectType`, `subNumber`, `objFlags` or `PDOmapping` is left unset.",
    example='<CANopenObject index="10x0" name="Device type" objectType="7"/>',
    fix='Write index as 4 hex digits ("1000"), subIndex as 2 ("0A"), dataType as hex ("0007"), '
    'objectType and subNumber in decimal ("7") and PDOmapping as no/default/optional/TPDO/RPDO.',
    blocks=True,
    blocking="The entry is skipped or left untyped, so the C would not match the file.",
    no_repair="What the attribute was meant to say is unknown.")

XML006 = define(
    "XML006", E, "duplicate object index", ref="CiA 311 CANopenObjectList",
    why="An index may be described once. Tools disagree on which copy wins; odgen keeps the first.",
    example='<CANopenObject index="2000" .../>\n<CANopenObject index="2000" .../>',
    fix="Remove or renumber one of the objects.",
    blocks=True,
    blocking="Two definitions of one object: the C would follow one of them and not match the other.",
    no_repair="Which copy the device has is unknown.")

XML007 = define(
    "XML007", E, "duplicate sub-index", ref="CiA 311 CANopenObjectList",
    why="A sub-index may appear once in an object. odgen keeps the first.",
    example='<CANopenSubObject subIndex="01" .../>\n<CANopenSubObject subIndex="01" .../>',
    fix="Remove or renumber one of the sub-objects.",
    blocks=True,
    blocking="Two definitions of one sub-object: the C would follow one of them and not match the other.",
    no_repair="Which copy the device has is unknown.")

XML008 = define(
    "XML008", E, "uniqueIDRef names no parameter", ref="CiA 311 uniqueIDRef",
    why="An object that takes its data type, access and values from a parameter of the device "
    "profile (as CANopenEditor writes every object) loses them when the parameter does not exist.",
    example='<CANopenObject index="2000" name="Speed" objectType="7" uniqueIDRef="UID_OBJ_2000"/>\n'
    "(no <parameter uniqueID=\"UID_OBJ_2000\">)",
    fix="Add the parameter to ApplicationProcess/parameterList, or correct the reference.",
    blocks=True,
    blocking="The entry's value, type or access is in the parameter that cannot be found, so the C would miss it.",
    no_repair="Which parameter was meant is unknown.")

XML009 = define(
    "XML009", W, "object attribute and its parameter disagree", ref="CiA 311 uniqueIDRef",
    why="The entry states a data type, access or value both on the CANopenObject and in the "
    "referenced parameter, differently. Tools pick different sides (CANopenEditor the parameter); "
    "odgen takes the CANopenObject attribute.",
    example='<CANopenObject index="2000" dataType="0007" uniqueIDRef="P"/>\n'
    '<parameter uniqueID="P"><label lang="en">Speed</label><UINT/></parameter>',
    fix="Make both agree, or state the value in one place only.")

XML010 = define(
    "XML010", E, "no object dictionary", ref="CiA 311 ApplicationLayers",
    why="The file has no `CANopenObjectList`, so it describes no object and nothing can be "
    "checked or generated.",
    example="<ApplicationLayers>\n  <dummyUsage>...</dummyUsage>\n</ApplicationLayers>",
    fix="Add the communication network profile with ApplicationLayers/CANopenObjectList.",
    blocks=True,
    blocking="There is no dictionary to generate.",
    no_repair="There is no dictionary to repair.")

XML011 = define(
    "XML011", E, "sub-objects on a single-value object", ref="CiA 311 CANopenObject",
    why="A VAR, DOMAIN or DEFTYPE object has exactly one value, described by the CANopenObject "
    "itself; its CANopenSubObject children are ignored.",
    example='<CANopenObject index="2000" objectType="7" ...>\n'
    '  <CANopenSubObject subIndex="00" .../>\n</CANopenObject>',
    fix='Make the object an ARRAY (objectType="8") or RECORD ("9"), or remove the sub-objects.',
    blocks=True,
    blocking="Whether the object is one value or a container is unclear, so the C would match one reading only.",
    no_repair="Which of the two the device has is unknown.")

XML012 = define(
    "XML012", W, "attribute value not in CiA 311 notation", ref="CiA 311 CANopenObjectList",
    why="The value is readable, and odgen reads it, but it is not written as CiA 311 says "
    "(for example an EDS word or a 0x prefix); stricter tools refuse it.",
    example='<CANopenObject index="0x2000" ... accessType="rww"/>',
    fix='Write index without 0x ("2000"), accessType as const/ro/wo/rw with PDOmapping="RPDO" '
    '(or "TPDO") for what EDS calls rww (rwr).')

XML013 = define(
    "XML013", W, "value on an ARRAY/RECORD object ignored", ref="CiA 311 CANopenObject",
    why="An ARRAY or RECORD has no value of its own: data type, access, values and PDO mapping "
    "belong to its sub-objects. CANopenEditor writes the actual values of an XDC's sub-objects "
    "onto the object's parameter by mistake; odgen ignores them.",
    example='<CANopenObject index="1018" objectType="9" dataType="0007" ...>',
    fix="Move the attribute or value to the sub-objects it belongs to.")
