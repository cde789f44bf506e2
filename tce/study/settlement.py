"""The finite-settlement variables of a scenario's dataset (``[settlement_path]``, ``docs/results.md``).

:func:`settlement_vars` runs :func:`tce.analysis.settlement_path.settlement_path` on a
scenario's settlement vectors and returns its variables on a ``settlement_step`` dimension,
whose ``settlement_magnitude`` coordinate holds the magnitudes (multiples of the scenario's
settlement vectors), merged into the scenario's load-path dataset by the runner.

Live loads after a finite settlement (``[settlement_path] live_at``): the path carries the
self-weight and the scenario's fixed loads (a fill's weight, fixed point and distributed
loads, fixed vehicles), each force carried by its block; at each requested magnitude the
live loads' ``lambda_max`` is computed on the deformed structure (:func:`deformed_assembly`)
with the fixed loads where the path has carried them: the critical position of the moving
loads searched again (:func:`tce.analysis.critical.critical_position`), or the direct limit
at their declared position. A small-displacement ``lambda_max`` does not depend on a support
motion (the static theorem); this one does, through the geometry.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import xarray as xr

from ..analysis.critical import critical_position
from ..analysis.settlement_path import CONTACT_GAP, SettlementPathResult, settlement_path
from ..core.analysis import Analysis
from ..core.loads import AppliedLoads, LoadPattern, PointLoad, resolve
from ..core.material import Material
from ..structures.assembly import Assembly, Interface
from .schema import Scenario

__all__ = ["HINGE_WIDTH", "NO_MOTION", "deformed_assembly", "fixed_part", "live_after_settlement", "settlement_vars"]

#: outcome of a scenario that moves no support (nothing to follow)
NO_MOTION = "no_motion"

#: a partly open interface keeps its closed contact points; its open ones are moved to this
#: fraction of their distance from the nearest closed point (its contact stays a polygon,
#: a strip this thin along the hinge: compression only at the hinge, to this fraction)
HINGE_WIDTH = 1e-6


def _sequence(r: SettlementPathResult, assembly: Assembly) -> str:
    names = assembly.names
    return "; ".join(
        f"s={s:.6g}: {names[assembly.interfaces[k].a]}|{names[assembly.interfaces[k].b]} {event}"
        for s, k, event in r.hinge_sequence
    )


def fixed_part(pattern: LoadPattern) -> LoadPattern:
    """``pattern`` without its live loads (the lateral pattern, scaled point and distributed
    loads, scaled vehicles): what a settlement path carries."""
    return replace(
        pattern,
        lateral=True,  # the path's loads exclude the lateral pattern; a pattern needs something to multiply
        point=tuple(p for p in pattern.point if not p.scaled),
        distributed=tuple(d for d in pattern.distributed if not d.scaled),
        vehicle=tuple(v for v in pattern.vehicle if not v.scaled),
    )


def deformed_assembly(
    assembly: Assembly, path: SettlementPathResult, index: int, gap: float
) -> tuple[Assembly, np.ndarray, float]:
    """``assembly`` at step ``index`` of ``path``, with the contacts that are closed there.

    Every block is moved rigidly to its placement. Each interface keeps the contact points
    whose two copies (one carried by each block) are within ``gap`` (m) along block A's turned
    normal, at block A's copy: the polygon stays in the plane of A's face (points off a
    contact plane would let unlimited tangential forces form a couple, a spurious strength);
    an interface with none is left out, and one with some open keeps its open points at
    :data:`HINGE_WIDTH` of their distance from the nearest closed one.

    Returns
    -------
    Assembly
        The deformed assembly (same blocks, names and supports).
    (n_blocks, 4, 4) ndarray
        The placement of each block: homogeneous matrices taking a reference point to its
        place (for carrying loads).
    float
        The widest opening of a contact point kept (m, >= 0): the motion that counting it
        as a contact neglects.
    """
    move = path.moves(assembly, index)
    rot = move[:, :3, :3]
    interfaces, widest = [], 0.0
    for itf in assembly.interfaces:
        pa = itf.points @ rot[itf.a].T + move[itf.a, :3, 3]
        pb = itf.points @ rot[itf.b].T + move[itf.b, :3, 3]
        normal = rot[itf.a] @ itf.normal
        opening = (pb - pa) @ normal
        closed = opening <= gap
        if not closed.any():
            continue
        widest = max(widest, float(opening[closed].max()))
        near = pa[closed][np.argmin(np.linalg.norm(pa[:, None] - pa[closed][None], axis=2), axis=1)]
        points = np.where(closed[:, None], pa, near + HINGE_WIDTH * (pa - near))
        interfaces.append(Interface(itf.a, itf.b, points, normal, itf.stiffness, itf.kind))
    blocks = path.deformed(assembly, index).blocks
    return Assembly(blocks, tuple(interfaces), dict(assembly.meta)), move, widest


def _carried(dead: AppliedLoads, move: np.ndarray, names: tuple[str, ...]) -> tuple[PointLoad, ...]:
    """The fixed forces of ``dead`` as fixed point loads at their carried points."""
    at = np.einsum("nij,nj->ni", move[dead.blocks, :3, :3], dead.points) + move[dead.blocks, :3, 3]
    return tuple(
        PointLoad(tuple(map(float, f)), block=names[b], at=tuple(map(float, p)), scaled=False)
        for b, p, f in zip(dead.blocks, at, dead.forces) if np.any(f)
    )


def live_after_settlement(
    sc: Scenario, assembly: Assembly, material: Material, path: SettlementPathResult, dead: AppliedLoads
) -> dict[str, np.ndarray]:
    """``lambda_max`` of the scenario's live loads on the deformed structure at each magnitude
    of ``[settlement_path] live_at`` (module docstring): per magnitude the path's step used
    (the last standing one at or below it), ``lambda_max``, the critical position (NaN
    without a search) and a status (``optimal``, ``unbounded``, ``infeasible``,
    ``numerical``, or ``not_standing`` beyond the path's last standing magnitude) and the
    widest opening counted as a contact (:func:`deformed_assembly`, m)."""
    opts = sc.settlement_path or {}
    wanted = np.asarray(opts["live_at"], dtype=float)
    pattern = sc.loads_pattern
    fill = None if pattern.fill is None else replace(pattern.fill, weight=False, k0=0.0)  # carried as point loads
    gap = opts.get("contact_gap")
    gap = CONTACT_GAP * assembly.size if gap is None else gap
    out = {k: np.full(len(wanted), np.nan) for k in ("at", "lambda", "x", "gap")}
    out["status"] = np.full(len(wanted), "not_standing", dtype=object)
    tol = 1e-9 * max(1.0, float(np.abs(path.magnitudes).max(initial=0.0)))
    for i, m in enumerate(wanted):
        below = np.flatnonzero(path.magnitudes <= m + tol)
        if not len(below) or m > path.magnitudes[-1] + tol:  # nothing stands there, or not known to
            continue
        k = int(below[-1])
        deformed, move, out["gap"][i] = deformed_assembly(assembly, path, k, gap)
        live = replace(pattern, fill=fill, point=pattern.point + _carried(dead, move, assembly.names))
        analysis = Analysis(deformed, material)
        if sc.loads.get("critical_position"):
            res = critical_position(analysis, live)
            lam, x = res.lambda_max, res.critical_x
        else:
            res = analysis.limit(loads=live)
            lam, x = res.lambda_max, math.nan
        out["at"][i], out["lambda"][i], out["x"][i] = path.magnitudes[k], lam, x
        out["status"][i] = res.status
    return out


def settlement_vars(sc: Scenario, assembly: Assembly, material: Material) -> xr.Dataset:
    """The ``settlement_*`` variables of scenario ``sc`` (its ``settlement_path`` settings)."""
    opts = sc.settlement_path or {}
    nb, ni, ns = len(assembly.blocks), len(assembly.interfaces), len(assembly.support_names)
    live_at = list(opts.get("live_at") or [])
    live: dict[str, np.ndarray] | None = None
    if not any(any(u != 0 for u in v) for v in sc.settlements.values()):
        # nothing to follow: one step of NaN, so that the scenario merges with the others
        scalars = dict(capacity=np.nan, upper=np.nan, n_solves=0, outcome=NO_MOTION,
                       message="the scenario moves no support", hinge_sequence="")
        per_step = dict(magnitudes=np.full(1, np.nan), reaction=np.full((1, ns, 6), np.nan),
                        lambda_max=np.full(1, np.nan), hinge=np.full((1, ni), np.nan),
                        open=np.full((1, ni), np.nan), displacement=np.full((1, nb, 6), np.nan),
                        hinge_point=np.full((1, ni, 3), np.nan))
    else:
        pattern = sc.loads_pattern
        dead = None if pattern.default else resolve(fixed_part(pattern), assembly)
        r = settlement_path(
            assembly,
            sc.settlements,
            material,
            increment=opts["increment"],
            s_max=opts["s_max"],
            atol=opts.get("tolerance"),
            lam=bool(opts.get("lam")),
            alpha=sc.alpha,
            contact_gap=opts.get("contact_gap"),
            dead=dead if dead is not None and len(dead.blocks) else None,
        )
        rotating = np.zeros((len(r.magnitudes), ni))  # float: padded with NaN when merged
        for i, h in enumerate(r.hinges):
            rotating[i, h] = 1
        scalars = dict(capacity=r.capacity, upper=r.upper, n_solves=r.n_solves, outcome=r.status,
                       message=r.message, hinge_sequence=_sequence(r, assembly))
        per_step = dict(magnitudes=r.magnitudes, reaction=r.wrenches(), lambda_max=r.lambda_max,
                        hinge=rotating, open=r.open_ends.sum(axis=2).astype(float),
                        displacement=r.displacements(), hinge_point=r.hinge_points)
        if live_at and dead is not None:
            live = live_after_settlement(sc, assembly, material, r, dead)
    dims = ("scenario", "settlement_step")
    data = {
        f"settlement_{k}": (("scenario",), np.asarray([v], dtype=object if isinstance(v, str) else None))
        for k, v in scalars.items()
    }
    data |= {
        "settlement_reaction": (dims + ("support", "component"), per_step["reaction"][None]),
        "settlement_lambda_max": (dims, per_step["lambda_max"][None]),
        "settlement_hinge": (dims + ("interface",), per_step["hinge"][None]),
        "settlement_open": (dims + ("interface",), per_step["open"][None]),
        "settlement_displacement": (dims + ("block", "dof"), per_step["displacement"][None]),
        "settlement_hinge_point": (dims + ("interface", "xyz"), per_step["hinge_point"][None]),
    }
    mags = per_step["magnitudes"]
    coords = {"settlement_step": np.arange(len(mags)), "settlement_magnitude": (dims, mags[None])}
    if live_at:
        n = len(live_at)
        if live is None:  # no motion: the small-displacement answer is the load path's
            live = {k: np.full(n, np.nan) for k in ("at", "lambda", "x", "gap")}
            live["status"] = np.full(n, NO_MOTION, dtype=object)
        ldims = ("scenario", "live_at")
        data |= {
            "settlement_live_step": (ldims, live["at"][None]),
            "settlement_live_lambda": (ldims, live["lambda"][None]),
            "settlement_live_x": (ldims, live["x"][None]),
            "settlement_live_status": (ldims, live["status"][None]),
            "settlement_live_gap": (ldims, live["gap"][None]),
        }
        coords["live_at"] = np.asarray(live_at, dtype=float)
    return xr.Dataset(data, coords=coords)
