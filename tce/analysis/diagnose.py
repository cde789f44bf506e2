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

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..core.analysis import Analysis
from ..core.limit import Mechanism
from ..core.solve import TCEResult

__all__ = ["Diagnosis", "binding_interfaces", "diagnose"]


def _on_boundary(point: np.ndarray, polygon: np.ndarray, tol: float) -> bool:
    """True when ``point`` lies within ``tol`` of an edge of ``polygon`` (both in 3D, m)."""
    a, b = polygon, np.roll(polygon, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", point - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    d = np.linalg.norm(a + t[:, None] * ab - point, axis=1)
    return bool(d.min() <= tol)


def binding_interfaces(result: TCEResult, friction: float | None, tol: float = 1e-6) -> list[tuple[str, str]]:
    """``(interface, what)`` pairs of an optimal force state that sit on a limit.

    ``what`` is ``"hinge"`` (pressure point on the polygon's boundary) or ``"sliding"``
    (some vertex with ``||ft|| >= (1 - tol) mu fn > 0``). ``tol`` is relative to the
    assembly size (distances) and to the cone.
    """
    if not result.ok:
        return []
    model = result.model_ref
    a = model.assembly
    vf = result.vertex_forces
    out = []
    for slot, k in enumerate(model.interfaces):
        itf = a.interfaces[k]
        name = f"{a.names[itf.a]}|{a.names[itf.b]}"
        pp = result.pressure_points[slot]
        if np.all(np.isfinite(pp)) and _on_boundary(pp, itf.points, tol * a.size):
            out.append((name, "hinge"))
        if friction is not None and friction > 0:
            f = vf[model.vertex_slot == slot]
            fn, ft = f[:, 0], np.linalg.norm(f[:, 1:], axis=1)
            if np.any((fn > tol * a.total_weight) & (ft >= (1 - tol) * friction * fn)):
                out.append((name, "sliding"))
    return out


@dataclass(frozen=True)
class Diagnosis:
    """What a scene's status means, where.

    Attributes
    ----------
    status : str
        Status of the scene's TCE solve.
    summary : str
        One or two sentences for the user.
    binding : list of (str, str)
        ``(interface "A|B", "hinge" | "sliding" | "self-stress")``.
    mechanism : Mechanism or None
    """

    status: str
    summary: str
    binding: list[tuple[str, str]] = field(default_factory=list)
    mechanism: Mechanism | None = None


def diagnose(
    analysis: Analysis,
    lam: float = 0.0,
    alpha: float = 0.0,
    settlements: Mapping[str, ArrayLike] | None = None,
) -> Diagnosis:
    """Solve one scene and explain its status (see module docstring)."""
    result = analysis.solve(lam, alpha, settlements)
    mu = analysis.material.friction
    a = analysis.assembly
    if result.status == "optimal":
        bind = binding_interfaces(result, mu)
        return Diagnosis("optimal", f"admissible at lambda = {lam:g}; {len(bind)} interface limit(s) reached", bind)
    if result.status == "infeasible":
        lim = analysis.limit(alpha)
        if lim.status == "optimal" and lam > lim.lambda_max:
            at = analysis.solve(lim.lambda_max * (1 - 1e-9), alpha, settlements)
            bind = binding_interfaces(at, mu, tol=1e-5)
            slots = analysis.model(lim.model).interfaces
            what = ", ".join(
                f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]} {m}"
                for k, m in zip(slots, lim.mechanism.modes)
                if m != "closed"
            )
            return Diagnosis(
                "infeasible",
                f"lambda = {lam:g} exceeds lambda_max = {lim.lambda_max:.6g} in direction {alpha:g} deg; "
                f"the collapse mechanism: {what}",
                bind,
                lim.mechanism,
            )
        return Diagnosis(
            "infeasible",
            "no admissible force state: the structure cannot carry these loads"
            + ("" if lim.mechanism is None else " (mechanism from the infeasibility certificate)"),
            [],
            lim.mechanism,
        )
    if result.status == "unbounded":
        kind = analysis.model_kind(alpha, settlements)
        solver = analysis.solver(kind)
        d = solver.recession_direction(result.settlements)
        model = solver.model
        mag = np.abs(d.reshape(model.n_contacts, model.dim)).max(axis=1)
        hot = sorted({int(model.contact_interface[c]) for c in np.flatnonzero(mag > 1e-6 * max(mag.max(), 1e-300))})
        names = [f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]}" for k in hot]
        return Diagnosis(
            "unbounded",
            "the support motion is incompatible with the material: the energy decreases without end along a "
            f"self-stress through {', '.join(names)}"
            + (" (tangential forces with no friction limit: give the joints a friction coefficient)" if mu is None else ""),
            [(n, "self-stress") for n in names],
        )
    return Diagnosis(result.status, f"the solver could not decide ({result.message})")
