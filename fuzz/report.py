"""Write docs/robustness.md from fuzz/robustness.md.in and the tables in fuzz/results/*.json.

    python fuzz/report.py [--results DIR] [--out FILE]

Each results file is one table: {"title", "columns", "rows", "notes"} (other keys are
ignored). The template names the files it places with `{{table NAME.json}}`; a missing
file renders as "not run"; files the template does not name follow at `{{others}}`.
`{{summary}}` is one line per file: its "summary" key, else its first note.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
TEMPLATE = HERE / "robustness.md.in"
RESULTS = HERE / "results"
OUT = HERE.parent / "docs" / "robustness.md"
_PLACE = re.compile(r"\{\{table ([\w.-]+\.json)\}\}")


def load(path: Path) -> dict | None:
    if not path.is_file():
        return None
    try:
        table = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        return {"title": path.name, "columns": [], "rows": [], "notes": [f"unreadable: {err}"]}
    return table if isinstance(table, dict) else {"title": path.name, "notes": ["not a table"]}


def cell(value: object) -> str:
    text = json.dumps(value) if isinstance(value, (list, dict)) else str(value)
    return " ".join(text.replace("|", "\\|").split())


def render(name: str, table: dict | None) -> str:
    if table is None:
        return f"### {name}\n\nNot run: fuzz/results/{name} is missing.\n"
    out = [f"### {cell(table.get('title', name))}\n", f"From fuzz/results/{name}.\n"]
    columns, rows = table.get("columns") or [], table.get("rows") or []
    if columns:
        out.append("| " + " | ".join(cell(c) for c in columns) + " |")
        out.append("| " + " | ".join("---" for _ in columns) + " |")
        out.extend("| " + " | ".join(cell(c) for c in row) + " |" for row in rows)
        out.append("")
    out.extend(f"- {cell(note)}" for note in table.get("notes") or [])
    return "\n".join(out).rstrip() + "\n"


def summary(names: list[str], tables: dict[str, dict | None]) -> str:
    lines = ["Figures of the last run:", ""]
    for name in names:
        table = tables[name]
        if table is None:
            lines.append(f"- {name}: not run.")
            continue
        first = table.get("summary") or (table.get("notes") or [""])[0]
        lines.append(f"- {cell(table.get('title', name))}: {cell(first)}")
    return "\n".join(lines)


def build(template: str, results: Path) -> str:
    placed = _PLACE.findall(template)
    others = sorted(p.name for p in results.glob("*.json") if p.name not in placed)
    tables = {name: load(results / name) for name in [*placed, *others]}
    text = _PLACE.sub(lambda m: render(m.group(1), tables[m.group(1)]).rstrip(), template)
    rest = "\n".join(render(name, tables[name]) for name in others)
    text = text.replace("{{others}}", ("## Other results\n\n" + rest) if rest else "")
    text = text.replace("{{summary}}", summary([*placed, *others], tables))
    return re.sub(r"\n{3,}", "\n\n", text).rstrip() + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", type=Path, default=RESULTS)
    parser.add_argument("--out", type=Path, default=OUT)
    args = parser.parse_args(argv)
    text = build(TEMPLATE.read_text(encoding="utf-8"), args.results)
    tmp = args.out.with_suffix(".md.tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(args.out)
    print(f"report: {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
