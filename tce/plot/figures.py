"""Figures of a results dataset: what a masonry engineer reads at a glance.

Every function takes a results dataset (``docs/results.md``), never a solver object, and
returns a :class:`matplotlib.figure.Figure` built without pyplot (no display, no global
state; ``savefig`` renders with Agg). The geometry comes from ``ds.attrs["assembly"]``
(JSON of :meth:`tce.assembly.Assembly.to_dict`), so a results file copied anywhere redraws
its figures without recomputing anything.

Conventions of the pictures
---------------------------
- Units as in the dataset: m, kN, kN m; lambda is dimensionless.
- Thrust curves (the paper's Fig. 8): ``H = sqrt(Fx^2 + Fy^2)`` is the magnitude of the
  horizontal reaction a support exerts on the structure (its thrust), ``V = Fz`` the
  vertical one (positive upwards). Only ``optimal`` steps are drawn.
- Interface resultants are arrows **centred** on their pressure points (the force acts on
  block B, the block the interface normal points into), all to one scale stated in the
  legend (``1 kN = x m``). Torques about the interface normal are arcs around the pressure
  point, radius proportional to the magnitude, arrow head by the right-hand rule.
- Geometry is drawn in orthographic projection with equal scales on every axis.
- The default step of a scenario is the optimal step at ``lambda_max``, else its last
  optimal step.
- Optional variables beyond the contract: ``vertex_force`` (scenario, step, vertex, xyz;
  kN, global frame, on block B) with ``vertex_point`` (vertex, xyz; m) for
  ``assembly_view(..., vertex_forces=True)``.
"""

from __future__ import annotations

import json
import math
import re
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import Literal

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon
from matplotlib.ticker import FixedLocator, MaxNLocator
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection
from numpy.typing import NDArray
from scipy.spatial import ConvexHull

from ..structures.assembly import Assembly
from .load_arrows import draw_loads_2d, draw_loads_3d

__all__ = [
    "assembly_view",
    "default_step",
    "figure_sheet",
    "mechanism_view",
    "thrust_curves",
    "thrust_line",
    "write_figures",
]

View = Literal["axo", "elevation", "plan"]
Canvas = Figure | SubFigure

# Okabe-Ito (colour-blind safe), black first; line styles and markers keep them apart in greyscale
COLOURS = ("#000000", "#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442")
LINESTYLES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 2)), (0, (8, 2)), (0, (3, 1, 3, 4)))
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "h")
BLOCK_COLOUR = "#d8c3a0"  # sandstone
SUPPORT_COLOUR = "#7f7f7f"
FORCE_COLOUR = "#c0141e"
TORQUE_COLOUR = "#000000"
VERTEX_COLOUR = "#0072B2"
HINGE_COLOUR = "#0072B2"
ARROW_FRACTION = 0.22  # longest resultant arrow, as a fraction of the assembly size
TORQUE_FRACTION = 0.05  # largest torque arc radius, as a fraction of the assembly size
MECHANISM_FRACTION = 0.06  # largest drawn mechanism displacement, as a fraction of the size
HINGE_MARKER = dict(linestyle="none", marker="o", markersize=7, markerfacecolor="white",
                    markeredgecolor=HINGE_COLOUR, markeredgewidth=1.8, zorder=6)
TORQUE_TOL = 1e-3  # torques below TORQUE_TOL * max|R| * size are negligible


# ---------------------------------------------------------------------------- dataset access
def _assembly(ds: xr.Dataset) -> Assembly:
    """The assembly stored in ``ds.attrs["assembly"]``."""
    try:
        data = ds.attrs["assembly"]
    except KeyError:
        raise ValueError("the dataset has no 'assembly' attribute: geometry cannot be drawn") from None
    return Assembly.from_dict(json.loads(data) if isinstance(data, str) else data)


def _scenarios(ds: xr.Dataset) -> list[str]:
    """Scenario names in dataset order."""
    return [str(s) for s in ds["scenario"].values]


def _value(ds: xr.Dataset, name: str, scenario: str) -> NDArray:
    """``ds[name]`` of one scenario as an ndarray."""
    return np.asarray(ds[name].sel(scenario=scenario).values)


def _text(ds: xr.Dataset, name: str, scenario: str, default: str = "") -> str:
    """A per-scenario string variable (``default`` when absent)."""
    return str(_value(ds, name, scenario)) if name in ds else default


def _no_limit_caption(ds: xr.Dataset, scenario: str, width: int = 80) -> str:
    """Why the scenario has no finite limit (``no_limit_reason``), wrapped; "" when it has one."""
    why = _text(ds, "no_limit_reason", scenario)
    return textwrap.fill(why, width) if why else ""


def _lambda_max(ds: xr.Dataset, scenario: str) -> float:
    return float(_value(ds, "lambda_max", scenario))


def _optimal_steps(ds: xr.Dataset, scenario: str) -> NDArray[np.int64]:
    """Indices of the optimal steps of a scenario, sorted by lambda."""
    lam = _value(ds, "lam", scenario).astype(float)
    ok = np.flatnonzero((_value(ds, "status", scenario).astype(str) == "optimal") & np.isfinite(lam))
    return ok[np.argsort(lam[ok], kind="stable")]


def default_step(ds: xr.Dataset, scenario: str) -> int | None:
    """The step drawn by default: the optimal step at ``lambda_max``, else the last optimal one.

    Returns
    -------
    int or None
        Index along ``step``; None when the scenario has no optimal step.
    """
    ok = _optimal_steps(ds, scenario)
    if ok.size == 0:
        return None
    lam = _value(ds, "lam", scenario).astype(float)[ok]
    lmax = _lambda_max(ds, scenario)
    at = np.flatnonzero(np.isclose(lam, lmax, rtol=1e-12, atol=1e-12)) if math.isfinite(lmax) else []
    return int(ok[at[-1]] if len(at) else ok[-1])


def _first_and_limit(ds: xr.Dataset, scenario: str) -> list[int] | None:
    """The first optimal step (the support motion alone) and :func:`default_step` (None if neither)."""
    ok = _optimal_steps(ds, scenario)
    return sorted({int(ok[0]), default_step(ds, scenario)}) if ok.size else None


def _is_planar(ds: xr.Dataset, scenario: str) -> bool:
    """True when the scenario ran on the planar model (or, without ``model``, its loads are in plane)."""
    if "model" in ds:
        return _text(ds, "model", scenario) == "planar"
    if "alpha" in ds.coords:
        return bool(np.isclose(math.sin(math.radians(float(_value(ds, "alpha", scenario)))), 0.0))
    return False


def _mechanism(ds: xr.Dataset, scenario: str, asm: Assembly) -> NDArray[np.float64] | None:
    """Block velocities ``(n_blocks, 6)`` in assembly order; None when there is no mechanism."""
    if "mechanism" not in ds:
        return None
    m = ds["mechanism"].sel(scenario=scenario).sel(block=list(asm.names))
    v = np.asarray(m.transpose("block", "dof").values, dtype=float)
    if not np.all(np.isfinite(v)) or not np.any(v):
        return None
    return v


def _hinge_points(ds: xr.Dataset, scenario: str) -> NDArray[np.float64]:
    """Hinge trace points ``(n, 3)`` of the interfaces that hinge at the limit (may be empty)."""
    if "interface_mode" not in ds or "hinge_point" not in ds:
        return np.empty((0, 3))
    mode = _value(ds, "interface_mode", scenario).astype(str)
    hp = np.asarray(ds["hinge_point"].sel(scenario=scenario).transpose("interface", "xyz").values, float)
    return hp[(mode == "hinge") & np.all(np.isfinite(hp), axis=1)]


def _interface_normals(ds: xr.Dataset, asm: Assembly) -> NDArray[np.float64]:
    """Unit normal of every dataset interface (``"A|B"`` names looked up in the assembly)."""
    by_name = {f"{asm.names[i.a]}|{asm.names[i.b]}": i.normal for i in asm.interfaces}
    return np.array([by_name[str(k)] for k in ds["interface"].values], dtype=float).reshape(-1, 3)


def _state(ds: xr.Dataset, scenario: str, step: int) -> tuple[NDArray, NDArray, NDArray]:
    """Pressure points ``(ni, 3)``, resultants ``(ni, 3)`` and torques ``(ni,)`` of one step."""
    at = dict(scenario=scenario, step=step)
    pp = np.asarray(ds["pressure_point"].sel(at).transpose("interface", "xyz").values, dtype=float)
    res = np.asarray(ds["resultant"].sel(at).transpose("interface", "xyz").values, dtype=float)
    tq = np.asarray(ds["torque"].sel(at).values, dtype=float)
    return pp, res, tq


def _step_label(ds: xr.Dataset, scenario: str, step: int) -> str:
    lam = float(_value(ds, "lam", scenario)[step])
    lmax = _lambda_max(ds, scenario)
    return f"λ = {lam:.3f}" + (" = λmax" if math.isfinite(lmax) and np.isclose(lam, lmax) else "")


# ---------------------------------------------------------------------------- helpers
def _nice(x: float) -> float:
    """The 1-2-5 number nearest below ``x`` (> 0)."""
    e = math.floor(math.log10(x))
    f = x / 10**e
    return float((5 if f >= 5 else 2 if f >= 2 else 1) * 10**e)


def _fmt(x: float) -> str:
    return f"{x:.3g}"


def _style(i: int) -> dict:
    """Colour and line style of the ``i``-th scenario."""
    return dict(color=COLOURS[i % len(COLOURS)], linestyle=LINESTYLES[i % len(LINESTYLES)])


def _slug(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("_") or "scenario"


def _canvas(fig: Canvas | None, figsize: tuple[float, float]) -> Canvas:
    return fig if fig is not None else Figure(figsize=figsize, layout="constrained")


def _camera(asm: Assembly, view: View, motion: NDArray[np.float64] | None = None) -> tuple[float, float]:
    """(elevation, azimuth) in degrees: looking along +y for elevations, down for plans;
    axonometric views sit lower for long arches than for domes, and turn towards the
    span when the blocks move mostly across it (``motion``: displacements, (n, 3))."""
    if view == "elevation":
        return 0.0, -90.0
    if view == "plan":
        return 90.0, -90.0
    if view != "axo":
        raise ValueError(f"view must be 'axo', 'elevation' or 'plan', got {view!r}")
    ext = np.ptp(np.vstack([b.shape.vertices for b in asm.blocks]), axis=0)
    elongated = ext[0] > 2.5 * max(ext[1], 1e-12)
    if motion is not None and elongated and np.abs(motion[:, 1]).sum() > np.abs(motion[:, 0]).sum():
        return 16.0, -32.0
    return (18.0, -62.0) if elongated else (28.0, -55.0)


def _equal_3d(ax: Axes, pts: NDArray[np.float64], size: float, view: View) -> None:
    """Limits around ``pts`` and a box aspect equal to the data ranges (equal scales)."""
    lo, hi = np.nanmin(pts, axis=0), np.nanmax(pts, axis=0)
    pad = 0.03 * size
    lo, hi = lo - pad, hi + pad
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(hi - lo), zoom=1.3)
    ax.set_proj_type("ortho")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    hidden = {"elevation": 1, "plan": 2}.get(view)  # the axis pointing at the viewer
    mid, ranges = 0.5 * (lo + hi), hi - lo
    for k, axis in enumerate((ax.xaxis, ax.yaxis, ax.zaxis)):
        axis.set_pane_color((1.0, 1.0, 1.0, 0.0))
        if k == hidden or (view == "plan" and k == 0):  # seen end-on (or, in plan, on its own ticks)
            axis.set_label_text("")
        if k == hidden:  # collapses to a point: no ticks
            axis.set_major_locator(FixedLocator([]))
        elif ranges[k] < 0.3 * ranges.max():  # a short axis: one tick, or its labels run together
            axis.set_major_locator(FixedLocator([float(np.round(mid[k], 1))]))
        else:
            axis.set_major_locator(MaxNLocator(nbins=max(2, round(6 * ranges[k] / ranges.max())),
                                               steps=[1, 2, 2.5, 5, 10]))


def _block_vertices(asm: Assembly) -> list[NDArray[np.float64]]:
    return [np.asarray(b.shape.vertices, dtype=float) for b in asm.blocks]


def _draw_blocks_3d(
    ax: Axes, asm: Assembly, verts: Sequence[NDArray[np.float64]], faint: bool = False
) -> None:
    """Blocks as translucent polyhedra (supports in grey); ``faint`` for a ghost outline."""
    for support, colour, gid in ((False, BLOCK_COLOUR, "blocks"), (True, SUPPORT_COLOUR, "supports")):
        polys = [
            verts[k][list(f)] for k, b in enumerate(asm.blocks) if b.support == support for f in b.shape.faces
        ]
        if not polys:
            continue
        coll = Poly3DCollection(
            polys,
            facecolor=colour,
            alpha=0.06 if faint else (0.45 if support else 0.35),
            edgecolor="#9a9a9a" if faint else "#3c3c3c",
            linewidths=0.3 if faint else 0.5,
            linestyle="--" if faint else "-",
        )
        coll.set_gid(f"{gid}-ghost" if faint else gid)
        ax.add_collection3d(coll)


def _hull_xz(v: NDArray[np.float64]) -> NDArray[np.float64]:
    """Outline of a block projected on the x-z plane (convex hull, counter-clockwise)."""
    xz = v[:, [0, 2]]
    try:
        return xz[ConvexHull(xz).vertices]
    except Exception:  # degenerate projection (a block seen edge-on): its extreme points
        return xz[[np.argmin(xz[:, 0]), np.argmax(xz[:, 0])]]


def _draw_blocks_2d(
    ax: Axes, asm: Assembly, verts: Sequence[NDArray[np.float64]], faint: bool = False
) -> None:
    """Blocks projected on the x-z plane (supports in grey); ``faint`` for a ghost outline."""
    for k, b in enumerate(asm.blocks):
        colour = SUPPORT_COLOUR if b.support else BLOCK_COLOUR
        patch = Polygon(
            _hull_xz(verts[k]),
            closed=True,
            facecolor="none" if faint else colour,
            alpha=None if faint else (0.6 if b.support else 0.5),
            edgecolor="#9a9a9a" if faint else "#3c3c3c",
            linewidth=0.6,
            linestyle="--" if faint else "-",
            gid=("ghost:" if faint else "block:") + b.name,
        )
        ax.add_patch(patch)


def _equal_2d(ax: Axes, pts: NDArray[np.float64], size: float) -> None:
    lo, hi = np.nanmin(pts, axis=0), np.nanmax(pts, axis=0)
    pad = 0.04 * size
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.grid(True, linewidth=0.3, alpha=0.5)


def _torque_arcs(
    centres: NDArray[np.float64], normals: NDArray[np.float64], torques: NDArray[np.float64], scale: float
) -> list[NDArray[np.float64]]:
    """Polylines of 270-degree arcs around each normal (radius ``scale * |T|``), with a head."""
    segs = []
    for c, n, t in zip(centres, normals, torques):
        a = np.cross(n, [0.0, 0.0, 1.0] if abs(n[2]) < 0.9 else [1.0, 0.0, 0.0])
        a /= np.linalg.norm(a)
        b = np.cross(n, a)  # (a, b, n) right-handed: positive angle = positive torque
        r = scale * abs(t)
        phi = np.linspace(0.0, 1.5 * math.pi, 25) * math.copysign(1.0, t)
        arc = c + r * (np.outer(np.cos(phi), a) + np.outer(np.sin(phi), b))
        tip, tangent = arc[-1], arc[-1] - arc[-2]
        tangent /= np.linalg.norm(tangent)
        radial = (tip - c) / r
        head = 0.35 * r
        segs.append(arc)
        segs.append(np.array([tip - head * (tangent - 0.6 * radial), tip, tip - head * (tangent + 0.6 * radial)]))
    return segs


# ---------------------------------------------------------------------------- figures
def thrust_curves(ds: xr.Dataset, fig: Canvas | None = None) -> Canvas:
    """Horizontal and vertical support reactions against lambda (the paper's Fig. 8).

    One line per scenario and support in each panel (scenario: colour and line style;
    support: marker); a dotted vertical line at every distinct ``lambda_max``.

    Parameters
    ----------
    ds : xarray.Dataset
        Results dataset (``docs/results.md``).
    fig : Figure or SubFigure, optional
        Where to draw; a new figure by default.

    Returns
    -------
    Figure or SubFigure
        Axes 0: ``|H| = sqrt(Fx^2 + Fy^2)`` (kN); axes 1: ``V = Fz`` (kN). Lines carry the
        gid ``"reaction:<scenario>:<support>"``, lambda_max lines the gid ``"lambda_max"``.
    """
    fig = _canvas(fig, (10.0, 4.4))
    ax_h, ax_v = fig.subplots(1, 2, sharex=True)
    supports = [str(s) for s in ds["support"].values]
    scen = _scenarios(ds)
    for i, s in enumerate(scen):
        steps = _optimal_steps(ds, s)
        lam = _value(ds, "lam", s).astype(float)[steps]
        wrench = np.asarray(ds["reaction"].sel(scenario=s).transpose("step", "support", "component").values)
        for j, sup in enumerate(supports):
            f = wrench[steps, j].astype(float)
            for ax, y in ((ax_h, np.hypot(f[:, 0], f[:, 1])), (ax_v, f[:, 2])):
                ax.plot(
                    lam, y, **_style(i), marker=MARKERS[j % len(MARKERS)], markersize=4.5,
                    markerfacecolor="white" if j % 2 else _style(i)["color"],
                    markevery=(0.04 * (j % 2) + 0.013 * i, 0.08),  # coincident curves keep both markers
                    linewidth=1.4, gid=f"reaction:{s}:{sup}",
                )
    lmax = sorted({round(v, 9) for v in np.asarray(ds["lambda_max"].values, float) if math.isfinite(v)})
    for ax in (ax_h, ax_v):
        for k, v in enumerate(lmax):
            ax.axvline(v, color="#555555", linestyle=":", linewidth=1.2, gid="lambda_max")
            ax.annotate(
                f"λmax = {v:.3f}", (v, 0.5), xycoords=("data", "axes fraction"), xytext=(3, 0),
                textcoords="offset points", ha="left", va="center", rotation=90, fontsize=8, color="#333333",
            )
        ax.set_xlabel("load multiplier λ (–)")
        ax.grid(True, linewidth=0.3, alpha=0.6)
        ax.set_xlim(0.0, 1.1 * max([*lmax, ax.get_xlim()[1] / 1.1]))
    ax_h.set_ylabel("horizontal reaction |H| (kN)")
    ax_v.set_ylabel("vertical reaction V (kN)")
    ax_h.set_title("thrust H of each support")
    ax_v.set_title("vertical reaction V of each support")
    scen_handles = [Line2D([], [], **_style(i), linewidth=1.4, label=s) for i, s in enumerate(scen)]
    sup_handles = [
        Line2D([], [], color="black", linestyle="none", marker=MARKERS[j % len(MARKERS)],
               markerfacecolor="white" if j % 2 else "black", label=f"support {s}")
        for j, s in enumerate(supports)
    ]
    fig.legend(handles=scen_handles + sup_handles, loc="outside lower center",
               ncols=min(len(scen) + len(supports), 6), fontsize=8, frameon=False)
    return fig


def assembly_view(
    ds: xr.Dataset,
    scenario: str,
    step: int | None = None,
    view: View = "axo",
    vertex_forces: bool = False,
    fig: Canvas | None = None,
) -> Canvas:
    """3D view of the blocks with the interface resultants and torques of one step.

    Parameters
    ----------
    ds : xarray.Dataset
    scenario : str
    step : int, optional
        Index along ``step``; default :func:`default_step`.
    view : {"axo", "elevation", "plan"}
        Axonometric (camera set for arches or domes), elevation (looking along +y) or plan.
    vertex_forces : bool
        Also draw the force at every interface vertex (needs the optional ``vertex_force``
        and ``vertex_point`` variables), to the resultants' scale.
    fig : Figure or SubFigure, optional

    Returns
    -------
    Figure or SubFigure
        One 3D axes. Collections: ``"blocks"``, ``"supports"`` (Poly3DCollection),
        ``"resultants"`` (quiver, centred on the pressure points), ``"torques"``,
        ``"vertex_forces"``; the pressure points are the line ``"pressure_points"``.
    """
    asm = _assembly(ds)
    fig = _canvas(fig, (8.0, 6.0))
    ax = fig.add_subplot(projection="3d", computed_zorder=False)  # forces drawn over the blocks
    _draw_blocks_3d(ax, asm, _block_vertices(asm))
    pts = [np.vstack(_block_vertices(asm))]
    step = default_step(ds, scenario) if step is None else step
    handles = [Patch(facecolor=BLOCK_COLOUR, edgecolor="#3c3c3c", alpha=0.6, label="block"),
               Patch(facecolor=SUPPORT_COLOUR, edgecolor="#3c3c3c", alpha=0.6, label="support")]
    if step is None:
        ax.set_title(f"{scenario}: no admissible state ({_text(ds, 'outcome', scenario, 'no optimal step')})")
    else:
        pp, res, tq = _state(ds, scenario, step)
        ok = np.all(np.isfinite(pp), axis=1) & np.all(np.isfinite(res), axis=1)
        fmax = float(np.linalg.norm(res[ok], axis=1).max(initial=0.0))
        scale = _nice(ARROW_FRACTION * asm.size / fmax) if fmax > 0 else 0.0
        if ok.any():
            vec = res[ok] * scale
            ax.quiver(*pp[ok].T, *vec.T, pivot="middle", color=FORCE_COLOUR, linewidth=1.6,
                      arrow_length_ratio=0.25, zorder=4, gid="resultants")
            ax.plot(*pp[ok].T, linestyle="none", marker="o", markersize=2.5, color=FORCE_COLOUR,
                    zorder=5, gid="pressure_points")
            pts += [pp[ok] + 0.5 * vec, pp[ok] - 0.5 * vec]
            handles.append(Line2D([], [], color=FORCE_COLOUR, linewidth=1.6, marker=">", markersize=5,
                                  label=f"interface resultant at pressure point\n(arrow: 1 kN = {_fmt(scale)} m)"))
        load_handles, tails = draw_loads_3d(ax, ds, scenario, float(_value(ds, "lam", scenario)[step]), scale)
        handles, pts = handles + load_handles, pts + [tails]
        sig = ok & np.isfinite(tq) & (np.abs(np.nan_to_num(tq)) > TORQUE_TOL * fmax * asm.size)
        if sig.any():
            tmax = float(np.abs(tq[sig]).max())
            tscale = _nice(TORQUE_FRACTION * asm.size / tmax)
            arcs = Line3DCollection(_torque_arcs(pp[sig], _interface_normals(ds, asm)[sig], tq[sig], tscale),
                                    colors=TORQUE_COLOUR, linewidths=1.2, zorder=4)
            arcs.set_gid("torques")
            ax.add_collection3d(arcs)
            handles.append(Line2D([], [], color=TORQUE_COLOUR, linewidth=1.2,
                                  label=f"torque about the normal\n(arc radius: 1 kN m = {_fmt(tscale)} m)"))
        if vertex_forces:
            if "vertex_force" not in ds or "vertex_point" not in ds:
                raise ValueError("vertex_forces=True needs the variables 'vertex_force' and 'vertex_point'")
            vf = np.asarray(ds["vertex_force"].sel(scenario=scenario, step=step).transpose("vertex", "xyz").values)
            vp = np.asarray(ds["vertex_point"].transpose("vertex", "xyz").values, dtype=float)
            live = np.all(np.isfinite(vf), axis=1) & (np.linalg.norm(np.nan_to_num(vf), axis=1) > 0)
            ax.quiver(*vp[live].T, *(vf[live] * scale).T, color=VERTEX_COLOUR, linewidth=0.7,
                      arrow_length_ratio=0.3, zorder=3, gid="vertex_forces")
            pts.append(vp[live] + vf[live] * scale)
            handles.append(Line2D([], [], color=VERTEX_COLOUR, linewidth=0.7,
                                  label=f"vertex force (1 kN = {_fmt(scale)} m)"))
        where = {"axo": "", "elevation": ", elevation (x-z, m)", "plan": ", plan (x-y, m)"}[view]
        caption = _no_limit_caption(ds, scenario, 70)
        ax.set_title(f"{scenario}: {_step_label(ds, scenario, step)}{where}" + (f"\n{caption}" if caption else ""),
                     fontsize=10 if not caption else 7)
    _equal_3d(ax, np.vstack(pts), asm.size, view)
    ax.view_init(*_camera(asm, view))
    fig.legend(handles=handles, loc="outside upper center", ncols=2, fontsize=7, frameon=False)
    return fig


def thrust_line(
    ds: xr.Dataset, scenario: str, step: int | Sequence[int] | None = None, fig: Canvas | None = None
) -> Canvas:
    """Elevation (x-z) of the blocks and the line of thrust through the pressure points.

    Parameters
    ----------
    ds : xarray.Dataset
    scenario : str
    step : int or sequence of int, optional
        Index (or indices, drawn together like the paper's Fig. 7) along ``step``;
        default :func:`default_step`.
    fig : Figure or SubFigure, optional

    Returns
    -------
    Figure or SubFigure
        One 2D axes with equal aspect. Each line of thrust is the line
        ``"thrust_line:<step>"`` (x, z of the pressure points in interface order, broken
        where an interface carries nothing); at ``lambda_max`` the hinges of the mechanism
        are the line ``"hinges"``; block outlines are patches ``"block:<name>"``.
    """
    asm = _assembly(ds)
    fig = _canvas(fig, (8.0, 5.0))
    ax = fig.add_subplot()
    verts = _block_vertices(asm)
    _draw_blocks_2d(ax, asm, verts)
    steps = [default_step(ds, scenario)] if step is None else list(np.atleast_1d(step))
    steps = [int(k) for k in steps if k is not None]
    lmax = _lambda_max(ds, scenario)
    lam = _value(ds, "lam", scenario).astype(float)
    if not steps:
        ax.set_title(f"{scenario}: no admissible state ({_text(ds, 'outcome', scenario, 'no optimal step')})")
    for i, k in enumerate(steps):
        pp, _, _ = _state(ds, scenario, k)
        ax.plot(pp[:, 0], pp[:, 2], color=FORCE_COLOUR if i == len(steps) - 1 else "#555555",
                linestyle=LINESTYLES[len(steps) - 1 - i], linewidth=1.8, marker="o", markersize=3.5,
                gid=f"thrust_line:{k}", label=_step_label(ds, scenario, k))
    hinges = _hinge_points(ds, scenario)
    if len(hinges) and math.isfinite(lmax) and any(np.isclose(lam[k], lmax) for k in steps):
        ax.plot(hinges[:, 0], hinges[:, 2], **HINGE_MARKER, gid="hinges", label="hinge")
    tails = draw_loads_2d(ax, ds, scenario, asm.size)
    if steps:
        fig.legend(loc="outside lower center", ncols=min(len(steps) + 1, 3), fontsize=7, frameon=False,
                   title="line of thrust (pressure points)", title_fontsize=7)
        ax.set_title(f"{scenario}: line of thrust", fontsize=10)
    _equal_2d(ax, np.vstack([np.vstack(verts)[:, [0, 2]], tails]), asm.size)
    return fig


def mechanism_view(
    ds: xr.Dataset, scenario: str, view: View | None = None, fig: Canvas | None = None
) -> Canvas:
    """The collapse mechanism: blocks displaced by the (exaggerated) mechanism, hinges marked.

    A vertex ``p`` of a block with centroid ``c`` and velocities ``(v, w)`` moves to
    ``p + s (v + w x (p - c))``; ``s`` makes the largest vertex displacement
    ``MECHANISM_FRACTION`` of the assembly size and the title states it.

    Parameters
    ----------
    ds : xarray.Dataset
    scenario : str
    view : {"axo", "elevation", "plan"}, optional
        Default: a 2D elevation (x-z) for planar scenarios, an axonometric 3D view otherwise.
        ``"elevation"`` is always drawn in 2D.
    fig : Figure or SubFigure, optional

    Returns
    -------
    Figure or SubFigure
        One axes; hinge markers are the line ``"hinges"`` (at ``hinge_point``), original
        blocks ghosts (``"ghost:<name>"`` patches in 2D, ``"blocks-ghost"`` in 3D).
    """
    asm = _assembly(ds)
    fig = _canvas(fig, (8.0, 5.6))
    view = view or ("elevation" if _is_planar(ds, scenario) else "axo")
    flat = view == "elevation"
    ax = fig.add_subplot() if flat else fig.add_subplot(projection="3d", computed_zorder=False)
    verts = _block_vertices(asm)
    vel = _mechanism(ds, scenario, asm)
    lmax = _lambda_max(ds, scenario)
    disp = None
    if vel is None:
        why = _no_limit_caption(ds, scenario, 70) or _text(ds, "outcome", scenario, "none")
        moved, title = verts, f"{scenario}: no collapse mechanism\n{why}"
    else:
        cen = asm.centroids
        disp = [vel[k, :3] + np.cross(vel[k, 3:], v - cen[k]) for k, v in enumerate(verts)]
        dmax = max(float(np.linalg.norm(d, axis=1).max()) for d in disp)
        s = MECHANISM_FRACTION * asm.size / dmax
        moved = [v + s * d for v, d in zip(verts, disp)]
        lam = f"λmax = {lmax:.3f}" if math.isfinite(lmax) else "direct limit"
        title = f"{scenario}: collapse mechanism at {lam}\n(exaggerated: largest displacement drawn {s * dmax:.2f} m)"
    hinges = _hinge_points(ds, scenario) if vel is not None else np.empty((0, 3))
    marker = HINGE_MARKER | dict(gid="hinges")
    if flat:
        _draw_blocks_2d(ax, asm, verts, faint=True)
        _draw_blocks_2d(ax, asm, moved)
        ax.plot(hinges[:, 0], hinges[:, 2], **marker)
        tails = draw_loads_2d(ax, ds, scenario, asm.size)
        _equal_2d(ax, np.vstack([np.vstack(verts + moved)[:, [0, 2]], tails]), asm.size)
    else:
        _draw_blocks_3d(ax, asm, verts, faint=True)
        _draw_blocks_3d(ax, asm, moved)
        ax.plot(*hinges.T, **marker)
        _equal_3d(ax, np.vstack(verts + moved), asm.size, view)
        ax.view_init(*_camera(asm, view, None if disp is None else np.vstack(disp)))
    fig.legend(
        handles=[Patch(facecolor="none", edgecolor="#9a9a9a", linestyle="--", label="original position"),
                 Patch(facecolor=BLOCK_COLOUR, edgecolor="#3c3c3c", alpha=0.6, label="displaced block"),
                 Line2D([], [], **HINGE_MARKER, label="hinge")],
        loc="outside lower center" if flat else "outside upper center", ncols=3, fontsize=7, frameon=False,
    )
    ax.set_title(title, fontsize=10)
    return fig


def figure_sheet(ds: xr.Dataset, max_columns: int = 4) -> Figure:
    """One sheet per study: the thrust curves on top, then one column per scenario.

    Each scenario column holds its assembly view at the default step, its line of thrust
    (planar scenarios) or plan view (spatial ones), and its collapse mechanism when it has
    one. Columns wrap after ``max_columns``.

    Parameters
    ----------
    ds : xarray.Dataset
    max_columns : int

    Returns
    -------
    Figure
    """
    scen = _scenarios(ds)
    asm = _assembly(ds)
    ncols = max(1, min(len(scen), max_columns))
    nrows = math.ceil(len(scen) / ncols)
    cell_w, panel_h = 5.2, 3.4
    fig = Figure(figsize=(cell_w * max(ncols, 2), 4.4 + 3 * panel_h * nrows), layout="constrained")
    title = str(ds.attrs.get("study_name", "")) or "study"
    fig.suptitle(f"{title}: support reactions, interface resultants, lines of thrust, mechanisms",
                 fontsize=12)
    top, bottom = fig.subfigures(2, 1, height_ratios=[4.4, 3 * panel_h * nrows])
    thrust_curves(ds, fig=top)
    cells = np.atleast_1d(bottom.subfigures(nrows, ncols, squeeze=False)).ravel()
    for cell, s in zip(cells, scen):
        panels = cell.subfigures(3, 1)
        assembly_view(ds, s, fig=panels[0])
        if _is_planar(ds, s):  # the settlement alone against the limit state (the paper's Fig. 7)
            thrust_line(ds, s, step=_first_and_limit(ds, s), fig=panels[1])
        else:
            assembly_view(ds, s, view="plan", fig=panels[1])
        if _mechanism(ds, s, asm) is not None:
            mechanism_view(ds, s, fig=panels[2])
        elif _no_limit_caption(ds, s):
            panels[2].text(0.5, 0.5, f"{s}: no finite limit\n\n{_no_limit_caption(ds, s, 60)}",
                           ha="center", va="center", fontsize=8, wrap=True)
    return fig


def write_figures(ds: xr.Dataset, outdir: Path) -> list[Path]:
    """Write every figure of a study beside its dataset.

    Files: ``thrust.png``; per scenario ``assembly_<s>.png``, ``thrust_line_<s>.png`` (planar
    scenarios only) and ``mechanism_<s>.png`` (when the scenario has a mechanism);
    ``bracket.png`` when a material parameter is swept (:mod:`tce.plot.materials`);
    ``sheet.png`` and ``sheet.pdf``. ``<s>`` is the scenario name made safe for file names.
    A load-position sweep (a ``load_x`` coordinate) first gets ``capacity.png``
    (:func:`tce.plot.capacity.influence_line`); its other figures show only the critical
    position of each group (:func:`tce.plot.capacity.critical_scenarios`).

    Parameters
    ----------
    ds : xarray.Dataset
    outdir : pathlib.Path
        Created if missing.

    Returns
    -------
    list of pathlib.Path
        The files written (``capacity.png`` first for a load-position sweep).
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    asm = _assembly(ds)
    written: list[Path] = []

    def save(fig: Canvas, name: str) -> None:
        path = outdir / name
        fig.savefig(path, dpi=150)
        written.append(path)

    if "load_x" in ds.coords:  # a load-position sweep: its influence line, then its critical positions only
        from .capacity import critical_scenarios, influence_line

        save(influence_line(ds), "capacity.png")
        ds = ds.sel(scenario=critical_scenarios(ds))
    save(thrust_curves(ds), "thrust.png")
    seen: set[str] = set()
    for i, s in enumerate(_scenarios(ds)):
        slug = _slug(s)
        slug = slug if slug not in seen else f"{slug}_{i}"
        seen.add(slug)
        save(assembly_view(ds, s), f"assembly_{slug}.png")
        if _is_planar(ds, s):
            save(thrust_line(ds, s, step=_first_and_limit(ds, s)), f"thrust_line_{slug}.png")
        if _mechanism(ds, s, asm) is not None:
            save(mechanism_view(ds, s), f"mechanism_{slug}.png")
    from .materials import write_material_figures  # imports this module: not at the top

    written += write_material_figures(ds, outdir)
    sheet = figure_sheet(ds)
    save(sheet, "sheet.png")
    save(sheet, "sheet.pdf")
    return written
