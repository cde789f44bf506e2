"""Analyses built on TCE solves: the load path, minimum thickness, the diagnosis of a failing scene
and the probability of collapse (:mod:`tce.analysis.reliability`).

:class:`Analysis` (one assembly and material, scene by scene) lives in :mod:`tce.core.analysis`
and is re-exported here, where scripts import it from.
"""

from typing import Any

__all__ = ["Analysis"]


def __getattr__(name: str) -> Any:
    if name == "Analysis":  # imported on first use: importing one analysis module does not build the solvers
        from ..core.analysis import Analysis

        return Analysis
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
