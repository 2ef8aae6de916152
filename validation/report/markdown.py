"""``report.md``: the :class:`~.document.Document` in Markdown (GitHub flavour: pipe tables, heading anchors)."""
from __future__ import annotations

from ballbench.validation.report.document import (Bullets, Document, Files, Image, Paragraph, Quote, Section, Table)

QUIET = ("", "pass", "within budget")  # statuses written plain; any other is bold


def inline(text) -> str:
    """A string, a :class:`Span` or a tuple of them as Markdown."""
    if isinstance(text, tuple):
        return "".join(inline(t) for t in text)
    if isinstance(text, str):
        return text
    out = text.text
    if text.style == "code":
        out = f"`{out}`"
    elif text.style == "em":
        out = f"*{out}*"
    if text.link:
        out = f"[{out}]({text.link})"
    if text.style == "strong" or text.status not in QUIET:
        out = f"**{out}**"
    return out


def _cell(text) -> str:
    return inline(text).replace("|", "\\|").replace("\n", " ")


def _block(block) -> list[str]:
    if isinstance(block, Paragraph):
        return [inline(block.text), ""]
    if isinstance(block, Table):
        lines = ["| " + " | ".join(block.header) + " |", "|" + "---|" * len(block.header)]
        return lines + ["| " + " | ".join(_cell(c) for c in r) + " |" for r in block.rows] + [""]
    if isinstance(block, Bullets):
        return [f"- {inline(item)}" for item in block.items] + [""]
    if isinstance(block, Quote):
        return [f"> {block.text}", ""]
    if isinstance(block, Image):
        return [f"![{block.alt}]({block.path})", ""]
    if isinstance(block, Files):
        return [f"- [{path}]({path})" for path in block.paths] + [""]
    raise TypeError(f"no Markdown for {type(block).__name__}")


def _section(section: Section) -> list[str]:
    lines = []
    if section.title:
        lines += [f"## {section.title}", ""]
    for block in section.blocks:
        lines += _block(block)
    return lines


def render(document: Document) -> str:
    """The Markdown text of ``document``."""
    lines = [f"# {document.title}", ""]
    for section in document.sections:
        lines += _section(section)
    return "\n".join(lines)
