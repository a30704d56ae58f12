"""Pieces of the report's front page: reStructuredText, with raw HTML where rst cannot fold or
size (tables of short cells, evidence folded beneath them, figures embedded as data URIs),
numbers with their units and three significant digits, and what is missing said in words.

Snakemake renders the front page (report/front.rst, which includes the pages made from these
pieces) with docutils into the report's landing view; its HTML is the report's own, so the
embedded figures travel with the single report file.
"""

import base64
import html
import math
import textwrap
from collections.abc import Sequence
from pathlib import Path

#: the class of the element that holds every front-page piece (report/front.rst styles it)
FRONT = "sim-front"
#: the narrowest a table column may be, in characters of its font (at a 1000 px window)
COLUMN_CH = 25


def digits(value: float, sign: str = "") -> str:
    """A finite number rounded to three significant digits, written out below a million
    (6620, not 6.62e+03); ``sign`` "+" writes a plus sign on positive numbers."""
    return format(float(f"{float(value):.3g}"), f"{sign}g")


def number(value: float, unit: str = "", missing: str = "not computed") -> str:
    """A number as a table shows it: three significant digits and its unit; ``missing`` (why
    there is none) for NaN or infinity."""
    if value is None or not math.isfinite(float(value)):
        return missing
    return f"{digits(value)} {unit}" if unit else digits(value)


def interval(low: float, high: float, unit: str = "", missing: str = "no interval") -> str:
    """An interval [low, high] with three significant digits and its unit."""
    if not (math.isfinite(float(low)) and math.isfinite(float(high))):
        return missing
    return f"[{digits(low)}, {digits(high)}]" + (f" {unit}" if unit else "")


def escaped(text: str) -> str:
    """Text as HTML shows it literally."""
    return html.escape(str(text), quote=True)


def raw(markup: str) -> str:
    """An rst block that passes ``markup`` (HTML) through, a line per element: docutils
    drops any line longer than 10 000 characters."""
    lines = markup.strip().replace("><", ">\n<")
    return ".. raw:: html\n\n" + textwrap.indent(lines, "   ") + "\n\n"


def table(header: Sequence[str], rows: Sequence[Sequence[str]], *, cells_are_html=False) -> str:
    """An HTML table of short cells, none narrower than ``COLUMN_CH`` characters; the cells
    are escaped unless ``cells_are_html``."""
    cell = (lambda text: text) if cells_are_html else escaped
    style = f"min-width:{COLUMN_CH}ch;vertical-align:top;text-align:left"
    head = "".join(f'<th style="{style}">{escaped(h)}</th>' for h in header)
    body = "".join(
        "<tr>" + "".join(f'<td style="{style}">{cell(c)}</td>' for c in row) + "</tr>"
        for row in rows
    )
    return (
        '<table style="width:auto;table-layout:auto;border-collapse:collapse">'
        f"<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
    )


def details(summary: str, body: str) -> str:
    """HTML: ``body`` (HTML) folded beneath a one-line ``summary`` (text)."""
    return f"<details><summary>{escaped(summary)}</summary>{body}</details>"


def paragraph(text: str) -> str:
    """HTML: a paragraph of text."""
    return f"<p>{escaped(text)}</p>"


def figure(path: str | Path, alt: str, width: str | None = None) -> str:
    """HTML: a PNG or SVG file embedded as a data URI (the report is one file), at its own size
    or ``width`` of the page's width, never wider than the page; its alternative text ``alt``."""
    path = Path(path)
    return image(path.read_bytes(), alt, "svg+xml" if path.suffix == ".svg" else "png", width)


def image(data: bytes, alt: str, kind: str = "png", width: str | None = None) -> str:
    """HTML: an image's bytes (``kind``: png or svg+xml) embedded as a data URI, sized as
    :func:`figure` says."""
    # in lines of 76 characters: a URL parser drops the line breaks (WHATWG URL standard)
    encoded = base64.encodebytes(data).decode("ascii").strip()
    return (
        f'<img src="data:image/{kind};base64,{encoded}" alt="{escaped(alt)}" '
        f'style="{f"width:{width};" if width else ""}max-width:100%;height:auto"/>'
    )


def heading(text: str, underline: str) -> str:
    """An rst section heading (its underline character sets its level)."""
    return f"{text}\n{underline * max(len(text), 3)}\n\n"
