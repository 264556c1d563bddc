"""Reporters: the same lint results as text, JSON or SARIF 2.1.0."""

from .github import render_github
from .json_report import render_json
from .sarif import render_sarif
from .text import render_text

RENDERERS = {"text": render_text, "json": render_json, "sarif": render_sarif, "github": render_github}

__all__ = ["RENDERERS", "render_github", "render_json", "render_sarif", "render_text"]
