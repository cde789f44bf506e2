"""What a finished scenario's answer depends on beyond the study file (for resuming).

A scenario file is reused by a rerun only when its key (:attr:`tce.study.Scenario.key`) is
the key the scenario has now. Besides every input of the study, the key holds what this
module returns: how the study runner narrows a load path (:data:`BRACKET`), the solver's
settings (:func:`solver_settings`) and a digest of the installed tce code
(:func:`code_digest`), so that a change of a tolerance or an iteration limit in the
installed code, with the same version number, solves every scenario again.
"""

from __future__ import annotations

import dataclasses
import hashlib
import inspect
from functools import lru_cache
from pathlib import Path

__all__ = ["BRACKET", "code_digest", "solver_settings"]

#: how the study runner narrows the last increment of a load path
#: (``bracket`` of :func:`tce.analysis.loadpath.load_path`)
BRACKET = "direct"

#: the installed tce package (the folder holding this module's package)
PACKAGE = Path(__file__).resolve().parents[1]


@lru_cache(maxsize=4)
def code_digest(root: Path = PACKAGE) -> str:
    """SHA-256 of the installed tce code: every ``.py`` file under ``root``, by relative path
    and content, in sorted order (read once per process)."""
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(path.relative_to(root).as_posix().encode() + b"\x00")
        h.update(path.read_bytes() + b"\x00")
    return h.hexdigest()


def solver_settings() -> dict[str, dict]:
    """The settings the study runner solves with: the TCE solves'
    :class:`tce.core.clarabel_solver.SolverOptions` and the direct limit's tolerance."""
    from ..core.clarabel_solver import SolverOptions
    from ..core.limit import LimitSolver

    limit_tol = inspect.signature(LimitSolver.__init__).parameters["tol"].default
    return {"tce": dataclasses.asdict(SolverOptions()), "limit": {"tol": limit_tol}}
