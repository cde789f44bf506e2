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

No finite limit (:func:`explain_no_limit`, :func:`no_limit_reason`): when the load path
reaches ``lambda_cap`` (outcome ``no_limit``) or the direct limit is unbounded, the reason
in words. An unbounded direct limit has a certificate: an admissible force state ``F`` with
``A_eq F + b_live = 0``, carrying the live load with no self-weight
(:meth:`tce.core.limit.LimitSolver.lateral_ray`); any multiple of it can be added to any
admissible state. The interfaces it loads are the ones responsible: if the contacts of the
free blocks with the supports can carry it alone, the live load goes straight into a
support; otherwise the blocks lock against each other.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..core.analysis import Analysis
from ..core.limit import LimitSolver, Mechanism
from ..core.loads import LoadPattern, as_pattern
from ..core.result import Result
from ..core.solve import TCEResult
from ..structures.assembly import Assembly
from .loadpath import LoadPathResult

__all__ = [
    "Diagnosis",
    "NoLimit",
    "binding_interfaces",
    "diagnose",
    "explain_no_limit",
    "no_limit_reason",
    "unbounded_reason",
]

#: interfaces named in a no-limit message before "and k more"
NAMED = 6


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


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class Diagnosis(Result):
    """What a scene's status means, where (``status``: that of the scene's TCE solve;
    ``message``: the explanation, also :attr:`summary`).

    Attributes
    ----------
    binding : list of (str, str)
        ``(interface "A|B", "hinge" | "sliding" | "self-stress")``.
    mechanism : Mechanism or None
    no_limit : NoLimit or None
        Why the scene's direction has no finite collapse load, when it has none.
    """

    binding: list[tuple[str, str]] = field(default_factory=list)
    mechanism: Mechanism | None = None
    no_limit: NoLimit | None = None


    @property
    def summary(self) -> str:
        """The explanation: the :attr:`message`."""
        return self.message


@dataclass(frozen=True)
class NoLimit:
    """Why a direction has no finite collapse load.

    Attributes
    ----------
    reason : str
        ``into_support`` (the free blocks' contacts with the supports carry the live load
        without limit), ``locked`` (the blocks lock against each other and the supports),
        ``beyond_cap`` (the direct limit is finite but above the largest load tried),
        ``finite`` (there is a finite limit) or ``undecided`` (the direct limit analysis did
        not answer).
    summary : str
        The explanation in words.
    interfaces : list of str
        ``"A|B"`` of the interfaces that carry the live load without limit, most loaded first.
    blocks : list of str
        Free blocks that pass their live load straight into a support.
    """

    reason: str
    summary: str
    interfaces: list[str] = field(default_factory=list)
    blocks: list[str] = field(default_factory=list)


def _names(items: list[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def explain_no_limit(
    analysis: Analysis, alpha: float | None = None, reached: float | None = None, loads: LoadPattern | None = None
) -> NoLimit:
    """Why lateral loads in direction ``alpha`` (degrees), or the live loads of the pattern
    ``loads``, find no collapse (module docstring); ``reached`` is the largest multiplier a
    load path found admissible (for the message when the direct limit is finite)."""
    pattern = as_pattern(alpha, loads)
    where = f"in direction {pattern.alpha:g} deg" if pattern.default else "for the live loads of the pattern"
    what = "lateral load" if pattern.default else "live load"
    lim = analysis.limit(loads=pattern)
    if lim.status == "optimal":
        lmax = f"lambda_max = {lim.lambda_max:.6g} {where}"
        if reached is not None and lim.lambda_max > reached:
            return NoLimit("beyond_cap", f"the direct limit {lmax} lies beyond the largest load tried "
                           f"(lambda = {reached:g}); raise [loads] lambda_cap")
        below = "" if reached is None else f", below the largest load found admissible (lambda = {reached:g})"
        return NoLimit("finite", f"there is a finite limit: {lmax}{below}")
    if lim.status != "unbounded":
        return NoLimit(
            "undecided",
            f"no collapse found, and the direct limit analysis {where} is {lim.status} ({lim.message})",
        )
    a = analysis.assembly
    model = analysis.model(lim.model)
    solver = LimitSolver(model, analysis.material)
    sup = set(a.support_indices)
    touches = np.array([a.interfaces[k].a in sup or a.interfaces[k].b in sup for k in model.contact_interface], bool)
    ray = solver.lateral_ray(contacts=touches, loads=pattern)
    reason = "into_support" if ray is not None else "locked"
    if ray is None:
        ray = solver.lateral_ray(loads=pattern)
    if ray is None:
        return NoLimit("undecided", f"the direct limit {where} is unbounded, but no force state "
                       f"carrying the {what} alone was found")
    load = np.zeros(len(a.interfaces))
    np.add.at(load, model.contact_interface, np.linalg.norm(ray, axis=1))
    carried = [int(k) for k in np.argsort(-load, kind="stable") if load[k] > 1e-6 * load.max()]
    names = list(dict.fromkeys(f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]}" for k in carried))
    direct = {i.a if i.b in sup else i.b for i in (a.interfaces[k] for k in carried) if (i.a in sup) != (i.b in sup)}
    bearing = [a.names[i] for i in a.free_indices if i in direct]
    # the blocks the ray passes the load through (all of them for the lateral pattern)
    involved = {b for k in carried for b in (a.interfaces[k].a, a.interfaces[k].b)}
    held = [a.names[i] for i in a.free_indices if i not in direct and i in involved]
    supports = [a.names[i] for i in a.support_indices if any(i in (a.interfaces[k].a, a.interfaces[k].b) for k in carried)]
    listed = _names(names[:NAMED] + ([f"{len(names) - NAMED} more"] if len(names) > NAMED else []))
    s_sup = f"support{'s' if len(supports) > 1 else ''} {_names(supports)}"
    heyman = " (the contacts have no friction limit: Heyman material)" if analysis.material.friction is None else ""
    if reason == "into_support":
        summary = (
            f"no finite collapse load {where}: the {what} goes straight into the {s_sup}: "
            f"{'block' if len(bearing) == 1 else 'blocks'} {_names(bearing)} "
            f"{'bears' if len(bearing) == 1 else 'bear'} on {'it' if len(supports) == 1 else 'them'} through "
            f"{listed}, which carry any multiple of it under rigid contacts{heyman}"
        )
    else:
        who = (
            f"{'block' if len(bearing) == 1 else 'blocks'} {_names(bearing)} "
            f"{'bears' if len(bearing) == 1 else 'bear'} on the {s_sup}"
        ) if bearing else ""
        if held:
            who += (" and " if who else "") + (
                f"{'block' if len(held) == 1 else 'blocks'} {_names(held)} "
                f"{'is' if len(held) == 1 else 'are'} held between {'its' if len(held) == 1 else 'their'} neighbours"
            )
        summary = (
            f"no finite collapse load {where}: the blocks lock under rigid contacts: {who}, "
            f"so any multiple of the {what} is carried through {listed}; no collapse mechanism exists{heyman}"
        )
    return NoLimit(reason, summary, names, bearing)


def no_limit_reason(analysis: Analysis, lp: LoadPathResult) -> str:
    """The explanation of the load path ``lp`` run by ``analysis`` when its outcome is
    ``no_limit`` ("" for any other outcome)."""
    if lp.outcome != "no_limit":
        return ""
    reached = max((r.lam for r in lp.steps if r.ok), default=None)
    return explain_no_limit(analysis, reached=reached, loads=lp.loads).summary


_COMPONENTS = ("ux", "uy", "uz", "rx", "ry", "rz")


def unbounded_reason(analysis: Analysis, lp: LoadPathResult) -> str:
    """Why a load path ended ``unbounded`` ("" for any other outcome): which support motion the
    material cannot follow, and why, as :func:`no_limit_reason` explains ``no_limit``.

    An unbounded TCE has a certificate: a self-stress ``d`` (``A_eq d = 0``, ``d`` in the
    recession cone of the contact law: a force state that carries no load) whose support
    reactions do positive work on the prescribed motion, ``-(B_sup d) . U < 0``
    (:func:`tce.core.problem.recession_problem`); adding any multiple of it lowers the energy
    without end. The supports whose reactions do that work are the motions the material
    cannot follow; the contacts it loads say how: mainly tangential forces at contacts with
    no friction limit (a Heyman material cannot slide, and the motion asks it to), or
    mainly normal forces (rigid contacts cannot shorten, and the motion presses the blocks
    together).
    """
    if lp.outcome != "unbounded":
        return ""
    step = next(r for r in lp.steps if r.status == "unbounded")
    solver = analysis.solver(step.model)
    model, a = solver.model, analysis.assembly
    U = np.asarray(step.settlements, dtype=float)
    d = solver.recession_direction(U)
    if not np.all(np.isfinite(d)):
        return "the support motion is incompatible with the material (the self-stress that shows why was not found)"
    F = d.reshape(model.n_contacts, model.dim)
    work = -(model.B_sup @ d).reshape(-1, 6) * U.reshape(-1, 6)  # per support and component, in -(R . U)
    names = list(a.support_names)
    moving = [k for k in range(len(names)) if work[k].sum() < -1e-9 * max(np.abs(work).max(), 1e-300)]
    what = [
        f"{names[k]} ({', '.join(f'{c} = {v:g}' for c, v in zip(_COMPONENTS, U.reshape(-1, 6)[k]) if v)})"
        for k in moving
    ]
    mag = np.linalg.norm(F, axis=1)
    hot = sorted({int(model.contact_interface[c]) for c in np.flatnonzero(mag > 1e-6 * max(mag.max(), 1e-300))})
    itfs = [f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]}" for k in hot]
    listed = _names(itfs[:NAMED] + ([f"{len(itfs) - NAMED} more"] if len(itfs) > NAMED else []))
    tangential = float(np.abs(F[:, 1:]).sum()) > float(np.abs(F[:, 0]).sum())
    if tangential and analysis.material.friction is None:
        why = ("the joints have no friction limit (Heyman material): they take any tangential force and cannot "
               "slide, and the motion asks them to; give the joints a friction coefficient")
    elif tangential:
        why = "the motion asks the contacts to slide in a way their friction cones do not allow"
    else:
        why = ("rigid contacts cannot shorten, and the motion presses the blocks together; give the joints a "
               "stiffness (normal_stiffness) to let them follow it")
    who = f"the motion of support{'s' if len(what) > 1 else ''} {_names(what)}" if what else "the support motion"
    return (f"{who} cannot be followed: a self-stress (a force state carrying no load) through {listed} is "
            f"admissible and its reactions do positive work on that motion, so the energy decreases without end; "
            f"{why}")


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

    def done(
        status: str, summary: str, binding: list | None = None, mechanism: Mechanism | None = None,
        no_limit: NoLimit | None = None,
    ) -> Diagnosis:
        return Diagnosis(
            status=status, message=summary, binding=list(binding or []), mechanism=mechanism, no_limit=no_limit,
            solve_time=sum(r.solve_time for r in solved), wall_time=time.perf_counter() - t0,
        )

    result = analysis.solve(lam, settlements=settlements, loads=pattern)
    solved.append(result)
    mu = analysis.material.friction
    a = analysis.assembly
    if result.status == "optimal":
        bind = binding_interfaces(result, a, mu)
        summary = f"admissible at lambda = {lam:g}; {len(bind)} interface limit(s) reached"
        if analysis.limit(loads=pattern).status == "unbounded":
            why = explain_no_limit(analysis, loads=pattern)
            return done("optimal", f"{summary}; {why.summary}", bind, no_limit=why)
        return done("optimal", summary, bind)
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
