"""``report.html``: the :class:`~.document.Document` as one self-contained page.

Inline CSS, figures as data URIs, no script and no server: it opens offline
in any browser and can be mailed as one file.
"""
from __future__ import annotations

import base64
import html
from pathlib import Path

from ballbench.validation.report.document import (Bullets, Document, Files, Image, Paragraph, Quote, Section, Table)

CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:1.5em auto;max-width:1300px;
color:#222;line-height:1.35;padding:0 1em}
table{border-collapse:collapse;margin:.5em 0 1em;font-size:13px}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#f0f0f0}td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.pass{color:#0072B2}.fail,.error,.unexpected{color:#D55E00;font-weight:bold}.gap{color:#9a6b00;font-weight:bold}
.finding{color:#7b3294;font-weight:bold}.na{color:#555;font-weight:bold;font-style:italic}
.na::before{content:"\\2298\\00a0"}.inconclusive{color:#555;font-weight:bold}
.inconclusive::before{content:"?\\00a0"}
.banner{padding:.6em 1em;border-radius:4px;margin:.5em 0}.banner.ok{background:#e6f0fa}
.banner.bad{background:#fde3d6}.banner.warn{background:#fff1d0}
.banner.muted{background:#eeeeee;border-left:4px solid #888}
blockquote{margin:.4em 0 .4em 1em;padding-left:.8em;border-left:3px solid #ccc;color:#444;font-size:13px}
img{max-width:100%;border:1px solid #ddd;margin:.3em 0}figure{margin:.5em 0}figcaption{font-size:12px;color:#555}
h2{border-bottom:1px solid #ddd;padding-bottom:.2em;margin-top:1.6em}nav a{margin-right:.6em;font-size:13px}
.small{font-size:12px;color:#555}
"""
STATUS_CLASS = {"pass": "pass", "within budget": "pass", "known gap": "gap", "fail": "fail", "error": "error",
                "unexpected pass": "unexpected", "over budget": "gap", "outside accuracy": "finding",
                "findings": "finding", "not applicable": "na",
                "inconclusive": "inconclusive"}
_TAGS = {"strong": "b", "code": "code", "em": "i"}


def inline(text) -> str:
    """A string, a :class:`Span` or a tuple of them as escaped HTML."""
    if isinstance(text, tuple):
        return "".join(inline(t) for t in text)
    if isinstance(text, str):
        return html.escape(text)
    out = html.escape(text.text)
    if text.style:
        out = f"<{_TAGS[text.style]}>{out}</{_TAGS[text.style]}>"
    if text.link:
        out = f'<a href="{html.escape(text.link)}">{out}</a>'
    if text.status in STATUS_CLASS:
        out = f'<span class="{STATUS_CLASS[text.status]}">{out}</span>'
    return out


def _image(out_dir: Path, image: Image) -> str:
    path = out_dir / image.path
    if not path.exists():
        return f'<p class="small">Figure not written: {html.escape(image.path)}</p>'
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    alt, name = html.escape(image.alt), html.escape(image.path)
    caption = alt if image.alt == image.path else f"{alt} ({name})"
    return (f'<figure><img alt="{alt}" data-artifact="{name}" src="data:image/png;base64,{data}">'
            f"<figcaption>{caption}</figcaption></figure>")


def _table(table: Table) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in table.header) + "</tr></thead>"
           "<tbody>"]
    for r in table.rows:
        cells = "".join(f'<td class="num">{inline(c)}</td>' if i in table.numeric else f"<td>{inline(c)}</td>"
                        for i, c in enumerate(r))
        out.append(f"<tr>{cells}</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def _block(block, out_dir: Path) -> str:
    if isinstance(block, Paragraph):
        if block.tone:
            return f'<div class="banner {block.tone}">{inline(block.text)}</div>'
        return f'<p class="small">{inline(block.text)}</p>' if block.small else f"<p>{inline(block.text)}</p>"
    if isinstance(block, Table):
        return _table(block)
    if isinstance(block, Bullets):
        return '<ul class="small">' + "".join(f"<li>{inline(item)}</li>" for item in block.items) + "</ul>"
    if isinstance(block, Quote):
        return f"<blockquote>{html.escape(block.text)}</blockquote>"
    if isinstance(block, Image):
        return _image(out_dir, block)
    if isinstance(block, Files):
        links = ", ".join(f'<a href="{html.escape(p)}">{html.escape(p)}</a>' for p in block.paths)
        return f'<p class="small">Files: {links}</p>'
    raise TypeError(f"no HTML for {type(block).__name__}")


def _section(section: Section, out_dir: Path) -> str:
    body = "\n".join(_block(b, out_dir) for b in section.blocks)
    anchor = html.escape(section.anchor)
    if section.scene:
        return (f'<section id="{anchor}" data-scene="{anchor}"><h2>{html.escape(section.title)}</h2>\n{body}'
                "</section>")
    if not section.title:
        return body
    loud = ' class="unexpected"' if section.loud else ""
    return f'<h2 id="{anchor}"{loud}>{html.escape(section.title)}</h2>\n{body}'


def render(document: Document, out_dir: Path) -> str:
    """The page of ``document``; figures are read from ``out_dir`` and inlined."""
    out_dir = Path(out_dir)
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             f"<title>{html.escape(document.title)}</title>", f"<style>{CSS}</style></head><body>",
             f"<h1>{html.escape(document.title)}</h1>"]
    for section in document.sections:
        if section.anchor == "summary" and document.nav:  # the scene links, above the summary
            parts.append("<nav>" + "".join(f'<a href="#{html.escape(n)}">{html.escape(n)}</a>'
                                           for n in document.nav) + "</nav>")
        parts.append(_section(section, out_dir))
    parts.append("</body></html>")
    return "\n".join(parts)
