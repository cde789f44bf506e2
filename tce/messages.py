"""Messages of input errors: what is wrong, where, and how to fix it.

Study files (:mod:`tce.study.schema`) and block files (:mod:`tce.structures.io`) are read by
pydantic models; :func:`describe` turns a :class:`pydantic.ValidationError` into one line
per problem, ``<file>: <key>: <what is wrong> (got <value>); fix: <how>``, the key written as
in the document (``loads.point[1].at``, ``blocks[3].vertices``) and an unknown key answered
with a "did you mean" (:func:`did_you_mean`). This module imports nothing of tce: every floor
may use it.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any, get_args, get_origin

from pydantic import BaseModel, ValidationError

__all__ = ["HINTS", "did_you_mean", "describe", "key"]

#: how to fix each kind of pydantic error (formatted with the error's context; ``{docs}``
#: is the document that lists the keys)
HINTS = {
    "extra_forbidden": "remove it or correct its spelling",
    "missing": "add it",
    "greater_than": "use a value > {gt}",
    "greater_than_equal": "use a value >= {ge}",
    "less_than": "use a value < {lt}",
    "less_than_equal": "use a value <= {le}",
    "multiple_of": "use a multiple of {multiple_of}",
    "finite_number": "use a finite number (NaN and inf are not allowed)",
    "too_short": "give at least {min_length} items",
    "too_long": "give at most {max_length} items",
    "float_type": "write a number",
    "float_parsing": "write a number",
    "int_type": "write a whole number",
    "int_from_float": "write a whole number",
    "int_parsing": "write a whole number",
    "list_type": "write a list, e.g. [1, 2]",
    "dict_type": "write a table",
    "model_type": "write a table",
    "string_type": "write a quoted string",
    "string_too_short": "give a non-empty value",
    "string_too_long": "use at most {max_length} characters",
    "bool_type": "write true or false",
    "value_error": "{fix}",
    "literal_error": "use one of the values listed",
}


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """``" (did you mean 'x'?)"`` for the choice closest to a misspelt ``word``, else ``""``."""
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def key(loc: tuple[Any, ...], tags: Iterable[str] = ()) -> str:
    """The key of a pydantic location as written in the document: ``a.b[2].c``, without the
    labels pydantic inserts for union members (``float``, the ``tags`` of a discriminated union)."""
    tags = set(tags)
    parts: list[str] = []
    for item in loc:
        if isinstance(item, int):
            parts[-1:] = [f"{parts[-1]}[{item}]" if parts else f"[{item}]"]
        elif item == "float" or item in tags or "[" in str(item):
            continue
        else:
            parts.append(str(item))
    return ".".join(parts) or "(top level)"


def _model(annotation: Any) -> type[BaseModel] | None:
    """The model a field holds, directly or as the items of a list."""
    if get_origin(annotation) is list and get_args(annotation):
        annotation = get_args(annotation)[0]
    return annotation if isinstance(annotation, type) and issubclass(annotation, BaseModel) else None


def _siblings(loc: tuple[Any, ...], model: type[BaseModel], tags: Mapping[str, type[BaseModel]]) -> list[str]:
    """The keys allowed beside the last item of a pydantic location (for "did you mean")."""
    current: type[BaseModel] | None = model
    for item in loc[:-1]:
        if isinstance(item, int):  # an item of a list of tables
            continue
        if item in tags:
            current = tags[item]
        elif current is not None and item in current.model_fields:
            current = _model(current.model_fields[item].annotation)
        else:
            return []
    return list(current.model_fields) if current is not None else []


def _short(value: Any) -> str:
    """``repr`` of an input, cut to 60 characters."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def describe(
    path: Path | str,
    exc: ValidationError,
    model: type[BaseModel],
    docs: str,
    hints: Mapping[str, str] | None = None,
    tags: Mapping[str, type[BaseModel]] | None = None,
    where: Callable[[tuple[Any, ...]], str] | None = None,
) -> list[str]:
    """One line per problem of a document that ``model`` refused: file, key, what is wrong,
    how to fix it.

    Parameters
    ----------
    path : Path or str
        The document's file (named first in every line).
    exc : ValidationError
        What ``model.model_validate`` raised.
    model : type of BaseModel
        The document's model (its fields answer the "did you mean" of an unknown key).
    docs : str
        Where the keys are listed (named in the hint of an unknown key).
    hints : mapping, optional
        Hints that replace those of :data:`HINTS` for some error types.
    tags : mapping, optional
        Tag -> model of the document's discriminated union.
    where : callable, optional
        The key of a location (default :func:`key`).

    Returns
    -------
    list of str
        The lines, in document order; a location reported by several union members once.
    """
    tags = dict(tags or {})
    table = {**HINTS, **(hints or {})}
    lines, seen = [], set()
    for err in exc.errors():
        name = where(err["loc"]) if where is not None else key(err["loc"], tags)
        if name in seen:  # a union reports each alternative: keep the first
            continue
        seen.add(name)
        kind = err["type"]
        ctx = dict(err.get("ctx", {}))
        if kind == "value_error":  # our validators write "what is wrong; fix: how"
            what, _, ctx["fix"] = str(ctx.get("error", "")).partition("; fix: ")
            ctx["fix"] = ctx["fix"] or f"see {docs}"
        else:
            what = err["msg"]
        hint = table.get(kind, f"see {docs}").format(**ctx, tags=list(tags))
        if kind == "extra_forbidden":
            hint += f"{did_you_mean(err['loc'][-1], _siblings(err['loc'], model, tags))} (keys: {docs})"
        elif kind == "union_tag_invalid":
            hint += did_you_mean(ctx["tag"], tags)
        got = "" if kind in ("missing", "value_error", "union_tag_invalid") else f" (got {_short(err.get('input'))})"
        lines.append(f"{path}: {name}: {what}{got}; fix: {hint}")
    return lines
