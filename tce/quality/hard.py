"""Hard cases for the solver, as data: used by ``tests/hard`` and by ``tce check``.

Each :class:`HardCase` runs one or more solves, checks the case's invariants (identical
dimensionless answers across units, monotone thrust, ...) and bounds the residuals of its
``optimal`` answers (:class:`tce.core.solve.TCEResult`). :func:`run_case` never raises: an
exception is reported as a failure.

Reference scene: the paper's semicircular arch (inner radius 1 m, thickness 0.2 m, depth
0.25 m, 14 voussoirs, 20 kN/m^3); settlements are applied to the right support; thrust ``H``
is the horizontal reaction of the right support on the arch, made dimensionless by the
total weight ``W``.
"""

from __future__ import annotations

import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from ..core.analysis import Analysis
from ..structures.arch import semicircular_arch
from ..structures.assembly import Assembly, Block, Interface
from ..structures.geometry import box
from ..core.material import Material
from ..core.solve import TCEResult

__all__ = ["CASES", "CaseRun", "HardCase", "Outcome", "run_case"]

MM = 1e-3  # a 1 mm support motion (m)
HEYMAN = Material()
FRICTION = Material(0.8)


@dataclass
class Outcome:
    """What a case's runner returns: every solve it made, and any broken invariant."""

    results: list[TCEResult] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)

    def add(self, result: TCEResult) -> TCEResult:
        """Record ``result`` and return it."""
        self.results.append(result)
        return result

    def expect_close(self, what: str, got: float, ref: float, rtol: float) -> None:
        """Record an error when ``got`` differs from ``ref`` by more than ``rtol`` (relative)."""
        if not np.isfinite(got) or abs(got - ref) > rtol * max(abs(ref), 1e-300):
            self.errors.append(f"{what}: {got!r} != {ref!r} (rtol {rtol:g})")


@dataclass(frozen=True)
class HardCase:
    """One hard case.

    Attributes
    ----------
    name : str
    run : callable
        ``() -> Outcome``.
    expected : tuple of str
        Statuses every solve may end with.
    residual_bound : float
        Bound on ``max(eq_residual, cone_residual)`` of every ``optimal`` solve.
    """

    name: str
    run: Callable[[], Outcome]
    expected: tuple[str, ...]
    residual_bound: float = 1e-9


@dataclass(frozen=True)
class CaseRun:
    """The result of :func:`run_case`.

    Attributes
    ----------
    case : HardCase
    statuses : tuple of str
        Distinct statuses, in order of appearance ("error" on an exception).
    residual : float
        Largest residual over the ``optimal`` solves (NaN if none).
    retries : tuple of str
        Distinct non-empty ``TCEResult.retry`` values.
    n_solves : int
    time : float
        Wall time of the case (s).
    errors : tuple of str
        Wrong statuses, residuals above the bound, broken invariants, exceptions, no solve.
    """

    case: HardCase
    statuses: tuple[str, ...]
    residual: float
    retries: tuple[str, ...]
    n_solves: int
    time: float
    errors: tuple[str, ...]

    @property
    def ok(self) -> bool:
        """True when the case passed."""
        return not self.errors


def run_case(case: HardCase) -> CaseRun:
    """Run ``case`` and judge it (never raises)."""
    t0 = time.perf_counter()
    try:
        out = case.run()
    except Exception as exc:  # a hard case must never raise: report it as a failure
        tb = traceback.format_exception_only(type(exc), exc)[-1].strip()
        return CaseRun(case, ("error",), float("nan"), (), 0, time.perf_counter() - t0, (tb,))
    elapsed = time.perf_counter() - t0
    errors = list(out.errors)
    if not out.results:
        errors.append("no solve recorded: the case checked nothing")
    res = []
    for k, r in enumerate(out.results):
        # np.max, not max: a residual that is NaN (never computed) must not pass as small
        worst = float(np.max([r.eq_residual, r.cone_residual]))
        if r.ok:
            res.append(worst)
        if r.status not in case.expected:
            errors.append(f"solve {k} (lam={r.lam:.12g}): status {r.status!r} ({r.message})")
        elif r.ok and not worst <= case.residual_bound:
            errors.append(f"solve {k}: residual {worst:.3g} above bound {case.residual_bound:.3g}")
    statuses = tuple(dict.fromkeys(r.status for r in out.results))
    retries = tuple(dict.fromkeys(r.retry for r in out.results if r.retry))
    return CaseRun(
        case, statuses, float(np.max(res)) if res else float("nan"), retries, len(out.results), elapsed, tuple(errors)
    )


# ---------------------------------------------------------------------- helpers
def _right(u: Sequence[float]) -> dict[str, list[float]]:
    """Motion ``u`` of the right support."""
    return {"right": list(map(float, u))}


def _thrust(r: TCEResult) -> float:
    """Thrust H / W: the +x reaction of the right (last) support on the arch over the sum of
    the supports' vertical reactions."""
    w = r.support_wrenches
    return float(w[-1, 0] / w[:, 2].sum())


@lru_cache(maxsize=None)
def _arch(voussoirs: int = 14) -> Assembly:
    """The reference arch with ``voussoirs`` voussoirs, validated (built once)."""
    return semicircular_arch(voussoirs=voussoirs).validate()


@lru_cache(maxsize=None)
def _lambda_max(material: Material, kind: str) -> float:
    """Direct lambda_max of the reference arch at alpha = 0."""
    lim = Analysis(_arch(), material, model=kind).limit(0.0)  # type: ignore[arg-type]
    if lim.status != "optimal":
        raise RuntimeError(f"direct limit analysis: {lim.status} ({lim.message})")
    return lim.lambda_max


@lru_cache(maxsize=None)
def _min_thickness(centre_radius: float = 1.1, voussoirs: int = 14) -> float:
    """Minimum thickness (m) of the semicircular arch with this centreline radius (Heyman)."""
    from ..analysis.thickness import arch_minimum_thickness

    return arch_minimum_thickness(centre_radius, voussoirs, tol=1e-8).thickness


# ---------------------------------------------------------------------- cases
def _near_limit(factor: float) -> Callable[[], Outcome]:
    """lam = factor * lambda_max, planar Heyman and spatial mu=0.8, with and without settlement."""

    def run() -> Outcome:
        out = Outcome()
        for material, kind in ((HEYMAN, "planar"), (FRICTION, "spatial")):
            an = Analysis(_arch(), material, model=kind)  # type: ignore[arg-type]
            lam = factor * _lambda_max(material, kind)
            for sett in (None, _right([MM, 0, 0, 0, 0, 0]), _right([0, 0, -MM, 0, 0, 0])):
                out.add(an.solve(lam, 0.0, sett))
        return out

    return run


def _thickness(factor: float) -> Callable[[], Outcome]:
    """Arch of thickness factor * t_min at lam = 0 (Heyman), planar and spatial."""

    def run() -> Outcome:
        out = Outcome()
        R = 1.1
        t = factor * _min_thickness(R)
        asm = semicircular_arch(R - t / 2, t)
        for kind in ("planar", "spatial"):
            an = Analysis(asm, HEYMAN, model=kind)  # type: ignore[arg-type]
            for sett in (None, _right([MM, 0, 0, 0, 0, 0])):
                out.add(an.solve(0.0, 0.0, sett))
        return out

    return run


def _units(length: float, force: float, stiffness: float | None = None) -> Callable[[], Outcome]:
    """The arch in other units: lambda_max and H/W must not change (rel. 1e-7)."""

    def run() -> Outcome:
        out = Outcome()
        for material, kind in ((HEYMAN, "planar"), (FRICTION, "spatial")):
            scaled = material
            if stiffness is not None:
                material, scaled = Material(material.friction, stiffness), Material(material.friction, stiffness * force / length**3)
            ref = Analysis(_arch(), material, model=kind)  # type: ignore[arg-type]
            an = Analysis(_arch().scaled(length, force), scaled, model=kind)  # type: ignore[arg-type]
            lim, lim0 = an.limit(0.0), ref.limit(0.0)
            if lim.status != "optimal":
                out.errors.append(f"{kind} limit: {lim.status}")
            else:
                out.expect_close(f"{kind} lambda_max", lim.lambda_max, lim0.lambda_max, 1e-7)
            for lam, u in ((0.1, [MM, 0, 0, 0, 0, 0]), (0.2, [0, 0, -MM, 0, 0, 0])):
                r = out.add(an.solve(lam, 0.0, _right(np.multiply(u, length))))
                r0 = ref.solve(lam, 0.0, _right(u))
                if r.ok and r0.ok:
                    out.expect_close(f"{kind} H/W at lam={lam}", _thrust(r), _thrust(r0), 1e-7)
        return out

    return run


SETTLEMENTS = (1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 1e-2, 0.1)


def _rigid_settlements() -> Outcome:
    """Rigid: any outward settlement gives the same (minimum-thrust) state."""
    out = Outcome()
    for material, kind in ((HEYMAN, "planar"), (FRICTION, "spatial")):
        an = Analysis(_arch(), material, model=kind)  # type: ignore[arg-type]
        rs = [out.add(an.solve(0.0, 0.0, _right([d, 0, 0, 0, 0, 0]))) for d in SETTLEMENTS]
        if all(r.ok for r in rs):
            ref = rs[len(rs) // 2].support_wrenches
            scale = np.abs(ref).max()
            for d, r in zip(SETTLEMENTS, rs):
                dev = np.abs(r.support_wrenches - ref).max() / scale
                if dev > 1e-7:
                    out.errors.append(f"{kind}: reactions at {d:g} m differ by {dev:.2g} (relative)")
    return out


def _compliant_settlements() -> Outcome:
    """Compliant: |H| falls monotonically with the outward settlement, to the rigid minimum."""
    out = Outcome()
    rigid = Analysis(_arch(), FRICTION, model="planar").solve(0.0, 0.0, _right([MM, 0, 0, 0, 0, 0]))
    for kind in ("planar", "spatial"):
        an = Analysis(_arch(), Material(0.8, 1e6), model=kind)  # type: ignore[arg-type]
        h = [_thrust(out.add(an.solve(0.0, 0.0, _right([d, 0, 0, 0, 0, 0])))) for d in SETTLEMENTS]
        mag = np.abs(h)
        if np.any(np.diff(mag) > 1e-9 * mag[0]):
            out.errors.append(f"{kind}: |H|/W not monotone in the settlement: {mag}")
        out.expect_close(f"{kind} H/W at 0.1 m vs rigid minimum thrust", h[-1], _thrust(rigid), 1e-6)
    return out


STIFFNESSES = (1e-3, 1.0, 1e3, 1e6, 1e9, 1e12)


def _stiffness_range() -> Outcome:
    """1 mm outward settlement, stiffness 1e-3 .. 1e12 kN/m^3: |H| falls monotonically from
    the elastic state (no effect of the settlement) to the rigid minimum thrust."""
    out = Outcome()
    for mu, kind in ((None, "planar"), (0.8, "spatial")):
        h = []
        for k in STIFFNESSES:
            an = Analysis(_arch(), Material(mu, k), model=kind)  # type: ignore[arg-type]
            h.append(_thrust(out.add(an.solve(0.0, 0.0, _right([MM, 0, 0, 0, 0, 0])))))
        elastic = _thrust(Analysis(_arch(), Material(mu, 1.0), model=kind).solve(0.0))  # type: ignore[arg-type]
        rigid = _thrust(Analysis(_arch(), Material(mu), model=kind).solve(0.0, 0.0, _right([MM, 0, 0, 0, 0, 0])))  # type: ignore[arg-type]
        mag = np.abs(h)
        if np.any(np.diff(mag) > 1e-9 * mag[0]):
            out.errors.append(f"{kind}: |H|/W not monotone in the stiffness: {mag}")
        out.expect_close(f"{kind} H/W at k=1e-3 vs elastic", h[0], elastic, 1e-6)
        out.expect_close(f"{kind} H/W at k=1e12 vs rigid", h[-1], rigid, 1e-6)
    return out


def _stiff_interface() -> Outcome:
    """One joint (the crown's) 1e6 and 1e9 times stiffer than its neighbours, 1 mm spreading:
    planar and spatial agree, and the thrust has converged as the joint becomes rigid."""
    out = Outcome()
    base = _arch()
    crown = len(base.interfaces) // 2
    h = {}
    for ratio in (1e6, 1e9):
        itfs = [replace(i, stiffness=ratio) if k == crown else i for k, i in enumerate(base.interfaces)]
        a = base.with_interfaces(itfs)
        for kind in ("planar", "spatial"):
            an = Analysis(a, Material(0.8, 1e6), model=kind)  # type: ignore[arg-type]
            h[ratio, kind] = _thrust(out.add(an.solve(0.0, 0.0, _right([MM, 0, 0, 0, 0, 0]))))
        out.expect_close(f"planar vs spatial H/W, stiffness x{ratio:g}", h[ratio, "planar"], h[ratio, "spatial"], 1e-6)
    out.expect_close("H/W stiffness x1e6 vs x1e9", h[1e6, "planar"], h[1e9, "planar"], 1e-4)
    return out


def _friction(mu: float | None, expected_at_zero: str) -> Callable[[], Outcome]:
    """Friction ``mu`` (None: Heyman): lam 0, and (1 -+ 1e-6) lambda_max when there is one."""

    def run() -> Outcome:
        out = Outcome()
        for kind in ("planar", "spatial"):
            an = Analysis(_arch(), Material(mu), model=kind)  # type: ignore[arg-type]
            r0 = out.add(an.solve(0.0, 0.0, _right([MM, 0, 0, 0, 0, 0])))
            out.add(an.solve(0.0))
            if r0.status != expected_at_zero:
                out.errors.append(f"{kind}: lam=0 is {r0.status}, expected {expected_at_zero}")
            if expected_at_zero == "optimal":
                lm = _lambda_max(Material(mu), kind)
                below = out.add(an.solve(lm * (1 - 1e-6), 0.0, _right([MM, 0, 0, 0, 0, 0])))
                above = out.add(an.solve(lm * (1 + 1e-6), 0.0, _right([MM, 0, 0, 0, 0, 0])))
                if (below.status, above.status) != ("optimal", "infeasible"):
                    out.errors.append(f"{kind}: around lambda_max: {below.status}, {above.status}")
        return out

    return run


def _many_voussoirs() -> Outcome:
    """1,000 voussoirs (nearly parallel joints): answers near the limit and planar = spatial."""
    out = Outcome()
    n = 1000
    lm = {}
    for material, kind in ((HEYMAN, "planar"), (FRICTION, "spatial")):
        an = Analysis(_arch(n), material, model=kind)  # type: ignore[arg-type]
        lm[kind] = an.limit(0.0).lambda_max
        out.add(an.solve(lm[kind] * (1 - 1e-6), 0.0, _right([MM, 0, 0, 0, 0, 0])))
        above = an.solve(lm[kind] * (1 + 1e-6), 0.0, _right([MM, 0, 0, 0, 0, 0]))
        if above.status != "infeasible":
            out.errors.append(f"{kind}: (1 + 1e-6) lambda_max is {above.status}")
    out.expect_close("lambda_max planar vs spatial", lm["spatial"], lm["planar"], 1e-7)
    return out


SLIVER = 1e-6  # area of the sliver interface relative to the base interface


def sliver_assembly(ratio: float = SLIVER) -> Assembly:
    """A 1 m cube on a base slab, pushed (+x) against a wall through a sliver interface.

    The wall is a support plate touching the cube's +x face along a strip ``ratio`` m high
    (``ratio`` times the base's area). Under a lateral load along +x the wall holds the cube
    against sliding; it rocks about its base edge at x = 1 for lam = 1 (the wall's thrust,
    at the base, adds no restoring moment).
    """
    base = Block("base", box([-0.5, 0.0, -0.5], [1.5, 1.0, 0.0]), 20.0, support=True)
    cube = Block("cube", box([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]), 20.0)
    wall = Block("wall", box([1.0, 0.0, 0.0], [1.5, 1.0, ratio]), 20.0, support=True)
    bottom = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    strip = np.array([[1, 0, 0], [1, 1, 0], [1, 1, ratio], [1, 0, ratio]], float)
    return Assembly((base, cube, wall), (Interface(0, 1, bottom, [0, 0, 1]), Interface(1, 2, strip, [1, 0, 0])))


def _sliver() -> Outcome:
    """Sliver interface (1e-6 of the base's area): rigid and compliant, up to the rocking limit."""
    out = Outcome()
    asm = sliver_assembly()
    for material in (Material(0.3), Material(0.3, 1e6), Material(0.3, 1e12)):
        an = Analysis(asm, material, model="spatial")
        lm = an.limit(0.0).lambda_max
        if not 1.0 <= lm <= 1.0 + 10 * SLIVER:  # the wall's thrust has a lever arm <= SLIVER
            out.errors.append(f"{material}: rocking lambda_max {lm!r}, expected 1 + O({SLIVER:g})")
        for lam in (0.0, 0.5, lm * (1 - 1e-6)):
            out.add(an.solve(lam, 0.0, {"wall": [MM, 0, 0, 0, 0, 0]} if material.rigid else None))
        r = out.add(an.solve(0.5))
        if r.ok:  # the wall holds what the base's friction does not
            out.expect_close("horizontal equilibrium", -float(r.support_wrenches[:, 0].sum()), 0.5 * asm.total_weight, 1e-7)
        above = an.solve(lm * (1 + 1e-6))
        if above.status != "infeasible":
            out.errors.append(f"{material}: (1 + 1e-6) lambda_max is {above.status}")
    return out


def degenerate_vertices_arch() -> Assembly:
    """The reference arch with a repeated vertex and a collinear (mid-edge) vertex on two joints."""
    asm = _arch()
    itfs = list(asm.interfaces)
    k1, k2 = 3, 7
    p = itfs[k1].points
    itfs[k1] = Interface(itfs[k1].a, itfs[k1].b, np.vstack([p[:2], p[1:2], p[2:]]), itfs[k1].normal)
    p = itfs[k2].points
    mid = 0.5 * (p[0] + p[1])
    itfs[k2] = Interface(itfs[k2].a, itfs[k2].b, np.vstack([p[:1], mid[None], p[1:]]), itfs[k2].normal)
    return asm.with_interfaces(itfs)


def _degenerate_vertices() -> Outcome:
    """Duplicate and collinear contact vertices: same lambda_max and thrust as the clean arch."""
    out = Outcome()
    asm = degenerate_vertices_arch()
    for material in (HEYMAN, FRICTION, Material(0.8, 1e8)):
        an, ref = Analysis(asm, material, model="spatial"), Analysis(_arch(), material, model="spatial")
        if material.rigid:
            out.expect_close(f"{material.friction}: lambda_max", an.limit(0.0).lambda_max, ref.limit(0.0).lambda_max, 1e-7)
        for lam, u in ((0.0, [MM, 0, 0, 0, 0, 0]), (0.2, [0, 0, -MM, 0, 0, 0]), (0.1, [0, MM, 0, 0, 0, 0])):
            if material.heyman and u[1]:
                continue
            r = out.add(an.solve(lam, 0.0, _right(u)))
            if material.rigid and r.ok:
                out.expect_close(f"{material.friction}: H/W at lam={lam}", _thrust(r), _thrust(ref.solve(lam, 0.0, _right(u))), 1e-6)
    return out


def _uniqueness() -> Outcome:
    """Rigid, no settlement: an admissible state flagged non-unique; with compliance, unique."""
    out = Outcome()
    for kind in ("planar", "spatial"):
        for material, unique in ((FRICTION, False), (Material(0.8, 1e12), True), (Material(None, 1e12), True)):
            r = out.add(Analysis(_arch(), material, model=kind).solve(0.1))  # type: ignore[arg-type]
            if r.unique is not unique:
                out.errors.append(f"{kind} {material}: unique is {r.unique}, expected {unique}")
    return out


TRANSVERSAL = {"uy": [0, MM, 0, 0, 0, 0], "rx": [0, 0, 0, MM, 0, 0], "rz": [0, 0, 0, 0, 0, MM]}


def _transversal(material: Material) -> Callable[[], Outcome]:
    """Transversal motions of the right support (translation uy, rotations rx and rz)."""

    def run() -> Outcome:
        out = Outcome()
        an = Analysis(_arch(), material)
        for u in TRANSVERSAL.values():
            for lam in (0.0, 0.1):
                out.add(an.solve(lam, 0.0, _right(u)))
        return out

    return run


CASES: tuple[HardCase, ...] = (
    HardCase("lam = (1 - 1e-6) lambda_max", _near_limit(1 - 1e-6), ("optimal",)),
    HardCase("lam = (1 - 1e-9) lambda_max", _near_limit(1 - 1e-9), ("optimal",)),
    HardCase("lam = lambda_max", _near_limit(1.0), ("optimal", "infeasible")),
    HardCase("lam = (1 + 1e-6) lambda_max", _near_limit(1 + 1e-6), ("infeasible",)),
    HardCase("thickness (1 + 1e-4) t_min", _thickness(1 + 1e-4), ("optimal",)),
    HardCase("thickness (1 - 1e-4) t_min", _thickness(1 - 1e-4), ("infeasible",)),
    HardCase("units mm/N", _units(1e3, 1e3), ("optimal",)),
    HardCase("units km/MN", _units(1e-3, 1e-3), ("optimal",)),
    HardCase("units mm/N, compliant", _units(1e3, 1e3, 1e6), ("optimal",)),
    HardCase("geometry x 1e-3", _units(1e-3, 1e-9), ("optimal",)),
    HardCase("geometry x 1e3", _units(1e3, 1e9), ("optimal",)),
    HardCase("settlement 1e-12..0.1 m, rigid", _rigid_settlements, ("optimal",)),
    HardCase("settlement 1e-12..0.1 m, compliant", _compliant_settlements, ("optimal",)),
    HardCase("stiffness 1e-3..1e12", _stiffness_range, ("optimal",)),
    HardCase("one joint 1e6, 1e9 x stiffer", _stiff_interface, ("optimal",)),
    HardCase("friction 1e-4", _friction(1e-4, "infeasible"), ("infeasible",)),
    HardCase("friction 0", _friction(0.0, "infeasible"), ("infeasible",)),
    HardCase("friction 1e4", _friction(1e4, "optimal"), ("optimal", "infeasible")),
    HardCase("friction none (Heyman)", _friction(None, "optimal"), ("optimal", "infeasible")),
    HardCase("1000 voussoirs", _many_voussoirs, ("optimal",)),
    HardCase("sliver interface 1e-6", _sliver, ("optimal",)),
    HardCase("duplicate/collinear vertices", _degenerate_vertices, ("optimal",)),
    HardCase("rigid, no settlement: non-unique", _uniqueness, ("optimal",)),
    HardCase("transversal motion, Heyman", _transversal(HEYMAN), ("unbounded",)),
    HardCase("transversal motion, mu 0.8", _transversal(FRICTION), ("optimal",)),
)
