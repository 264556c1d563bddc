"""mkdocs hook (mkdocs.yml `hooks`): the C runtime's own pages join the docs site.

runtime/README.md (the C API) and runtime/NODE.md (the node layer) live beside the sources they
describe and ship with them (`odgen --runtime-dir`); the site shows them as runtime/index and
runtime/node without a copy in docs/.
"""

from __future__ import annotations

from pathlib import Path

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.structure.files import File, Files
from mkdocs.structure.pages import Page

RUNTIME = Path(__file__).resolve().parent.parent / "runtime"
PAGES = {"README.md": "runtime/index.md", "NODE.md": "runtime/node.md"}


def on_files(files: Files, config: MkDocsConfig) -> Files:
    for name, uri in PAGES.items():
        files.append(File.generated(config, uri, abs_src_path=str(RUNTIME / name)))
    return files


def on_page_markdown(markdown: str, page: Page, config: MkDocsConfig, files: Files) -> str:
    """Drop a leading SPDX comment, so the page's first heading is its title in the navigation."""
    first, _, rest = markdown.partition("\n")
    return rest if first.startswith("<!-- SPDX-License-Identifier:") else markdown
