"""Analyses built on TCE solves: the load path, minimum thickness and the diagnosis of a failing scene.

:class:`Analysis` (one assembly and material, scene by scene) lives in :mod:`tce.core.analysis`
and is re-exported here, where scripts import it from.
"""

from ..core.analysis import Analysis

__all__ = ["Analysis"]
