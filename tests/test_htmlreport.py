"""`odgen report`: pages rendered by headless Chromium and checked in the DOM it builds.

A sample of the corpus (every k-th file, about ten, and a file of each format) is reported, loaded by Chromium with the
network cut off, dumped as DOM and photographed into build/test-reports/report/. The DOM must
have a row per entry, a box per mapped entry at its bit offset and width (decoded here from
the raw mapping values), every lint finding in its entry's row, and nothing that fetches.
Chromium is installed by `make sysdeps`; without it these tests fail rather than skip.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import lxml.etree
import lxml.html
import pytest

from odgen.check import run_check
from odgen.pipeline import Request
from odgen.codegen.memory import memory_rows
from odgen.formats import load_path
from odgen.report.render import render_html, render_markdown
from odgen.report.view import build_report, row_key
from odgen.model import ObjectDictionary
from odgen.model.values import plain_int

from .conftest import BUILD, FIXTURES, ROOT, corpus_files, lint

OUT = BUILD / "report"
SAMPLE_SIZE = 10
EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
EXAMPLE_OPTIONS = EXAMPLE.with_suffix(".toml")
NETWORK = FIXTURES / "network" / "NET006.toml"
NO_NETWORK = ("--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND",
              "--disable-background-networking", "--disable-component-update", "--no-first-run")


def _sample() -> list:
    files = corpus_files()
    if not files:
        return [pytest.param(None, marks=pytest.mark.skip(reason="../shared/corpus is absent"))]
    step = max(1, len(files) // SAMPLE_SIZE)
    sample = files[::step]
    sample += [next(p for p in files if p.suffix == suffix) for suffix in sorted({p.suffix for p in files})
               if all(q.suffix != suffix for q in sample)]  # every format at least once
    return [pytest.param(p, id=p.name) for p in sample]


def chromium(page: Path, *args: str) -> str:
    exe = shutil.which("chromium")
    if exe is None:
        pytest.fail("chromium is not installed: `make sysdeps` installs it (Debian package chromium)")
    # a profile per pytest-xdist worker: two Chromiums running at once must not share one
    profile = OUT / "-".join(["chromium-profile", *filter(None, [os.environ.get("PYTEST_XDIST_WORKER")])])
    cmd = [exe, "--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={profile}", *NO_NETWORK,
           *args, page.resolve().as_uri()]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=120, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


def page_requests(netlog: Path) -> list[str]:
    """The URLs the page asked for, from Chromium's network log. Chromium's own background
    requests (updates, accounts) carry the initiator "not an origin"; a file:// page's carry its
    opaque origin "null" (test_page_requests_are_seen shows the check sees them)."""
    events = json.loads(netlog.read_text(encoding="utf-8"))["events"]
    return sorted({e["params"]["url"] for e in events if "url" in e.get("params", {})
                   and e["params"].get("initiator", "not an origin") != "not an origin"})


def expected_layouts(od: ObjectDictionary) -> dict[str, list[tuple[int, int]] | None]:
    """(bit, bits) per mapped entry, from the raw 0xIIIISSLL values; None where sub0 or an entry is
    not a plain number (the report still draws what the lint pass makes of them)."""
    layouts: dict[str, list[tuple[int, int]] | None] = {}
    for obj in od.sorted_objects():
        kind = "tpdo" if 0x1A00 <= obj.index < 0x1C00 else "rpdo" if 0x1600 <= obj.index < 0x1800 else None
        if kind is None or obj.is_var:
            continue
        key = f"{kind}{obj.index - (0x1A00 if kind == 'tpdo' else 0x1600) + 1}"
        sub0 = obj.subs.get(0)
        count = plain_int(od.value_in_force(sub0)) if sub0 is not None else None
        raws = [plain_int(od.value_in_force(obj.subs[n])) if n in obj.subs else None
                for n in range(1, (count or 0) + 1)]
        if count is None or count > 64 or None in raws or sub0 is None or sub0.compact:
            layouts[key] = None
            continue
        boxes, bit = [], 0
        for raw in raws:
            if raw:
                boxes.append((bit, raw & 0xFF))
                bit += raw & 0xFF
        layouts[key] = boxes
    return layouts


def _check_rows(dom: lxml.html.HtmlElement, od: ObjectDictionary) -> None:
    rows = dom.xpath('//table[@class="od"]//tr[contains(@class, "entry")]')
    want = [row_key(obj.index, sub.subindex) for obj in od.sorted_objects() for sub in obj.sorted_subs()]
    assert [r.get("id") for r in rows] == want


def _check_pdos(dom: lxml.html.HtmlElement, od: ObjectDictionary) -> None:
    for key, layout in expected_layouts(od).items():
        svgs = dom.xpath(f'//section[@id="{key}"]//*[local-name()="svg"]')
        assert len(svgs) == 1, f"{key}: one picture"
        svg = svgs[0]
        left, scale = int(svg.get("data-left")), int(svg.get("data-scale"))
        boxes = svg.xpath('.//*[local-name()="rect"][contains(@class, "box")]')
        drawn = [(int(b.get("data-bit")), int(b.get("data-bits"))) for b in boxes]
        for b, (bit, bits) in zip(boxes, drawn, strict=True):
            assert (float(b.get("x")), float(b.get("width"))) == (left + bit * scale, bits * scale), key
        table = dom.xpath(f'//section[@id="{key}"]//table[@class="mapping"]//tbody/tr[td[2] != "0"]')
        assert len(table) == len(drawn), f"{key}: a table row per box"
        if layout is not None:
            assert drawn == layout, key


def _check_findings(dom: lxml.html.HtmlElement, path: Path, od: ObjectDictionary, total: int) -> None:
    placed = dom.xpath('//table[@class="od"]//li[contains(@class, "finding")]')
    general = dom.xpath('//section[@id="file-findings"]//li[contains(@class, "finding")]')
    assert len(placed) + len(general) == total
    for d in lint(path).diagnostics:
        obj = od.objects.get(d.index) if d.index is not None else None
        if obj is None or not obj.subs or d.loc.file != str(path):
            continue
        sub = d.sub if d.sub in obj.subs else obj.sorted_subs()[0].subindex
        row = dom.xpath(f'//tr[@id="{row_key(obj.index, sub)}"]')[0]
        texts = [li.text_content() for li in row.xpath('.//li[@data-rule=$r]', r=d.rule)]
        assert any(d.message in t for t in texts), f"{d.text()} not in its row"


def _check_self_contained(dom: lxml.html.HtmlElement, page: str) -> None:
    assert not dom.xpath("//script | //link | //img | //iframe | //object | //embed | //@src | //@srcset")
    hrefs = dom.xpath("//@href | //@*[local-name()='href']")
    assert all(h.startswith(("#", "docs/rules.md#")) for h in hrefs), [h for h in hrefs if "#" not in h][:5]
    assert "url(" not in page and "@import" not in page


@pytest.mark.parametrize("path", _sample())
def test_corpus_report_in_chromium(path: Path) -> None:
    report, diags = build_report(path)
    if report is None:  # unreadable: the command says so and writes nothing
        out = OUT / f"{path.name}.html"
        out.unlink(missing_ok=True)
        done = subprocess.run([sys.executable, "-m", "odgen", "report", str(path), "-o", str(out)],
                              capture_output=True, text=True, check=False)
        assert done.returncode == 1 and "no report written" in done.stderr and not out.exists()
        return
    OUT.mkdir(parents=True, exist_ok=True)
    page = OUT / f"{path.name}.html"
    html = render_html(report)
    page.write_text(html, encoding="utf-8")
    netlog = OUT / f"{path.name}.netlog.json"
    dom = lxml.html.document_fromstring(chromium(page, "--dump-dom", f"--log-net-log={netlog}"))
    shot = OUT / f"{path.name}.png"
    chromium(page, f"--screenshot={shot}", "--window-size=1400,1600", "--hide-scrollbars")
    assert shot.stat().st_size > 10000
    assert page_requests(netlog) == []
    od, _ = load_path(path)
    assert od is not None and dom.xpath("//h1")[0].text_content() == report.title
    _check_rows(dom, od)
    _check_pdos(dom, od)
    _check_findings(dom, path, od, len(diags))
    _check_self_contained(dom, html)


def test_page_requests_are_seen() -> None:
    """The control for the check above: a page that fetches is caught."""
    OUT.mkdir(parents=True, exist_ok=True)
    page, netlog = OUT / "fetching.html", OUT / "fetching.netlog.json"
    page.write_text('<html><body><img src="http://example.invalid/x.png"></body></html>', encoding="utf-8")
    chromium(page, "--dump-dom", f"--log-net-log={netlog}")
    assert page_requests(netlog) == ["http://example.invalid/x.png"]


def test_example_and_network_in_chromium() -> None:
    """The example with its options (storage, hooks, memory) and the network part."""
    report, _ = build_report(EXAMPLE, EXAMPLE_OPTIONS)
    assert report is not None
    from odgen.report.network import build_network
    report.network = build_network(NETWORK, FIXTURES / "network" / "master.eds", False)
    OUT.mkdir(parents=True, exist_ok=True)
    page = OUT / "io-node.html"
    page.write_text(render_html(report), encoding="utf-8")
    dom = lxml.html.document_fromstring(chromium(page, "--dump-dom"))
    chromium(page, f"--screenshot={OUT / 'io-node.png'}", "--window-size=1400,3000", "--hide-scrollbars")
    storage = dom.xpath(f'//tr[@id="{row_key(0x1017, 0)}"]/td[9]')[0].text_content()
    assert storage.startswith("persist:comm") and "io-node.toml:" in storage
    seg = {(s.get("data-label"), s.get("data-place")): int(s.get("data-bytes"))
           for s in dom.xpath('//*[local-name()="rect"][@class="seg"]')}
    assert report.memory is not None
    for m in report.memory:
        for place, size in (("FLASH", m.flash), ("RAM", m.ram)):
            assert seg.get((m.label, place), 0) == size
    matrix = [[td.text_content() for td in tr.xpath("td")] for tr in dom.xpath('//table[@class="matrix"]/tbody/tr')]
    assert matrix == [["", "0x181", "0x181"], ["0x182", "", ""], ["0x183", "", ""]]
    assert dom.xpath('//section[@id="network"]//li[@data-rule="NET006"]') or \
        dom.xpath('//li[@data-rule="NET006"]')
    lanes = dom.xpath('//section[@id="net-n1-tpdo1"]//table[@class="mapping"]/@data-lane')
    assert lanes == ["node 1 TPDO1", "node 2 RPDO1", "node 3 RPDO1"]


def test_memory_figures_are_those_odgen_check_prints() -> None:
    """The report's memory rows against the compiled self-test's sizeof lines."""
    cases = [(EXAMPLE, EXAMPLE_OPTIONS)] + [(p, None) for p in corpus_files(".eds")[:2]]
    for path, options in cases:
        outcome = run_check(Request(path, options=options))
        if not outcome.result.files:
            continue  # refused by its errors: no dictionary, no figures (the report says so)
        printed = [line.split() for line in outcome.output.splitlines() if line.startswith(("values", "tables"))]
        assert outcome.result.view is not None
        rows = memory_rows(outcome.result.view)
        assert [(p[0], " ".join(p[1:p.index("bytes") - 1]), int(p[p.index("bytes") - 1])) for p in printed] == \
            [(r.kind, r.label, r.size) for r in rows], path


def _cli(*args: str, seed: str) -> None:
    env = {**os.environ, "PYTHONHASHSEED": seed}
    done = subprocess.run([sys.executable, "-m", "odgen", "report", *args], capture_output=True, text=True,
                          check=False, env=env, cwd=ROOT)
    assert done.returncode == 0, done.stderr


def test_two_runs_give_identical_bytes(tmp_path: Path) -> None:
    sources = [EXAMPLE] + corpus_files(".eds", ".xdd")[:1]
    for n, source in enumerate(sources):
        for fmt in ("html", "md"):
            runs = []
            for seed in ("1", "2"):
                out = tmp_path / seed / f"r{n}.{fmt}"
                out.parent.mkdir(exist_ok=True)
                _cli(str(source), "--network", str(NETWORK), "-o", str(out), seed=seed)
                runs.append({p.relative_to(out.parent): p.read_bytes() for p in sorted(out.parent.rglob("*"))
                             if p.is_file()})
            assert runs[0] == runs[1], source


def test_markdown_has_the_same_content(tmp_path: Path) -> None:
    for source in [EXAMPLE] + corpus_files(".eds")[:3]:
        report, _ = build_report(source)
        if report is None:
            continue
        out = tmp_path / f"{source.stem}.md"
        files = render_markdown(report, out)
        for path, text in files.items():
            path.parent.mkdir(exist_ok=True)
            path.write_text(text, encoding="utf-8")
        md = out.read_text(encoding="utf-8")
        lines = md.splitlines()
        for row in report.rows:
            assert any(line.startswith(f"| {row.address} |") for line in lines), row.address
        html = lxml.html.document_fromstring(render_html(report))
        for pdo in report.pdos:
            link = f"{out.stem}-svg/{pdo.key}.svg"
            assert f"]({link})" in md
            svg = lxml.etree.fromstring((tmp_path / link).read_bytes())
            boxes = svg.xpath('//*[local-name()="rect"][contains(@class, "box")]')
            in_html = html.xpath(f'//section[@id="{pdo.key}"]//*[local-name()="rect"][contains(@class, "box")]')
            assert [(b.get("x"), b.get("width")) for b in boxes] == [(b.get("x"), b.get("width")) for b in in_html]
        findings = sum(len(r.findings) for r in report.rows) + len(report.general)
        assert sum(line.count("](docs/rules.md#") for line in lines if line.startswith(("| 0x", "- **"))) >= findings
        if report.memory is not None:
            for m in report.memory:
                assert f"| {m.kind} | {m.label} | {m.size} | {m.where} |" in lines


def test_cli_refuses_what_it_cannot_write(tmp_path: Path) -> None:
    base = [sys.executable, "-m", "odgen", "report", str(EXAMPLE)]
    wrong = ([tmp_path], [tmp_path / "missing" / "r.html"], [tmp_path / "r.html", "--options", tmp_path / "no.toml"],
             [tmp_path / "r.html", "--network", tmp_path / "no.toml"])
    for out, *more in wrong:
        done = subprocess.run([*base, "-o", str(out), *map(str, more)], capture_output=True, text=True, check=False)
        assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert not (tmp_path / "missing").exists() and not (tmp_path / "r.html").exists()


def test_can_fd_draws_a_512_bit_ruler() -> None:
    """A PDO over 64 bits: drawn past the frame with PDO005 at its sub0; with --can-fd, neither."""
    source = FIXTURES / "rules" / "PDO005.eds"
    for can_fd, ruler in ((False, 64), (True, 512)):
        report, _ = build_report(source, can_fd=can_fd)
        assert report is not None and report.pdos
        dom = lxml.html.document_fromstring(render_html(report))
        pdo = report.pdos[0]
        svg = dom.xpath(f'//section[@id="{pdo.key}"]//*[local-name()="svg"]')[0]
        assert int(svg.get("data-scale")) == min(12, 1024 // max(ruler, -(-pdo.used_bits // 8) * 8))
        overflow = svg.xpath('.//*[local-name()="rect"][@class="overflow"]')
        assert bool(overflow) == (pdo.used_bits > ruler)
        pdo005 = dom.xpath('//table[@class="od"]//li[@data-rule="PDO005"]')
        assert bool(pdo005) == (pdo.used_bits > ruler)
