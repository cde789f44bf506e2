"""Guards on a study file before and after it is parsed: what it is, how big, how deep, and
how much work it asks for.

:func:`read_study_text` reads only a regular file (not a folder, a device, a pipe, or a link
to one) of at most :data:`MAX_STUDY_BYTES` whose path holds no NUL. :func:`check_text` and
:func:`check_tree` refuse nesting deeper than :data:`MAX_TOML_DEPTH` (before and after
parsing), and :func:`check_tree` any key or text value holding a control character (which
would break every file name made from it). :func:`check_work` bounds the scenarios
(:data:`MAX_SCENARIOS`), worst-case solves (:func:`work`: every load path to ``lambda_cap``
plus its drawn states, critical-position searches, settlement paths and sampled capacities; at most ``[study]
max_solves``, :data:`MAX_SOLVES` by default) and drawn states (:data:`MAX_DRAWN_STATES`) before the
scenarios are expanded, each message giving the estimate and the keys that set it.

Every refusal is a :class:`tce.study.schema.StudyError` naming the file and the key.
"""

from __future__ import annotations

import math
import re
import stat
from collections.abc import Mapping
from pathlib import Path
from typing import Any

__all__ = [
    "MAX_DRAWN_STATES",
    "MAX_SCENARIOS",
    "MAX_SOLVES",
    "MAX_STUDY_BYTES",
    "MAX_TOML_DEPTH",
    "check_path",
    "check_text",
    "check_tree",
    "check_work",
    "read_study_text",
    "work",
]

#: Largest study file read (bytes): a study is a page of text; sweeps are lists, not files.
MAX_STUDY_BYTES = 2**20
#: Deepest nesting of tables and arrays in a study (a study needs 4).
MAX_TOML_DEPTH = 16
#: Most scenarios in a study (settlement cases x directions x sweep values).
MAX_SCENARIOS = 10_000
#: Most solves a study may ask for in the worst case (every load path to lambda_cap, search and
#: settlement path), unless its ``[study] max_solves`` says otherwise.
MAX_SOLVES = 20_000_000
#: Most drawn states (per-scenario figures' scenarios x ``[plots] steps``).
MAX_DRAWN_STATES = 200


class StudyError(ValueError):
    """A study file that cannot be run; the message says where and how to fix it (raised by
    these guards and by :mod:`tce.study.schema`, which exports it)."""


def _worst_steps(step: float | None, cap: float | None) -> int:
    """Most load increments of one path (:func:`tce.analysis.loadpath.increments_and_cap`):
    ``cap / step`` when both are given; anchored on the direct limit otherwise (about
    ``AUTO_INCREMENTS``, or at most ``MAX_INCREMENTS`` for a given step without a cap)."""
    from ..analysis.loadpath import AUTO_INCREMENTS, MAX_INCREMENTS

    if step is not None and cap is not None:
        return math.floor(cap / step) + 1
    return MAX_INCREMENTS + 1 if step is not None else AUTO_INCREMENTS + 2


def _error(msg: str) -> Exception:
    return StudyError(msg)


def check_path(path: Path | str, what: str) -> None:
    """Refuse a path holding a NUL character (no file can have one); ``what`` names it."""
    if "\0" in str(path):
        raise _error(f"{what}: {str(path)!r} holds a NUL character; fix: give a file name without it")


def read_study_text(path: Path) -> str:
    """The text of the study file ``path``, read only if it is a regular file of at most
    :data:`MAX_STUDY_BYTES` (links are followed: a link to ``/dev/zero`` is a device)."""
    check_path(path, "the study file")
    fix = "fix: give a readable TOML file"
    try:
        info = path.stat()
    except OSError as exc:
        raise _error(f"{path}: cannot read the study file ({exc.strerror or exc}); {fix}") from None
    if not stat.S_ISREG(info.st_mode):
        kind = "a folder" if stat.S_ISDIR(info.st_mode) else "a pipe" if stat.S_ISFIFO(info.st_mode) else "a device or socket"
        raise _error(f"{path}: not a regular file ({kind}); {fix}")
    if info.st_size > MAX_STUDY_BYTES:
        raise _error(f"{path}: {info.st_size} bytes, more than MAX_STUDY_BYTES = {MAX_STUDY_BYTES}; {fix}")
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_STUDY_BYTES + 1)  # the file may grow between stat and read
        if len(data) > MAX_STUDY_BYTES:
            raise _error(f"{path}: more than MAX_STUDY_BYTES = {MAX_STUDY_BYTES} bytes; {fix}")
        return data.decode("utf-8")
    except OSError as exc:
        raise _error(f"{path}: cannot read the study file ({exc.strerror or exc}); {fix}") from None
    except UnicodeDecodeError as exc:
        raise _error(f"{path}: not a UTF-8 text file ({exc.reason} at byte {exc.start}); {fix}") from None


#: TOML strings (basic, literal, multi-line), replaced by a word before the text is scanned
_TOML_STRING = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'')
_TOML_COMMENT = re.compile(r"#[^\n]*")


def check_text(path: Path, text: str) -> None:
    """Refuse TOML text nested more than :data:`MAX_TOML_DEPTH` deep, in one linear pass
    before it is parsed (the parser recurses once per level of arrays and inline tables,
    and takes time quadratic in the length of a dotted key)."""
    import numpy as np  # here: the tce program imports this module before it handles Ctrl-C

    bare = _TOML_COMMENT.sub("", _TOML_STRING.sub("s", text))
    chain = re.search(r"[\w-]+(?:[ \t]*\.[ \t]*[\w-]+){%d,}" % MAX_TOML_DEPTH, bare)
    codes = np.frombuffer(bare.encode("utf-8"), dtype=np.uint8)
    depth = np.cumsum(np.isin(codes, (ord("["), ord("{"))).astype(np.int64) - np.isin(codes, (ord("]"), ord("}"))))
    deepest = int(np.argmax(depth)) if len(depth) else 0
    if chain is None and (not len(depth) or depth[deepest] <= MAX_TOML_DEPTH):
        return
    at = chain.start() if chain is not None else deepest
    line = bare.count("\n", 0, at) + 1
    raise _error(
        f"{path}: line {line}: nested more than MAX_TOML_DEPTH = {MAX_TOML_DEPTH} deep; fix: a study needs "
        "tables of values and lists, no deeper"
    )


def _key(parts: list[Any]) -> str:
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "(top level)"


def check_tree(path: Path, data: Any) -> None:
    """Refuse nesting deeper than :data:`MAX_TOML_DEPTH` and control characters in keys and
    text values (walked without recursion)."""
    stack: list[tuple[Any, list[Any]]] = [(data, [])]
    while stack:
        node, where = stack.pop()
        if len(where) > MAX_TOML_DEPTH:
            raise _error(
                f"{path}: {_key(where[:3])}: nested more than MAX_TOML_DEPTH = {MAX_TOML_DEPTH} deep; "
                "fix: a study needs tables of values and lists, no deeper"
            )
        if isinstance(node, Mapping):
            items = list(node.items())
        elif isinstance(node, list):
            items = list(enumerate(node))
        else:
            items = []
            if isinstance(node, str) and _control(node):
                raise _error(f"{path}: {_key(where)}: the text {node[:40]!r} holds a control character; fix: remove it")
        for k, v in items:
            if isinstance(k, str) and _control(k):
                raise _error(f"{path}: {_key(where)}: the key {k[:40]!r} holds a control character; fix: remove it")
            stack.append((v, where + [k]))


def _control(text: str) -> bool:
    return any(ord(c) < 32 or ord(c) == 127 for c in text)


def work(spec: Any, search_solves: int = 0) -> tuple[int, str]:
    """The most solves a study asks for and how they are counted: every scenario's load path to
    ``lambda_cap`` with its drawn states, its critical-position search (``search_solves``
    limits each), its settlement path (``s_max / increment`` increments) and its ``[uncertainty]``
    samples (each at most a search or a settlement path). ``spec`` is the
    parsed :class:`tce.study.schema.StudyFile` (not imported: the schema imports these guards)."""
    count = _scenarios(spec)[0]
    loads = spec.loads
    steps = _worst_steps(loads.lambda_step, loads.lambda_cap)
    states = len(spec.plots.lambdas)
    if loads.lambda_step is not None and loads.lambda_cap is not None:
        how = f"to lambda_cap = {loads.lambda_cap:g} by lambda_step = {loads.lambda_step:g}"
    elif loads.lambda_step is not None:
        how = f"by lambda_step = {loads.lambda_step:g}, no lambda_cap"
    else:
        how = "anchored on the direct limit"
    terms = [f"{steps} load steps {how} + 2 + {states} drawn"]
    each = steps + 2 + states
    if loads.critical_position:
        terms.append(f"a critical-position search of {search_solves} limits")
        each += search_solves
    path = spec.settlement_path
    if path is not None:
        increments = math.ceil(path.s_max / path.increment)
        lives = len(path.live_at or []) * (1 + search_solves)
        terms.append(f"a settlement path of {increments} increments (s_max / increment)"
                     + (f" and {lives} live-load limits" if lives else ""))
        each += increments + lives
    sampled = spec.uncertainty
    if sampled is not None:
        # each sample: a direct limit, a critical-position search or a settlement path
        from .uncertainty import evaluations  # here: the tce program imports this module before it handles Ctrl-C

        per = max(1 + search_solves, math.ceil(path.s_max / path.increment) if path is not None else 1)
        extra = evaluations(sampled)
        terms.append(f"{sampled.samples} samples{f' + {extra} FORM and subset evaluations' if extra else ''} "
                     f"of at most {per} solves ([uncertainty])")
        each += (sampled.samples + extra) * per
    return count * each, f"{count} scenarios x ({' + '.join(terms)}) = {count * each} solves at most"


def _scenarios(spec: Any) -> tuple[int, list[tuple[str, int, str]]]:
    """The number of scenarios of a study and its factors ``(key, count, what)``."""
    factors = [("scenarios", len(spec.scenarios), "settlement case(s)"), ("loads.alpha", len(spec.loads.alphas),
                                                                          "direction(s)")]
    factors += [(f"sweep.{k}", len(v), "values") for k, v in spec.sweep.items()]
    return math.prod(n for _, n, _ in factors), factors


def check_work(path: Path, spec: Any, drawn_scenarios: int | None = None, search_solves: int = 0) -> None:
    """Refuse a study that asks for more than :data:`MAX_SCENARIOS` scenarios or more solves
    than its cap ``[study] max_solves`` (:func:`work`), or, given the number of scenarios
    drawn, more than :data:`MAX_DRAWN_STATES` drawn states."""
    count, factors = _scenarios(spec)
    if count > MAX_SCENARIOS:
        how = " x ".join(f"{n} {what} of {key}" for key, n, what in factors)
        key = max(factors, key=lambda f: f[1])[0]
        raise _error(
            f"{path}: {key}: {how} = {count} scenarios, more than MAX_SCENARIOS = {MAX_SCENARIOS}; "
            "fix: sweep fewer values, or split the study"
        )
    solves, how = work(spec, search_solves)
    cap = spec.study.max_solves
    if solves > cap:
        raise _error(
            f"{path}: study.max_solves: {how}, more than the study's cap max_solves = {cap} (by default MAX_SOLVES); "
            "fix: a larger loads.lambda_step or settlement_path.increment, a smaller loads.lambda_cap or "
            "settlement_path.s_max, fewer scenarios or uncertainty.samples, or raise [study] max_solves"
        )
    if drawn_scenarios is not None and drawn_scenarios * len(spec.plots.steps) > MAX_DRAWN_STATES:
        n = drawn_scenarios * len(spec.plots.steps)
        raise _error(
            f"{path}: plots.steps: {drawn_scenarios} scenario(s) drawn x {len(spec.plots.steps)} steps = {n} "
            f"drawn states, more than MAX_DRAWN_STATES = {MAX_DRAWN_STATES}; fix: draw fewer steps or name "
            "fewer scenarios in [plots] scenarios"
        )
