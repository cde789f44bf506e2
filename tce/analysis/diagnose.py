"""Why a scene fails: the interfaces that bind and the mechanism, in words a user can act on.

:func:`binding_interfaces` reads a force state: an interface binds when its pressure point
lies on the boundary of the contact polygon (the joint is about to open: a hinge) or when
a vertex force sits on the edge of its friction cone (about to slide). :func:`diagnose`
solves a scene and explains a non-``optimal`` answer:

``infeasible``
    beyond the limit: the direct limit state (its binding interfaces and its collapse
    mechanism); when the structure cannot even carry its self-weight, Clarabel's Farkas
    certificate as a mechanism, when it has one.
``unbounded``
    the support motion is incompatible with the material: the interfaces that carry the
    self-stress along which the TCE decreases without end (Heyman joints asked to slide).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..core.analysis import Analysis
from ..core.limit import Mechanism
from ..core.loads import LoadPattern, as_pattern
from ..core.result import Result
from ..core.solve import TCEResult
from ..structures.assembly import Assembly

__all__ = ["Diagnosis", "binding_interfaces", "diagnose"]


def _on_boundary(point: np.ndarray, polygon: np.ndarray, tol: float) -> bool:
    """True when ``point`` lies within ``tol`` of an edge of ``polygon`` (both in 3D, m)."""
    a, b = polygon, np.roll(polygon, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", point - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    d = np.linalg.norm(a + t[:, None] * ab - point, axis=1)
    return bool(d.min() <= tol)


def binding_interfaces(
    result: TCEResult, assembly: Assembly, friction: float | None, tol: float = 1e-6
) -> list[tuple[str, str]]:
    """``(interface, what)`` pairs of an optimal force state that sit on a limit.

    ``what`` is ``"hinge"`` (pressure point on the polygon's boundary) or ``"sliding"``
    (some vertex with ``||ft|| >= (1 - tol) mu fn > 0``). ``tol`` is relative to the
    assembly size (distances) and to the cone.
    """
    if not result.ok:
        return []
    a = assembly
    vf = result.vertex_forces
    vertex_slot = result.interface_map.vertex_slot
    out = []
    for slot, k in enumerate(result.interfaces):
        itf = a.interfaces[k]
        name = f"{a.names[itf.a]}|{a.names[itf.b]}"
        pp = result.pressure_points[slot]
        if np.all(np.isfinite(pp)) and _on_boundary(pp, itf.points, tol * a.size):
            out.append((name, "hinge"))
        if friction is not None and friction > 0:
            f = vf[vertex_slot == slot]
            fn, ft = f[:, 0], np.linalg.norm(f[:, 1:], axis=1)
            if np.any((fn > tol * a.total_weight) & (ft >= (1 - tol) * friction * fn)):
                out.append((name, "sliding"))
    return out


@dataclass(frozen=True, eq=False, kw_only=True)
class Diagnosis(Result):
    """What a scene's status means, where.

    Attributes
    ----------
    status : str
        Status of the scene's TCE solve.
    message : str
        One or two sentences for the user (also :attr:`summary`).
    binding : list of (str, str)
        ``(interface "A|B", "hinge" | "sliding" | "self-stress")``.
    mechanism : Mechanism or None
    """

    binding: list[tuple[str, str]] = field(default_factory=list)
    mechanism: Mechanism | None = None

    @property
    def summary(self) -> str:
        """The explanation: the :attr:`message`."""
        return self.message


def diagnose(
    analysis: Analysis,
    lam: float = 0.0,
    alpha: float | None = None,
    settlements: Mapping[str, ArrayLike] | None = None,
    loads: LoadPattern | None = None,
) -> Diagnosis:
    """Solve one scene (multiplier ``lam`` of the pattern ``loads``, or of the lateral pattern
    in direction ``alpha``) and explain its status (see module docstring)."""
    t0 = time.perf_counter()
    pattern = as_pattern(alpha, loads)
    solved: list[Result] = []

    def done(status: str, summary: str, binding: list | None = None, mechanism: Mechanism | None = None) -> Diagnosis:
        return Diagnosis(
            status=status, message=summary, binding=list(binding or []), mechanism=mechanism,
            solve_time=sum(r.solve_time for r in solved), wall_time=time.perf_counter() - t0,
        )

    result = analysis.solve(lam, settlements=settlements, loads=pattern)
    solved.append(result)
    mu = analysis.material.friction
    a = analysis.assembly
    if result.status == "optimal":
        bind = binding_interfaces(result, a, mu)
        return done("optimal", f"admissible at lambda = {lam:g}; {len(bind)} interface limit(s) reached", bind)
    if result.status == "infeasible":
        lim = analysis.limit(loads=pattern)
        solved.append(lim)
        if lim.status == "optimal" and lam > lim.lambda_max:
            at = analysis.solve(lim.lambda_max * (1 - 1e-9), settlements=settlements, loads=pattern)
            solved.append(at)
            bind = binding_interfaces(at, a, mu, tol=1e-5)
            slots = analysis.model(lim.model).interfaces
            what = ", ".join(
                f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]} {m}"
                for k, m in zip(slots, lim.mechanism.modes)
                if m != "closed"
            )
            return done(
                "infeasible",
                f"lambda = {lam:g} exceeds lambda_max = {lim.lambda_max:.6g} "
                + (f"in direction {pattern.alpha:g} deg" if pattern.default else "of the load pattern's live part")
                + f"; the collapse mechanism: {what}",
                bind,
                lim.mechanism,
            )
        return done(
            "infeasible",
            "no admissible force state: the structure cannot carry these loads"
            + ("" if lim.mechanism is None else " (mechanism from the infeasibility certificate)"),
            [],
            lim.mechanism,
        )
    if result.status == "unbounded":
        kind = analysis.model_kind(settlements=settlements, loads=pattern)
        solver = analysis.solver(kind)
        d = solver.recession_direction(result.settlements)
        model = solver.model
        mag = np.abs(d.reshape(model.n_contacts, model.dim)).max(axis=1)
        hot = sorted({int(model.contact_interface[c]) for c in np.flatnonzero(mag > 1e-6 * max(mag.max(), 1e-300))})
        names = [f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]}" for k in hot]
        return done(
            "unbounded",
            "the support motion is incompatible with the material: the energy decreases without end along a "
            f"self-stress through {', '.join(names)}"
            + (" (tangential forces with no friction limit: give the joints a friction coefficient)" if mu is None else ""),
            [(n, "self-stress") for n in names],
        )
    return done(result.status, f"the solver could not decide ({result.message})")
