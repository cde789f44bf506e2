"""Names and a tolerance that the study schema, the runner and the figures share, importable
without pydantic, xarray or the solvers: the command line's parser imports this, not
:mod:`tce.study.schema` or :mod:`tce.study.runner`."""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

__all__ = ["LAMBDA_TOL", "PLOT_KINDS", "missing_lambdas", "same_lambda", "slug"]

#: figure kinds of ``[plots] kinds`` (docs/studies.md, "Figures")
PLOT_KINDS = ("capacity", "thrust", "states", "thrust_lines", "transversal", "base", "mechanism", "summary", "bracket",
              "view", "settlement", "settlement_shapes", "fragility", "capacity_samples", "sensitivity", "convergence")
#: two load multipliers closer than this (relative to max(1, |lambda|)) are the same step
LAMBDA_TOL = 1e-9


def same_lambda(a: float, b: float) -> bool:
    """Whether two load multipliers are the same step (within :data:`LAMBDA_TOL`)."""
    return abs(a - b) <= LAMBDA_TOL * max(1.0, abs(a), abs(b))


def missing_lambdas(solved: Sequence[float], wanted: Sequence[float], upper: float) -> list[float]:
    """The multipliers of ``wanted`` that are not ``solved`` and may be admissible.

    A multiplier is missing when no solved one is :func:`same_lambda` as it. Those at or
    above ``upper`` (the smallest multiplier found inadmissible; NaN: none) are left out: the
    admissible multipliers form an interval (the admissible set of ``(lambda, F)`` is convex
    and holds ``lambda = 0`` or nothing).
    """
    return [
        float(w) for w in wanted
        if not any(same_lambda(w, s) for s in solved) and not (math.isfinite(upper) and w >= upper)
    ]


def slug(name: str) -> str:
    """``name`` made safe for one file name: runs of characters other than letters, digits and
    ``_.=-`` become ``_``, leading and trailing ``_`` and ``.`` are dropped (never ``..``).
    Two names may share a slug (``a b``, ``a_b``): a study refuses such scenario names."""
    return re.sub(r"[^A-Za-z0-9_.=-]+", "_", name).strip("_.") or "scenario"
