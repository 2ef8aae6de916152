"""The report as one document: plain dataclasses that the Markdown, HTML and JUnit renderers read.

A :class:`Document` holds the run's verdicts (one :class:`Verdict` per scene)
and its sections; a section holds blocks (:class:`Paragraph`, :class:`Table`,
:class:`Bullets`, :class:`Quote`, :class:`Image`, :class:`Files`); text is a
string or a tuple of strings and :class:`Span` (bold, code, a link, a status).
What the report says is decided once, in ``contents.py``; a renderer only
writes the document in its format (``markdown.py``, ``html.py``, ``junit.py``).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Union

from ballbench.validation.report.records import Tally


@dataclass(frozen=True)
class Span:
    """Inline text: ``style`` ``"strong"``, ``"code"`` or ``"em"``; ``link`` a ``#scene`` anchor or a file;
    ``status`` a check or scene status (the renderers mark any but a pass)."""

    text: str
    style: str = ""
    link: str = ""
    status: str = ""


Text = Union[str, Span, tuple]  # a string, a span, or a tuple of them


@dataclass(frozen=True)
class Paragraph:
    """A paragraph; ``small`` for explanations beside a table, ``tone`` for a banner."""

    text: Text
    small: bool = False
    tone: str = ""  # "" or a banner: "ok", "bad", "warn", "muted" (a scene that does not apply)


@dataclass(frozen=True)
class Table:
    """Rows of cells (each a :data:`Text`) under a header."""

    header: tuple[str, ...]
    rows: tuple[tuple[Text, ...], ...]
    numeric: tuple[int, ...] = ()  # columns of numbers (right-aligned in HTML)


@dataclass(frozen=True)
class Bullets:
    items: tuple[Text, ...]


@dataclass(frozen=True)
class Quote:
    text: str


@dataclass(frozen=True)
class Image:
    path: str  # relative to the report folder
    alt: str


@dataclass(frozen=True)
class Files:
    paths: tuple[str, ...]  # relative to the report folder


Block = Union[Paragraph, Table, Bullets, Quote, Image, Files]


@dataclass(frozen=True)
class Section:
    """A heading (none for the opening banner) and its blocks; ``anchor`` is the link target."""

    title: str
    anchor: str
    blocks: tuple[Block, ...]
    scene: bool = False  # a scene's own section (HTML: <section data-scene>)
    loud: bool = False   # a heading that must not be missed (unexpected passes)


@dataclass(frozen=True)
class Verdict:
    """A scene's outcome as every renderer states it (JUnit reads only these)."""

    name: str
    kind: str
    status: str
    wall_time_s: float
    budget: str
    error: str
    failures: tuple[str, ...]   # one line per failed check (JUnit failure text)
    gaps: tuple[str, ...]       # "quantity: reason" of each known gap
    checks: tuple[str, ...]     # every check as a line with its status
    reason: str = ""            # why the scene does not apply to its case (status "not applicable")
    inconclusive: str = ""      # why its reference is too uncertain at this fidelity (status "inconclusive")


@dataclass(frozen=True)
class Document:
    """The whole report: the run's tally, one verdict per scene, the sections in reading order, and the scene
    anchors for a page's navigation bar."""

    title: str
    fidelity: str
    tally: Tally
    verdicts: tuple[Verdict, ...]
    sections: tuple[Section, ...]
    nav: tuple[str, ...] = ()
