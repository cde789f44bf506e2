"""One assembly and material, solved scene by scene with the model each scene needs.

:class:`Analysis` builds the operators of the spatial and (when the geometry allows) the
planar model once, keeps one warm solver per model, and routes each scene: ``auto`` uses
the planar LP when the geometry has a vertical symmetry plane and the scene's loads (the
lateral direction, and every block's wrench of the other loads of its
:class:`tce.core.loads.LoadPattern`) and support motions lie in it (``docs/conventions.md``,
"model only what a scene needs"), the spatial model otherwise. Every answer records the
model that ran. Every method takes a lateral direction ``alpha`` (the paper's pattern) or a
load pattern ``loads``.
"""

from __future__ import annotations

import math

import time
from collections.abc import Callable, Mapping
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import display
from ..structures.assembly import Assembly
from .limit import LimitResult, LimitSolver
from .loads import AppliedLoads, LoadPattern, as_pattern, resolve
from .material import Material
from .model import Model, build_model, find_plane, motions_in_plane
from .problem import Formulation
from .solve import SolverOptions, TCEResult, TCESolver, check_settlements

__all__ = ["Analysis"]

Settlements = Mapping[str, ArrayLike] | None


class Analysis:
    """TCE solves and limit analyses of one assembly and material.

    Parameters
    ----------
    assembly : Assembly
        Validated on construction.
    material : Material
    model : {"auto", "spatial", "planar"}
        ``planar`` forces the 2D model (an error for scenes out of plane); ``spatial`` forces 3D.
    options : SolverOptions, optional
    """

    def __init__(
        self,
        assembly: Assembly,
        material: Material | None = None,
        model: Literal["auto", "spatial", "planar"] = "auto",
        options: SolverOptions | None = None,
    ) -> None:
        if model not in ("auto", "spatial", "planar"):
            raise ValueError(f"model must be 'auto', 'spatial' or 'planar', got {model!r}")
        self.assembly = assembly.validate()
        self.material = material or Material()
        self.choice = model
        self.options = options or SolverOptions()
        self.plane = find_plane(self.assembly) if model != "spatial" else None
        if model == "planar" and self.plane is None:
            raise ValueError("model='planar' asked for an assembly that is not planar")
        self._models: dict[str, Model] = {}
        self._solvers: dict[str, TCESolver] = {}
        self._limits: dict[tuple[str, LoadPattern], LimitResult] = {}
        self._limit_solvers: dict[str, LimitSolver] = {}
        self._formulations: dict[str, Formulation] = {}

    def _facts(self) -> dict[str, str]:
        """What the repr and the HTML table show."""
        a = self.assembly
        if self.choice == "spatial" or self.plane is None:
            models = "spatial" + (" (forced)" if self.choice == "spatial" else " (not planar)")
        else:
            models = "planar" if self.choice == "planar" else "planar for in-plane scenes, spatial otherwise"
        return {
            "assembly": f"{len(a.blocks)} blocks, {len(a.support_indices)} supports, {len(a.interfaces)} interfaces"
                        + (f" ({a.meta['generator']})" if "generator" in a.meta else ""),
            "models": models,
            "material": self.material.describe(),
            "built": ", ".join(sorted(self._models)) or "nothing yet",
        }

    def __repr__(self) -> str:
        f = self._facts()
        return display.call("Analysis", {}, head=f"{f['assembly']}; models: {f['models']}; {f['material']}")

    def _repr_html_(self) -> str:
        return display.html_table("Analysis", self._facts().items())

    def reset_solvers(self) -> None:
        """Drop the warm solvers (keeping the operators), so that the next answer does not
        depend on what was solved before (Clarabel keeps the first problem's scaling)."""
        self._solvers.clear()

    def applied_loads(self, alpha: float | None = None, loads: LoadPattern | None = None) -> AppliedLoads:
        """The pattern ``loads`` (or the default one in direction ``alpha``) resolved against
        the assembly: the point forces it applies (:func:`tce.core.loads.resolve`).

        Raises
        ------
        ValueError
            A non-finite ``alpha``, both ``alpha`` and a pattern with another one, or a load
            that cannot be applied (:class:`tce.core.loads.LoadError`, naming its key).
        """
        return resolve(as_pattern(alpha, loads), self.assembly)

    def model_kind(self, alpha: float | None = None, settlements: Settlements = None, loads: LoadPattern | None = None) -> str:
        """The model a scene runs on (see module docstring)."""
        return self.scene(alpha, settlements, loads)[0]

    def scene(
        self, alpha: float | None = None, settlements: Settlements = None, loads: LoadPattern | None = None
    ) -> tuple[str, NDArray[np.float64]]:
        """The model a scene runs on and its stacked support motions ``U`` (m, rad), checked.

        Raises
        ------
        ValueError
            A non-finite ``alpha``, loads that cannot be applied, an unknown support, a
            motion that is not 6 finite numbers, or a scene out of plane when
            ``model='planar'`` was asked for.
        """
        applied = self.applied_loads(alpha, loads)
        names = self.assembly.support_names
        sett = check_settlements(names, settlements)
        U = np.zeros((len(names), 6))
        for name, v in sett.items():
            U[names.index(name)] = v
        U = U.ravel()
        U.flags.writeable = False  # shared by every answer of the scene: nobody edits it
        if self.choice == "spatial" or self.plane is None:
            return "spatial", U
        inplane = applied.in_plane(self.plane) and motions_in_plane(self.plane, sett)
        if self.choice == "planar" and not inplane:
            raise ValueError("model='planar' but the scene's loads or support motions leave the plane")
        return ("planar" if inplane else "spatial"), U

    def model(self, kind: str) -> Model:
        """The operators of model ``kind`` (built on first use)."""
        if kind not in self._models:
            self._models[kind] = build_model(self.assembly, kind)  # type: ignore[arg-type]
        return self._models[kind]

    def formulation(self, kind: str) -> Formulation:
        """The scaled operators of model ``kind`` and the material (built on first use), which
        the TCE and limit solvers of that model share."""
        if kind not in self._formulations:
            self._formulations[kind] = Formulation(self.model(kind), self.material)
        return self._formulations[kind]

    def solver(self, kind: str) -> TCESolver:
        """The warm TCE solver of model ``kind``."""
        if kind not in self._solvers:
            self._solvers[kind] = TCESolver(self.model(kind), self.material, self.options, self.formulation(kind))
        return self._solvers[kind]

    def solve(
        self, lam: float = 0.0, alpha: float | None = None, settlements: Settlements = None, loads: LoadPattern | None = None
    ) -> TCEResult:
        """Minimise the TCE for one scene (checked once, :meth:`scene`); see
        :meth:`tce.core.solve.TCESolver.solve`."""
        t0 = time.perf_counter()
        if not math.isfinite(lam):
            raise ValueError(f"lam must be a finite number, got {lam!r}")
        pattern = as_pattern(alpha, loads)
        kind, U = self.scene(settlements=settlements, loads=pattern)
        return self.solver(kind).solve_scene(lam, pattern, U, t0)

    def path(
        self, alpha: float | None = None, settlements: Settlements = None, loads: LoadPattern | None = None
    ) -> Callable[[float], TCEResult]:
        """``solve(lam)`` for one scene at many multipliers: the scene is checked once, here
        (the load path's hot loop; each call is :meth:`solve` without the checks)."""
        pattern = as_pattern(alpha, loads)
        kind, U = self.scene(settlements=settlements, loads=pattern)

        def solve(lam: float) -> TCEResult:
            t0 = time.perf_counter()
            if not math.isfinite(lam):
                raise ValueError(f"lam must be a finite number, got {lam!r}")
            return self.solver(kind).solve_scene(lam, pattern, U, t0)

        return solve

    def limit(self, alpha: float | None = None, loads: LoadPattern | None = None, mechanism: bool = True) -> LimitResult:
        """Direct lambda_max of the live part of the pattern ``loads`` (default: the lateral
        pattern in direction ``alpha``, degrees), cached per pattern; its mechanism is
        classified when ``mechanism`` is True (once: a later call adds it to the cached
        answer)."""
        pattern = as_pattern(alpha, loads)
        kind = self.model_kind(loads=pattern)
        key = (kind, pattern)
        if kind not in self._limit_solvers:
            self._limit_solvers[kind] = LimitSolver(self.model(kind), self.material, formulation=self.formulation(kind))
        solver = self._limit_solvers[kind]
        if key not in self._limits:
            self._limits[key] = solver.solve(loads=pattern, mechanism=mechanism)
        elif mechanism:
            self._limits[key] = solver.with_mechanism(self._limits[key])
        return self._limits[key]
