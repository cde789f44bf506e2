"""Short text and HTML summaries of tce objects (their ``repr`` and notebook ``_repr_html_``).

A repr says what an object is in one line under :data:`MAX_REPR` characters (counts, names,
headline numbers), never its arrays; the HTML form is a small table of the same facts. This
module imports nothing of tce: every floor may use it.
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterable, Mapping, Sequence

__all__ = ["MAX_REPR", "call", "html_table", "names", "number"]

#: longest repr of a tce object (characters)
MAX_REPR = 400


def number(value: object, digits: int = 6) -> str:
    """``value`` in at most ``digits`` significant figures (floats), as text otherwise."""
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.{digits}g}"
    if isinstance(value, str):
        return repr(value)
    return str(value)


def names(items: Sequence[str], limit: int = 4) -> str:
    """``[a, b, c, ... (n in all)]``: at most ``limit`` names of ``items``."""
    shown = ", ".join(str(n) for n in items[:limit])
    return f"[{shown}{f', ... ({len(items)} in all)' if len(items) > limit else ''}]"


def call(cls: str, fields: Mapping[str, object], head: str = "") -> str:
    """``cls(head, key=value, ...)`` with :func:`number` values, cut to :data:`MAX_REPR`."""
    parts = ([head] if head else []) + [f"{k}={number(v)}" for k, v in fields.items()]
    text = f"{cls}({', '.join(parts)})"
    return text if len(text) <= MAX_REPR else text[: MAX_REPR - 4] + " ...)"


def html_table(title: str, rows: Iterable[tuple[str, object]], status: str | None = None) -> str:
    """A two-column HTML table (a notebook's ``_repr_html_``): ``title`` above, then one row
    per ``(label, value)``; ``status`` (if given) on the title line, green when it is an
    answer (``optimal``, ``limit``, ``converged``) and red otherwise."""
    esc = html.escape
    badge = ""
    if status is not None:
        colour = "#1a7f37" if status in ("optimal", "limit", "converged") else "#b42318"
        badge = f' <span style="color:{colour};font-weight:bold">{esc(status)}</span>'
    body = "".join(
        f'<tr><th style="text-align:left;padding-right:1em">{esc(str(k))}</th>'
        f'<td style="text-align:left">{esc(v if isinstance(v, str) else number(v))}</td></tr>'
        for k, v in rows
    )
    return f"<div><b>{esc(title)}</b>{badge}<table>{body}</table></div>"
