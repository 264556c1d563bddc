"""Generation speed, whole process: `odgen lint` and `odgen generate` next to objdictgen's
`odg convert X.eds X.c` and `canopen.import_od`, on the same files, taking turns in one run.

Times include interpreter start-up, as in ../shared/notes/peer-measurements.md. The peers run
from build/bench-venv (make bench installs them); a peer that is missing is reported, not faked.
CANopenEditor cannot be installed here: its figure is the one in the notes, labelled so.
"""

from __future__ import annotations

import compileall
import math
import shutil
from pathlib import Path

from common import BUILD, ODGEN, PEER_PYTHON, PEER_VENV, ROOT, Run, Target, interleaved, median, synth_label, timed

REPEAT = 5
REPEAT_LARGE = 3  # 16000 objects; common.interleaved runs a tool that needs over 20 s only once
CANOPENEDITOR_4000_S = 2.51  # notes, section 2 (EDSSharp under Mono), not measured here
OBJDICTGEN_4000_NOTES_S = 4.80
TARGET_4000_S = 0.5
TARGET_SPEEDUP = 5.0
TARGET_OBJDICTGEN = 10.0  # >= 10x faster than objdictgen in the same run
# Whole process against python canopen's import_od of the same file in the same run.
TARGET_GENERATE_VS_CANOPEN = 0.40
TARGET_LINT_VS_CANOPEN = 0.25
TOOLS = ("odgen lint", "odgen generate", "objdictgen odg convert", "canopen import_od")
# Synthetic inputs put 0x4000-0x5FFF into a persistence group of its own: a storage class's
# value block holds at most 64 KiB (GEN007), which 16000 RAM objects exceed.
SPLIT_OPTIONS = '[[entry]]\nmatch = "0x4000-0x5FFF"\nstorage = "persist:bulk"\n'


def _commands(label: str, eds: Path) -> dict:
    work = BUILD / "speed" / label
    shutil.rmtree(work, ignore_errors=True)
    (work / "odg").mkdir(parents=True)
    generate = [*ODGEN, "generate", str(eds), "-o", str(work / "odgen"), "--name", "od"]
    if label.startswith("synth_"):
        (work / "split.toml").write_text(SPLIT_OPTIONS)
        generate += ["--options", str(work / "split.toml")]
    commands = {
        "odgen lint": lambda: timed([*ODGEN, "lint", str(eds)]),
        "odgen generate": lambda: timed(generate),
    }
    if PEER_PYTHON.is_file():
        odg = [str(PEER_VENV / "bin" / "odg"), "convert", str(eds), str(work / "odg" / f"{label}.c")]
        commands["objdictgen odg convert"] = lambda: timed(odg)
        imp = [str(PEER_PYTHON), "-c", "import sys, canopen; canopen.import_od(sys.argv[1])", str(eds)]
        commands["canopen import_od"] = lambda: timed(imp)
    return commands


def _cell(runs: list[Run], ok_codes: tuple[int, ...]) -> dict[str, object]:
    failed = [r for r in runs if r.returncode not in ok_codes]
    cell: dict[str, object] = {"median_s": median(runs), "runs": len(runs),
                               "runs_s": [round(r.seconds, 4) for r in runs]}
    if failed:
        cell["failed"] = failed[0].error or f"exit {failed[0].returncode}"
    return cell


def measure(label: str, eds: Path) -> dict[str, object]:
    repeat = REPEAT_LARGE if label == synth_label(16000) else REPEAT
    runs = interleaved(_commands(label, eds), repeat)
    ok = {"odgen lint": (0, 1)}  # lint exits 1 when it finds errors: a finished run
    row: dict[str, object] = {"input": label, "repeat": repeat}
    for tool, tool_runs in runs.items():
        row[tool] = _cell(tool_runs, ok.get(tool, (0,)))
    return row


def _fmt(cell: object, tool: str) -> str:
    if not isinstance(cell, dict):
        return "not installed"
    if "failed" in cell:
        word = "refused" if tool.startswith("odgen") else "FAIL"
        return f"{word} ({cell['median_s']:.2f} s): {cell['failed']}"
    once = " (1 run)" if cell["runs"] == 1 else ""
    return f"{cell['median_s']:.3f} s{once}"


def _ok(row: dict, tool: str) -> float | None:
    cell = row.get(tool)
    return float(cell["median_s"]) if isinstance(cell, dict) and "failed" not in cell else None


def _exponent(rows: list[dict], tool: str) -> float | None:
    """Growth exponent between 4000 and 16000 objects: 1.0 is linear."""
    by = {r["input"]: _ok(r, tool) for r in rows}
    small, big = by.get(synth_label(4000)), by.get(synth_label(16000))
    return math.log(big / small) / math.log(4) if small and big else None


def _against_canopen(row: dict, gen: float | None) -> list[Target]:
    """odgen generate and lint as a share of python canopen's import_od, whole process, same run."""
    canopen, lint = _ok(row, "canopen import_od"), _ok(row, "odgen lint")
    out = []
    for what, mine, goal in (("generate", gen, TARGET_GENERATE_VS_CANOPEN), ("lint", lint, TARGET_LINT_VS_CANOPEN)):
        if mine and canopen:
            out.append(Target(f"odgen {what} vs canopen import_od, same run, 4000 objects", f"<= {goal:.2f}x",
                              f"{mine:.3f} s / {canopen:.3f} s", f"{mine / canopen:.2f}x", mine / canopen <= goal))
    return out


def targets(rows: list[dict]) -> list[Target]:
    row = next((r for r in rows if r["input"] == synth_label(4000)), None)
    if row is None:
        return []
    gen, odg = _ok(row, "odgen generate"), _ok(row, "objdictgen odg convert")
    out = [Target("odgen generate, 4000 objects", f"<= {TARGET_4000_S} s", f"{gen:.3f} s" if gen else "-",
                  f"{gen / TARGET_4000_S:.0%} of budget" if gen else "-", gen is not None and gen <= TARGET_4000_S)]
    fastest = min(p for p in (CANOPENEDITOR_4000_S, odg) if p)
    which = "CANopenEditor (notes)" if fastest == CANOPENEDITOR_4000_S else "objdictgen (this run)"
    speedup = fastest / gen if gen else None
    out.append(Target("speed-up over the fastest peer emitting C, 4000 objects", f">= {TARGET_SPEEDUP:.0f}x",
                      f"{which} {fastest:.2f} s / odgen {gen:.3f} s" if gen else "-",
                      f"{speedup:.1f}x" if speedup else "-", speedup is not None and speedup >= TARGET_SPEEDUP))
    if odg and gen:
        out.append(Target("speed-up over objdictgen, same run, 4000 objects", f">= {TARGET_OBJDICTGEN:.0f}x",
                          f"{odg:.2f} s / {gen:.3f} s", f"{odg / gen:.1f}x", odg / gen >= TARGET_OBJDICTGEN))
    out += _against_canopen(row, gen)
    exp = _exponent(rows, "odgen generate")
    out.append(Target("linear growth of odgen generate (4000 -> 16000 objects)", "exponent <= 1.10",
                      f"time x{4 ** exp:.2f} for 4x the objects" if exp else "-",
                      f"exponent {exp:.2f}" if exp else "-", exp is not None and exp <= 1.10))
    return out


def markdown(rows: list[dict]) -> str:
    lines = ["## Generation speed (whole process, median of repeated runs, tools taking turns)", "",
             "| input | runs | " + " | ".join(TOOLS) + " | objdictgen / odgen generate |",
             "|---|---:|" + "---:|" * (len(TOOLS) + 1)]
    for r in rows:
        cells = [_fmt(r.get(tool), tool) for tool in TOOLS]
        gen, odg = _ok(r, "odgen generate"), _ok(r, "objdictgen odg convert")
        ratio = f"{odg / gen:.1f}x" if gen and odg else "-"
        lines.append(f"| {r['input']} | {r['repeat']} | " + " | ".join(cells) + f" | {ratio} |")
    lines += ["", f"CANopenEditor (EDSSharp under Mono) is not installable here; the notes give "
              f"{CANOPENEDITOR_4000_S} s for 4000 objects (objdictgen {OBJDICTGEN_4000_NOTES_S} s there, same "
              "machine kind). Growth exponents between 4000 and 16000 objects (1.0 = linear): "
              + ", ".join(f"{t} {e:.2f}" for t in TOOLS if (e := _exponent(rows, t)) is not None) + ". "
              "On synthetic inputs `odgen generate` puts 0x4000-0x5FFF into a persistence group of its own "
              "(an options file): one storage class holds at most 64 KiB of values (GEN007).",
              "", "![time against objects](growth.svg)", ""]
    return "\n".join(lines)


def svg(rows: list[dict]) -> str:
    """Time against number of objects for each tool, linear axes, hand-written SVG."""
    series = {}
    for tool in TOOLS:
        points = [(int(str(r["input"]).split("_")[1]), t) for r in rows
                  if str(r["input"]).startswith("synth_") and (t := _ok(r, tool)) is not None]
        if points:
            series[tool] = points
    width, height, left, bottom, top, right = 640, 400, 60, 50, 20, 180
    xmax = max((x for pts in series.values() for x, _ in pts), default=1)
    ymax = max((y for pts in series.values() for _, y in pts), default=1.0) * 1.05
    plot_w, plot_h = width - left - right, height - top - bottom

    def px(x: float, y: float) -> tuple[float, float]:
        return left + plot_w * x / xmax, top + plot_h * (1 - y / ymax)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" '
           'font-size="11">', f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<line x1="{left}" y1="{top + plot_h}" x2="{left + plot_w}" y2="{top + plot_h}" stroke="black"/>',
           f'<line x1="{left}" y1="{top}" x2="{left}" y2="{top + plot_h}" stroke="black"/>']
    for k in range(5):
        x, y = xmax * k / 4, ymax * k / 4
        gx, _ = px(x, 0)
        _, gy = px(0, y)
        out.append(f'<text x="{gx:.1f}" y="{top + plot_h + 15}" text-anchor="middle">{x:.0f}</text>')
        out.append(f'<text x="{left - 5}" y="{gy + 4:.1f}" text-anchor="end">{y:.1f}</text>')
        out.append(f'<line x1="{left}" y1="{gy:.1f}" x2="{left + plot_w}" y2="{gy:.1f}" stroke="#ddd"/>')
    out.append(f'<text x="{left + plot_w / 2}" y="{height - 10}" text-anchor="middle">objects (synthetic EDS)'
               '</text>')
    out.append(f'<text x="15" y="{top + plot_h / 2}" transform="rotate(-90 15 {top + plot_h / 2})" '
               'text-anchor="middle">seconds, whole process</text>')
    colours = ("#1f77b4", "#2ca02c", "#d62728", "#9467bd")
    for k, (tool, pts) in enumerate(series.items()):
        colour = colours[k % len(colours)]
        path = " ".join(f"{a:.1f},{b:.1f}" for a, b in (px(x, y) for x, y in pts))
        out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="2"/>')
        out += [f'<circle cx="{a:.1f}" cy="{b:.1f}" r="3" fill="{colour}"/>' for a, b in (px(x, y) for x, y in pts)]
        ly = top + 15 + 18 * k
        out.append(f'<line x1="{left + plot_w + 10}" y1="{ly - 4}" x2="{left + plot_w + 30}" y2="{ly - 4}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{left + plot_w + 35}" y="{ly}">{tool}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def run(labels: dict[str, Path]) -> dict[str, object]:
    compileall.compile_dir(str(ROOT / "odgen"), quiet=1)  # as pip install does (startup.py): not timed
    rows = [measure(label, eds) for label, eds in labels.items()]
    return {"rows": rows, "targets": targets(rows), "markdown": markdown(rows), "svg": svg(rows)}
