"""One assembly and material, solved scene by scene with the model each scene needs.

:class:`Analysis` builds the operators of the spatial and (when the geometry allows) the
planar model once, keeps one warm solver per model, and routes each scene: ``auto`` uses
the planar LP when the geometry has a vertical symmetry plane and the scene's lateral
direction and support motions lie in it (DESIGN.md, "model only what a scene needs"),
the spatial model otherwise. Every answer records the model that ran.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Literal

from numpy.typing import ArrayLike

from ..structures.assembly import Assembly
from .limit import LimitResult, LimitSolver
from .material import Material
from .model import Model, build_model, find_plane, scene_in_plane
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
        self._limits: dict[tuple[str, float], LimitResult] = {}
        self._limit_solvers: dict[str, LimitSolver] = {}

    def reset_solvers(self) -> None:
        """Drop the warm solvers (keeping the operators), so that the next answer does not
        depend on what was solved before (Clarabel keeps the first problem's scaling)."""
        self._solvers.clear()

    def model_kind(self, alpha: float = 0.0, settlements: Settlements = None) -> str:
        """The model a scene runs on (see module docstring)."""
        if self.choice == "spatial" or self.plane is None:
            return "spatial"
        sett = check_settlements(self.assembly.support_names, settlements)
        inplane = scene_in_plane(self.plane, alpha, sett)
        if self.choice == "planar" and not inplane:
            raise ValueError("model='planar' but the scene's loads or support motions leave the plane")
        return "planar" if inplane else "spatial"

    def model(self, kind: str) -> Model:
        """The operators of model ``kind`` (built on first use)."""
        if kind not in self._models:
            self._models[kind] = build_model(self.assembly, kind)  # type: ignore[arg-type]
        return self._models[kind]

    def solver(self, kind: str) -> TCESolver:
        """The warm TCE solver of model ``kind``."""
        if kind not in self._solvers:
            self._solvers[kind] = TCESolver(self.model(kind), self.material, self.options)
        return self._solvers[kind]

    def solve(self, lam: float = 0.0, alpha: float = 0.0, settlements: Settlements = None) -> TCEResult:
        """Minimise the TCE for one scene; see :meth:`tce.solve.TCESolver.solve`."""
        return self.solver(self.model_kind(alpha, settlements)).solve(lam, alpha, settlements)

    def limit(self, alpha: float = 0.0) -> LimitResult:
        """Direct lambda_max in direction ``alpha`` (degrees), cached per direction."""
        kind = self.model_kind(alpha)
        key = (kind, float(alpha))
        if key not in self._limits:
            if kind not in self._limit_solvers:
                self._limit_solvers[kind] = LimitSolver(self.model(kind), self.material)
            self._limits[key] = self._limit_solvers[kind].solve(alpha)
        return self._limits[key]
