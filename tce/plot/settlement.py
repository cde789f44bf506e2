"""Figures of the finite-settlement path (``[settlement_path]``, ``docs/settlements.md``).

:func:`settlement_curves`
    Thrust, lambda_max of the deformed structure and the live loads' adequacy after the
    settlement against the settlement magnitude, one colour per scenario; the capacity a dotted vertical line, each snap (a hinge moving to a
    neighbouring joint) a cross. The settlement analogue of the paper's Fig. 8.
:func:`settlement_shapes`
    The deformed structure at 0, half the capacity and the capacity, true scale.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from scipy.spatial.transform import Rotation

from ..core.model import find_plane
from .data import assembly
from .figures import COLOURS

__all__ = ["MAX_SCENARIOS", "settled_scenarios", "settlement_curves", "settlement_shapes"]

#: most scenarios one settlement figure draws (the first ones of the study)
MAX_SCENARIOS = 6


def settled_scenarios(ds: xr.Dataset) -> list[str]:
    """The scenarios with a settlement path (not ``no_motion``), at most :data:`MAX_SCENARIOS`."""
    if "settlement_outcome" not in ds:
        return []
    names = [str(s) for s, o in zip(ds["scenario"].values, ds["settlement_outcome"].values) if str(o) != "no_motion"]
    return names[:MAX_SCENARIOS]


def _path(ds: xr.Dataset, name: str) -> tuple[np.ndarray, int]:
    """The magnitudes of a scenario's standing configurations and their count."""
    mags = np.asarray(ds["settlement_magnitude"].sel(scenario=name).values, dtype=float)
    n = int(np.isfinite(mags).sum())
    return mags[:n], n


def _snaps(mags: np.ndarray) -> np.ndarray:
    """Magnitudes recorded twice (before and after a snap)."""
    return mags[1:][np.diff(mags) == 0]


def _motion(ds: xr.Dataset, name: str) -> np.ndarray:
    """Unit translations ``(n_supports, 3)`` of the supports per unit magnitude (zero for
    supports that do not translate), read from the support blocks' displacements."""
    mags, n = _path(ds, name)
    disp = np.asarray(ds["settlement_displacement"].sel(scenario=name).values, dtype=float)[n - 1]
    sup = np.flatnonzero(np.asarray(ds["block_support"].values, dtype=bool))
    u = disp[sup, :3] / mags[-1] if mags[-1] > 0 else np.zeros((len(sup), 3))
    norm = np.linalg.norm(u, axis=1, keepdims=True)
    return np.divide(u, norm, out=np.zeros_like(u), where=norm > 0)


def _thrust_against_motion(ds: xr.Dataset, name: str, reac: np.ndarray) -> np.ndarray:
    """``-sum_s R_s . u_s / n`` over the ``n`` supports that translate (``u_s`` the unit
    direction of support ``s``'s translation, ``R_s`` its force on the structure, kN): the
    mean force each moving support exerts against its own motion (a dome's mean radial
    thrust). Unlike a single support's reaction, statically indeterminate in a rigid 3D
    structure, it is unique when the supports move by equal amounts: it is then the work the
    TCE minimises per unit motion."""
    u = _motion(ds, name)
    moving = max(int((np.linalg.norm(u, axis=1) > 0).sum()), 1)
    return -np.einsum("ksj,sj->k", reac[:, :, :3], u) / moving


def settlement_curves(ds: xr.Dataset, names: Sequence[str] | None = None) -> Figure:
    """Thrust and lambda_max of the deformed structure against the settlement magnitude.

    Parameters
    ----------
    ds : xarray.Dataset
    names : list of str, optional
        Scenarios drawn (default :func:`settled_scenarios`).

    Returns
    -------
    Figure
        Left: for a planar structure ``|H|`` of each support (kN; gid
        ``"thrust:<scenario>:<support>"``); for a spatial one the thrust against the motion
        (:func:`_thrust_against_motion`; gid ``"thrust:<scenario>"``); then, when computed:
        lambda_max of the lateral pattern (gid ``"lambda:<scenario>"``); with ``live_at``, the
        live loads' lambda_max on the deformed structure (:func:`_live`).
    """
    names = list(names or settled_scenarios(ds))
    asm = assembly(ds)
    plane = find_plane(asm)
    e = plane.e if plane is not None else np.array([1.0, 0.0, 0.0])
    lam = "settlement_lambda_max" in ds and bool(np.isfinite(ds["settlement_lambda_max"].values).any())
    live = "settlement_live_lambda" in ds
    n_axes = 1 + lam + live
    fig = Figure(figsize=(3.0 + 4.0 * n_axes, 5.0))
    width = 0.8 / n_axes - 0.06 * (n_axes > 1)
    axes = [fig.add_axes((0.08 + k / n_axes * 0.92, 0.26, width, 0.64)) for k in range(n_axes)]
    handles = []
    supports = [str(s) for s in ds["support"].values]
    for i, name in enumerate(names):
        colour = COLOURS[i % len(COLOURS)]
        mags, n = _path(ds, name)
        reac = np.asarray(ds["settlement_reaction"].sel(scenario=name).values, dtype=float)[:n]
        if plane is None:
            (line,) = axes[0].plot(mags, _thrust_against_motion(ds, name, reac), color=colour, lw=1.6)
            line.set_gid(f"thrust:{name}")
        for k, sup in enumerate(supports if plane is not None else ()):
            h = reac[:, k, :3] @ e
            (line,) = axes[0].plot(mags, np.abs(h), color=colour, ls=("-", "--", ":", "-.")[k % 4], lw=1.6)
            line.set_gid(f"thrust:{name}:{sup}")
        cap = float(ds["settlement_capacity"].sel(scenario=name))
        for ax in axes:
            if np.isfinite(cap):
                ax.axvline(cap, color=colour, ls=":", lw=1.0)
            for s in _snaps(mags):
                ax.axvline(s, color=colour, ls="-", lw=0.6, alpha=0.5)
        if lam:
            vals = np.asarray(ds["settlement_lambda_max"].sel(scenario=name).values, dtype=float)[:n]
            (line,) = axes[1].plot(mags, vals, color=colour, lw=1.6)
            line.set_gid(f"lambda:{name}")
            _gaps(axes[1], mags, vals, name, colour, i)
        if live:
            _live(axes[-1], ds, name, colour)
        outcome = str(ds["settlement_outcome"].sel(scenario=name).values)
        label = f"{name}: capacity {cap:.4g} ({outcome})" if np.isfinite(cap) else f"{name}: {outcome}"
        handles.append(Line2D([], [], color=colour, lw=1.6, label=label))
    if plane is not None:
        handles += [Line2D([], [], color="0.3", ls=("-", "--", ":", "-.")[k % 4], label=f"support {s}") for k, s in enumerate(supports)]
    handles.append(Line2D([], [], color="0.3", ls=":", lw=1.0, label="capacity"))
    handles.append(Line2D([], [], color="0.3", lw=0.6, alpha=0.5, label="snap (a hinge moves)"))
    axes[0].set_xlabel("settlement magnitude (multiples of the settlement vector)")
    axes[0].set_ylabel("|H|: horizontal reaction in the plane (kN)" if plane is not None
                       else "thrust against the motion, mean per moving support (kN)")
    axes[0].set_title("Thrust against support motion")
    if lam:
        axes[1].set_xlabel("settlement magnitude (multiples of the settlement vector)")
        axes[1].set_ylabel("λmax of the deformed structure")
        axes[1].set_title("Lateral capacity left")
    if live:
        handles.append(Line2D([], [], color="0.3", ls="--", lw=1.0, label="small displacements (any magnitude)"))
        axes[-1].set_xlabel("settlement magnitude (multiples of the settlement vector)")
        axes[-1].set_ylabel("λmax of the live loads on the deformed structure")
        axes[-1].set_title("Adequacy of the live loads after the settlement")
    for ax in axes:
        ax.grid(True, lw=0.4, alpha=0.5)
        ax.set_xlim(left=0.0)
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=8, frameon=False)
    return fig


def _gaps(ax, mags: np.ndarray, vals: np.ndarray, name: str, colour: str, row: int) -> None:
    """Where a lateral capacity is missing between computed ones: its isolated values drawn as
    dots (a line needs two neighbours) and the missing magnitudes counted below the axis (the
    settlement path's message, ``tce show``, says why: a value withheld or not solved)."""
    ok = np.isfinite(vals)
    if not ok.any():
        return
    inside = np.arange(np.flatnonzero(ok)[0], np.flatnonzero(ok)[-1] + 1)
    missing = inside[~ok[inside]]
    alone = ok & ~np.r_[False, ok[:-1]] & ~np.r_[ok[1:], False]
    if alone.any():
        (dots,) = ax.plot(mags[alone], vals[alone], "o", color=colour, ms=3)
        dots.set_gid(f"lambda_alone:{name}")
    if missing.size:
        ax.text(0.0, -0.2 - 0.08 * row, f"{name}: no lateral capacity at {missing.size} magnitude(s), "
                f"{mags[missing[0]]:.4g} to {mags[missing[-1]]:.4g}\n(withheld or not solved: tce show says why)",
                transform=ax.transAxes, fontsize=7, va="top")


def _live(ax, ds: xr.Dataset, name: str, colour: str) -> None:
    """The live loads' lambda_max on the deformed structure at each ``live_at`` magnitude
    (dots joined, gid ``"live:<scenario>"``; magnitudes not solved optimal left out and named
    below the axis), and the small-displacement lambda_max of the scenario's load path,
    which no magnitude changes (dashed, gid ``"live0:<scenario>"``)."""
    at = np.asarray(ds["settlement_live_step"].sel(scenario=name).values, dtype=float)
    vals = np.asarray(ds["settlement_live_lambda"].sel(scenario=name).values, dtype=float)
    status = [str(v) for v in ds["settlement_live_status"].sel(scenario=name).values]
    ok = np.array([v == "optimal" for v in status]) & np.isfinite(at)
    (line,) = ax.plot(at[ok], vals[ok], "o-", color=colour, lw=1.6, ms=4)
    line.set_gid(f"live:{name}")
    small = float(ds["lambda_direct"].sel(scenario=name)) if "lambda_direct" in ds else float("nan")
    if np.isfinite(small):
        ax.axhline(small, color=colour, ls="--", lw=1.0).set_gid(f"live0:{name}")
    others = [f"{a:g}: {s}" for a, s, good in zip(ds["live_at"].values, status, ok) if not good]
    if others:
        ax.text(0.0, -0.2, f"{name}, not drawn: " + "; ".join(others), transform=ax.transAxes, fontsize=7, va="top")


def _outline(points: np.ndarray) -> np.ndarray:
    """Convex outline of 2D points (monotone chain), counter-clockwise."""
    pts = sorted(map(tuple, np.round(points, 12)))
    if len(pts) < 3:
        return np.asarray(pts)

    def half(seq: list) -> list:
        out: list = []
        for p in seq:
            while len(out) >= 2 and np.cross(np.subtract(out[-1], out[-2]), np.subtract(p, out[-2])) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(pts[::-1])
    return np.asarray(lower[:-1] + upper[:-1])


def _section(asm) -> tuple[np.ndarray, np.ndarray]:
    """The vertical section drawn for a spatial structure: its horizontal direction ``e``
    (from the plan centre of the supports to the first support's centroid) and the blocks
    drawn (those whose centroid lies, seen in plan from that centre, within 30 degrees of
    ``+e`` or ``-e``)."""
    c = asm.centroids
    sup = list(asm.support_indices)
    o = c[sup, :2].mean(axis=0)
    d = c[sup[0], :2] - o
    if np.linalg.norm(d) == 0:
        d = np.array([1.0, 0.0])
    d = d / np.linalg.norm(d)
    rel = c[:, :2] - o
    r = np.linalg.norm(rel, axis=1)
    cos = np.abs(rel @ d) / np.where(r > 0, r, 1.0)
    return np.array([d[0], d[1], 0.0]), (cos >= np.cos(np.radians(30.0))) | (r <= 1e-9 * asm.size)


def settlement_shapes(ds: xr.Dataset, names: Sequence[str] | None = None) -> Figure:
    """The deformed structure at magnitudes 0, capacity / 2 and capacity (true scale).

    One panel per scenario, in elevation: blocks as the outline of their vertices in the
    plane of the structure (prisms of convex sections), hinges as dots (gid
    ``"hinge:<scenario>:<k>"``). A spatial structure is drawn in the vertical section
    through its first support (:func:`_section`; for a dome, two opposite lunes).
    """
    names = list(names or settled_scenarios(ds))
    asm = assembly(ds)
    plane = find_plane(asm)
    e = plane.e if plane is not None else np.array([1.0, 0.0, 0.0])
    drawn = np.ones(len(asm.blocks), dtype=bool)
    if plane is None:
        e, drawn = _section(asm)
    fig = Figure(figsize=(5.0 * len(names), 4.6))
    shades = ("0.85", "#9ecae1", "#fc9272")
    for i, name in enumerate(names):
        ax = fig.add_axes((0.02 + i / len(names), 0.18, 0.96 / len(names), 0.62))
        mags, n = _path(ds, name)
        cap = float(ds["settlement_capacity"].sel(scenario=name))
        last = cap if np.isfinite(cap) else mags[-1]
        chosen = sorted({0, int(np.argmin(np.abs(mags - last / 2))), n - 1})
        disp = np.asarray(ds["settlement_displacement"].sel(scenario=name).values, dtype=float)
        hp = np.asarray(ds["settlement_hinge_point"].sel(scenario=name).values, dtype=float)
        for j, k in enumerate(chosen):
            shade = shades[min(j, 2)] if len(chosen) == 3 else shades[2 * (j > 0)]
            for b, blk in enumerate(asm.blocks):
                if not drawn[b]:
                    continue
                u, r = disp[k, b, :3], disp[k, b, 3:]
                c = blk.shape.centroid
                p = c + u + Rotation.from_rotvec(r).apply(blk.shape.vertices - c)
                xy = _outline(np.column_stack([p @ e, p[:, 2]]))
                ax.add_patch(Polygon(xy, closed=True, fc=shade, ec="0.25", lw=0.4, alpha=0.9 if j == len(chosen) - 1 else 0.6))
            pts = hp[k][np.isfinite(hp[k, :, 0]) & (drawn[asm.interface_table.a] | drawn[asm.interface_table.b])]
            dots = ax.plot(pts @ e, pts[:, 2], "o", ms=5, color="#cb181d" if j == len(chosen) - 1 else "0.4")
            dots[0].set_gid(f"hinge:{name}:{k}")
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_axis_off()
        ax.set_title(f"{name}\n" + ", ".join(f"s = {mags[k]:.4g}" for k in chosen), fontsize=9)
    handles = [
        Polygon([[0, 0]], fc=shades[0], ec="0.25", label="s = 0"),
        Polygon([[0, 0]], fc=shades[1], ec="0.25", label="about half the capacity"),
        Polygon([[0, 0]], fc=shades[2], ec="0.25", label="at the capacity (last standing)"),
        Line2D([], [], marker="o", ls="", color="#cb181d", label="hinges at the capacity"),
        Line2D([], [], marker="o", ls="", color="0.4", label="hinges before"),
    ]
    fig.legend(handles=handles, loc="lower center", ncol=3 if len(names) > 1 else 2, fontsize=8, frameon=False)
    fig.suptitle("Deformed shapes along the settlement path (true scale)", fontsize=10)
    return fig
