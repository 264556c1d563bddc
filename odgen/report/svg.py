"""SVG pictures of the report: a PDO's bit layout and the memory map as bars.

Plain SVG 1.1 with presentation attributes (no CSS, no script, no external reference), so the
same text works inline in the HTML page and as a file next to the Markdown form. Boxes carry
their bit offset and width as data attributes; x = LEFT + bit * scale and width = bits * scale,
with the scale written on the <svg> element (tests/test_htmlreport.py checks both).
"""

from __future__ import annotations

from html import escape

from ..codegen.memory import MemoryRow
from .view import Box, Lane, Pdo

LEFT, TOP, LANE, GAP = 120, 26, 44, 8
CHAR = 6  # px per character of the 10 px font, for deciding what fits in a box
FILL = {"TPDO": "#cfe3ff", "RPDO": "#d4f0d0"}
PALETTE = ("#4e79a7", "#f28e2b", "#59a14f", "#b07aa1", "#edc948", "#76b7b2", "#ff9da7", "#9c755f", "#bab0ac")


def _attrs(**values: object) -> str:
    return " ".join(f'{k.rstrip("_").replace("_", "-")}="{escape(str(v))}"' for k, v in values.items())


def _el(tag: str, **values: object) -> str:
    return f"<{tag} {_attrs(**values)}/>"


def _text(x: float, y: float, text: str, size: int = 10, anchor: str = "start", weight: str = "normal") -> str:
    return (f'<text {_attrs(x=x, y=y, font_size=size, text_anchor=anchor, font_weight=weight)} '
            f'font-family="sans-serif" fill="#222">{escape(text)}</text>')


def _fit(text: str, width: int) -> str:
    room = (width - 6) // CHAR
    if room < 2:
        return ""
    return text if len(text) <= room else text[: room - 1] + "…"


def ruler_bits(pdo: Pdo) -> int:
    return max(pdo.frame_bits, -(-pdo.used_bits // 8) * 8)


def scale_of(bits: int) -> int:
    return min(12, max(1, 1024 // bits))


def _ruler(bits: int, scale: int, bottom: int) -> list[str]:
    out = [_el("line", x1=LEFT, y1=TOP, x2=LEFT + bits * scale, y2=TOP, stroke="#444")]
    label_every = 8 if bits <= 128 else 64
    for bit in range(0, bits + 1, 8 if scale < 4 else 1):
        x, labelled = LEFT + bit * scale, bit % label_every == 0
        out.append(_el("line", x1=x, y1=TOP - (6 if bit % 8 == 0 else 3), x2=x, y2=TOP, stroke="#444"))
        if labelled:  # a faint guide line down through the lanes, and the bit number
            out.append(_el("line", x1=x, y1=TOP, x2=x, y2=bottom, stroke="#ddd"))
            out.append(_text(x, TOP - 9, str(bit), 9, "middle"))
    return out


def _box(b: Box, y: int, scale: int, fill: str) -> list[str]:
    x, width = LEFT + b.bit * scale, b.bits * scale
    title = f"{b.address} {b.name}: bits {b.bit}..{b.bit + b.bits - 1} ({b.bits} bit)"
    look = {"fill": "#eeeeee", "stroke_dasharray": "4 3"} if b.dummy else {"fill": fill}
    rect = _el("rect", class_="box dummy" if b.dummy else "box", x=x, y=y, width=width, height=LANE,
               stroke="#555", data_bit=b.bit, data_bits=b.bits, data_target=b.target, **look)
    out = [f"<g><title>{escape(title)}</title>{rect}"]
    name = _fit(b.name, width)
    if name:
        out.append(_text(x + 3, y + 16, name, 10, weight="bold"))
        out.append(_text(x + 3, y + 32, _fit(f"{b.address} · {b.bits}b", width), 9))
    out.append("</g>")
    return out


def _lane(lane: Lane, y: int, frame: int, scale: int) -> list[str]:
    """The lane's label, its boxes, the unused bits of the frame (dashed) and bits past it (red)."""
    out = [_text(4, y + LANE // 2 + 4, lane.label, 10, weight="bold")]
    used = max((b.bit + b.bits for b in lane.boxes), default=0)
    if used < frame:
        gap = _el("rect", class_="gap", x=LEFT + used * scale, y=y, width=(frame - used) * scale,
                  height=LANE, fill="#ffffff", stroke="#999", stroke_dasharray="2 2")
        label = _text(LEFT + used * scale + 3, y + LANE // 2 + 4, _fit(f"unused {frame - used} bit",
                                                                      (frame - used) * scale), 9)
        out.append(f"<g><title>unused: bits {used}..{frame - 1}</title>{gap}{label}</g>")
    if used > frame:
        out.append(_el("rect", class_="overflow", x=LEFT + frame * scale, y=y - 3, width=(used - frame) * scale,
                       height=LANE + 6, fill="#f8c4c4"))
    fill = FILL["RPDO" if "RPDO" in lane.label else "TPDO"]
    for b in lane.boxes:
        out += _box(b, y, scale, fill)
    return out


def pdo_svg(pdo: Pdo) -> str:
    bits = ruler_bits(pdo)
    scale = scale_of(bits)
    height = TOP + GAP + len(pdo.lanes) * (LANE + GAP)
    width = LEFT + bits * scale + 12
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" {_attrs(class_="pdo", width=width, height=height)} '
           f'{_attrs(viewBox=f"0 0 {width} {height}", data_pdo=pdo.key, data_scale=scale, data_left=LEFT)}>',
           f"<title>{escape(pdo.kind)}{pdo.number} bit layout</title>"]
    out += _ruler(bits, scale, height - GAP)
    for n, lane in enumerate(pdo.lanes):
        out += _lane(lane, TOP + GAP + n * (LANE + GAP), pdo.frame_bits, scale)
    out.append("</svg>")
    return "\n".join(out) + "\n"


def memory_svg(rows: list[MemoryRow]) -> str:
    """Two stacked bars, FLASH and RAM, one segment per value block or table."""
    bars = (("FLASH", [(r, r.flash) for r in rows if r.flash]), ("RAM", [(r, r.ram) for r in rows if r.ram]))
    most = max((sum(n for _, n in segs) for _, segs in bars), default=0) or 1
    span = 640
    colour = {r.label: PALETTE[n % len(PALETTE)] for n, r in enumerate(rows)}
    height = 2 * 40 + 24 + 18 * ((len(rows) + 2) // 3)
    width = LEFT + span + 90
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" {_attrs(class_="memory", width=width, height=height)} '
           f'{_attrs(viewBox=f"0 0 {width} {height}")}>', "<title>memory map</title>"]
    for n, (place, segs) in enumerate(bars):
        y, x = 8 + n * 40, float(LEFT)
        out.append(_text(4, y + 19, place, 11, weight="bold"))
        for row, size in segs:
            w = size * span / most
            seg = _el("rect", class_="seg", x=f"{x:.2f}", y=y, width=f"{w:.2f}", height=28, fill=colour[row.label],
                      data_label=row.label, data_bytes=size, data_place=place)
            out.append(f"<g><title>{escape(row.label)}: {size} bytes in {place}</title>{seg}</g>")
            x += w
        out.append(_text(x + 6, y + 19, f"{sum(s for _, s in segs)} bytes", 10))
    for n, row in enumerate(rows):
        x, y = 4 + (n % 3) * 250, 2 * 40 + 18 + (n // 3) * 18
        out.append(_el("rect", x=x, y=y - 9, width=10, height=10, fill=colour[row.label]))
        out.append(_text(x + 14, y, f"{row.kind} {row.label}: {row.size} B ({row.place})", 10))
    out.append("</svg>")
    return "\n".join(out) + "\n"
