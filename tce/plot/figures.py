"""Figures of a results dataset: what each of the paper's figures shows, legible at any size.

Every function takes a results dataset (``docs/results.md``) and returns a
:class:`matplotlib.figure.Figure` built without pyplot, with a fixed layout computed from
its content (no constrained layout), so that legends are never clipped. The geometry comes
from the ``assembly`` attr; which states and scenarios are drawn from the arguments (see
:mod:`tce.plot.output` for the study's ``[plots]`` table).

:func:`thrust_curves` (Fig. 8), :func:`states_figure` (Figs. 3-7, 9, 10), :func:`thrust_lines`
(Figs. 3b, 7), :func:`base_figure` (Fig. 9), :func:`transversal_figure` (Figs. 5-6),
:func:`mechanism_view` and :func:`summary_figure`. Support forces carry their sign in the axis
label (:mod:`tce.plot.data`); coincident curves are drawn once and named together. A state
whose optimum is not unique (the canonical state is drawn, :mod:`tce.core.canonical`) or a
scenario whose outcome is not ``limit`` carries a note on every figure that draws it.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import to_hex
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon
from matplotlib.ticker import MaxNLocator
from numpy.typing import NDArray

from ..structures.assembly import Assembly
from . import draw
from .load_arrows import LOAD_COLOUR, declared_loads
from .data import (
    MAX_COLUMNS,
    SWEPT,
    State,
    assembly,
    block_rows,
    one_geometry,
    chain_interfaces,
    find_state,
    group_identical,
    groups_of,
    hinge_segments,
    is_planar,
    join_names,
    optimal_steps,
    outcome_note,
    scenarios,
    structure_frame,
    support_forces,
    swept_parameters,
    text,
    unique_note,
    value,
)

__all__ = [
    "base_figure",
    "mechanism_view",
    "states_figure",
    "summary_figure",
    "thrust_curves",
    "thrust_lines",
    "transversal_figure",
]

# Okabe-Ito (colour-blind safe), black first; line styles and markers keep them apart in greyscale
COLOURS = ("#000000", "#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442")
LINESTYLES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 2)), (0, (8, 2)), (0, (3, 1, 3, 4)))
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "h")
FORCE_COLOUR = "#c0141e"
TORQUE_COLOUR = "#000000"
THRUST_LINE_COLOUR = "#7a0c12"
HINGE_COLOUR = "#0072B2"
#: marker of a hinge on a face between two rings of a multi-ring arch (drawn smaller than a hinge)
RING_HINGE = dict(marker="o", markersize=3, markerfacecolor="#D55E00", markeredgecolor="#D55E00")
NOTE_COLOUR = "#8a4b00"
ARROW_FRACTION = 0.2  # longest resultant arrow, as a fraction of the assembly size
TORQUE_FRACTION = 0.05  # largest torque arc radius, as a fraction of the assembly size
MECHANISM_FRACTION = 0.06  # largest drawn mechanism displacement, as a fraction of the size
TORQUE_TOL = 1e-3  # torques below TORQUE_TOL * max|R| * size are not drawn
MAX_ARROWS = 40  # resultants drawn per panel (the largest)
LARGE_AT = 60  # interfaces: from here the states are drawn in wider panels, resultants on the near half only
LARGE_WIDTH = 5.4  # inches: panel width of a large structure's states
CATEGORICAL = ("alpha",)  # swept coordinates drawn as separate points, never joined by a line
FACET_AT = 8  # more scenarios than this in the thrust curves: one row per value of the other parameters
FONT = 7.5


# ---------------------------------------------------------------------------- layout
class _Grid:
    """A fixed layout: ``nrows x ncols`` panels of ``w x h`` inches with margins (inches)."""

    def __init__(self, nrows: int, ncols: int, w: float, h: float, *, left: float = 0.7, right: float = 0.2,
                 top: float = 0.55, bottom: float = 0.5, wspace: float = 0.6, hspace: float = 0.6,
                 below: float = 0.0) -> None:
        self.width = left + ncols * w + (ncols - 1) * wspace + right
        self.height = top + nrows * h + (nrows - 1) * hspace + bottom + below
        self.fig = Figure(figsize=(self.width, self.height))
        self.below = below
        self.axes = [
            [self.fig.add_axes(((left + c * (w + wspace)) / self.width,
                                (self.height - top - (r + 1) * h - r * hspace) / self.height,
                                w / self.width, h / self.height))
             for c in range(ncols)]
            for r in range(nrows)
        ]
        for row in self.axes:
            for ax in row:
                ax.tick_params(labelsize=FONT - 0.5, length=2.5, pad=1.5)
                ax.ticklabel_format(useOffset=False)
                ax.xaxis.set_major_locator(MaxNLocator(5))
                ax.yaxis.set_major_locator(MaxNLocator(5))


def _legend_rows(labels: Sequence[str], width: float) -> tuple[int, int]:
    """``(ncols, nrows)`` of a legend of ``labels`` that fits ``width`` inches at :data:`FONT`
    (every column as wide as the longest label line)."""
    longest = max((len(line) for s in labels for line in s.split("\n")), default=1)
    entry = 0.55 + 0.062 * longest
    ncols = max(1, min(len(labels), int((width - 0.3) // entry)))
    return ncols, math.ceil(len(labels) / ncols)


def _legend_height(labels: Sequence[str], width: float) -> float:
    """Inches a bottom legend of ``labels`` needs (0 without labels)."""
    if not labels:
        return 0.0
    ncols, nrows = _legend_rows(labels, width)
    lines = sum(max(s.count("\n") + 1 for s in labels[r * ncols:(r + 1) * ncols]) for r in range(nrows))
    return 0.2 + 0.17 * lines


def _bottom_legend(grid: _Grid | _Sheet, handles: list, y: float = 0.04) -> None:
    if not handles:
        return
    labels = [h.get_label() for h in handles]
    ncols, _ = _legend_rows(labels, grid.width)
    grid.fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, y / grid.height), ncols=ncols,
                    fontsize=FONT, frameon=False, handlelength=2.6, columnspacing=1.2)


def _wrap(note: str, width_in: float) -> str:
    return "\n".join(textwrap.wrap(note, max(20, int(width_in * 17)))) if note else ""


def _notes_figure(title: str, notes: Sequence[str], width: float = 7.0) -> Figure:
    """A figure of words only: ``title`` and one wrapped paragraph per note (why nothing is drawn)."""
    paras = [_wrap(n, width - 0.6) for n in notes]
    height = 0.8 + sum(0.16 * (p.count("\n") + 1) + 0.12 for p in paras)
    fig = Figure(figsize=(width, height))
    fig.suptitle(title, fontsize=FONT + 2, y=1 - 0.12 / height)
    y = height - 0.6
    for p in paras:
        fig.text(0.3 / width, y / height, p, ha="left", va="top", fontsize=FONT, color=NOTE_COLOUR)
        y -= 0.16 * (p.count("\n") + 1) + 0.12
    return fig


def _min_span(ax: Axes, values: NDArray[np.float64]) -> None:
    """Limits that make a constant look constant: at least 5 % of the largest magnitude."""
    v = values[np.isfinite(values)]
    if not v.size:
        return
    lo, hi = float(v.min()), float(v.max())
    span = max(0.05 * max(abs(lo), abs(hi)), 1e-9)
    if hi - lo < span:
        mid = 0.5 * (lo + hi)
        ax.set_ylim(mid - 0.6 * span, mid + 0.6 * span)


# ---------------------------------------------------------------------------- styles of scenarios
@dataclass(frozen=True)
class _Styles:
    """Colour by one swept parameter (else by settlement case), line style by settlement case."""

    colour_by: str
    colours: dict[str, str]
    styles: dict[str, object]
    colour_values: dict[str, str]  # legend label -> colour
    style_values: dict[str, object]  # settlement case -> line style

    @classmethod
    def of(cls, ds: xr.Dataset, names: Sequence[str]) -> _Styles:
        swept = swept_parameters(ds, names)
        cases = [str(value(ds, "settlement", s)) if "settlement" in ds.coords else s for s in names]
        order = list(dict.fromkeys(cases))
        style_of = {c: LINESTYLES[k % len(LINESTYLES)] for k, c in enumerate(order)}
        if swept:
            key = swept[0]
            vals = [float(value(ds, key, s)) for s in names]
            uniq = sorted(set(vals))
            palette = _palette(len(uniq))
            colour_of = {v: palette[k] for k, v in enumerate(uniq)}
            colours = {s: colour_of[v] for s, v in zip(names, vals)}
            labels = {f"{key} = {v:g}": colour_of[v] for v in uniq}
        else:
            key = "settlement"
            palette = _palette(len(order))
            colours = {s: palette[order.index(c)] for s, c in zip(names, cases)}
            labels = {}
        return cls(key, colours, {s: style_of[c] for s, c in zip(names, cases)}, labels,
                   style_of if len(order) > 1 or not swept else {})

    def handles(self, linewidth: float = 1.4) -> list:
        """Legend entries: one per colour value, then one per line style."""
        out: list = [Line2D([], [], color=c, linewidth=linewidth, label=k) for k, c in self.colour_values.items()]
        # coloured by settlement case: each case in its colour; else grey, the colour is another parameter's
        n = len(self.style_values)
        palette = _palette(n) if self.colour_by == "settlement" else ["#555555"] * n
        return out + [Line2D([], [], color=colour, linestyle=st, linewidth=linewidth, label=c)
                      for colour, (c, st) in zip(palette, self.style_values.items())]


def _palette(n: int) -> list[str]:
    """``n`` colours: Okabe-Ito up to 8, a sequential map (viridis) beyond."""
    if n <= len(COLOURS):
        return list(COLOURS[:n])
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [to_hex(cmap(0.92 * k / (n - 1))) for k in range(n)]


# ---------------------------------------------------------------------------- thrust curves
def _facets(ds: xr.Dataset, names: Sequence[str], styles: _Styles, by_scenario: bool) -> list[tuple[str, list[str]]]:
    """Rows ``(title, scenarios)`` of the thrust curves: one per scenario when ``by_scenario``,
    else one, or one per value of the other swept parameters beyond :data:`FACET_AT` scenarios."""
    if by_scenario:
        return [(s, [s]) for s in names]
    others = [p for p in swept_parameters(ds, names) if p != styles.colour_by]
    if len(names) <= FACET_AT or not others:
        return [("", list(names))]
    rows: dict[str, list[str]] = {}
    for s in names:
        key = ", ".join(f"{p} = {float(value(ds, p, s)):g}" for p in others)
        rows.setdefault(key, []).append(s)
    return list(rows.items())


def _coincide(groups: Sequence[Sequence[tuple[str, str]]], one_scenario: bool) -> str:
    """Panel note naming coincident (scenario, support) curves: ``a, b (left, right); ...``
    (groups of the same scenarios merged; within one scenario, only the supports named)."""
    if one_scenario:
        return "; ".join(", ".join(sup for _, sup in g) for g in groups)
    merged: dict[tuple[str, ...], list[str]] = {}
    for g in groups:
        by_scen: dict[str, list[str]] = {}
        for s, sup in g:
            by_scen.setdefault(s, []).append(sup)
        sups = {tuple(v) for v in by_scen.values()}
        if len(sups) == 1:
            merged.setdefault(tuple(by_scen), []).extend(next(iter(sups)))
        else:
            merged.setdefault((join_names([f"{s} ({', '.join(v)})" for s, v in by_scen.items()], 3),), [])
    return "; ".join(join_names(k, 3) + (f" ({', '.join(dict.fromkeys(v))})" if v else "") for k, v in merged.items())


def thrust_curves(ds: xr.Dataset, names: Sequence[str] | None = None) -> Figure:
    """Forces on the supports against lambda, in the frame of the structure (Fig. 8).

    Parameters
    ----------
    ds : xarray.Dataset
    names : sequence of str, optional
        Scenarios drawn (default: all).

    Returns
    -------
    Figure
        Panels ``H``, ``V`` (and ``S``, ``M`` when a scenario is spatial; ``M`` not for
        radial supports). Up to two supports: colour and line style per scenario
        (:class:`_Styles`), marker per support, faceted beyond :data:`FACET_AT` scenarios;
        more supports: one row per scenario, colour and marker per support. Curves have the
        gid ``"reaction:<component>:<scenario>:<support>"`` (the first of coincident ones),
        lambda_max lines ``"lambda_max"``.
    """
    names = list(names or scenarios(ds))
    asm = assembly(ds, names[0] if names else None)  # the frame of the span: the same for every geometry
    frame = structure_frame(asm)
    spatial = any(not is_planar(ds, s) for s in names)
    comps = (["H", "S", "V"] + ([] if frame.kind == "radial" else ["M"])) if spatial else ["H", "V"]
    supports = [str(s) for s in ds["support"].values]
    by_support = len(supports) > 2
    styles = _Styles.of(ds, names)
    facets = _facets(ds, names, styles, by_support)
    forces = {s: support_forces(ds, s, frame) for s in names}
    steps = {s: optimal_steps(ds, s) for s in names}
    lams = {s: value(ds, "lam", s).astype(float)[steps[s]] for s in names}
    faint = {s: bool(unique_note(ds, s)) for s in names}
    sup_colours = _palette(len(supports)) if by_support else []

    def style(s: str, j: int) -> dict:
        colour = sup_colours[j] if by_support else styles.colours[s]
        return dict(color=colour, linestyle=styles.styles[s], marker=MARKERS[j % len(MARKERS)],
                    markerfacecolor=colour if by_support or j % 2 == 0 else "white")

    if by_support:
        handles: list = [Line2D([], [], linewidth=1.3, markersize=4, label=f"support {sup}",
                                **{k: v for k, v in style(names[0], j).items() if k != "linestyle"})
                         for j, sup in enumerate(supports)]
        if len(styles.style_values) > 1:
            handles += [Line2D([], [], color="#555555", linestyle=st, linewidth=1.3, label=c)
                        for c, st in styles.style_values.items()]
    else:
        handles = styles.handles()
        handles += [Line2D([], [], color="black", linestyle="none", marker=MARKERS[j % len(MARKERS)], markersize=4.5,
                           markerfacecolor="white" if j % 2 else "black", label=f"support {sup}")
                    for j, sup in enumerate(supports)]
    if any(faint.values()):
        handles.append(Line2D([], [], color="black", alpha=0.4, linewidth=2.5,
                              label="faint: optimum not unique\n(the canonical state is drawn)"))
    limits = sorted({round(float(value(ds, "lambda_max", s)), 9) for s in names
                     if math.isfinite(float(value(ds, "lambda_max", s)))})
    if limits:
        shown = ", ".join(f"{v:.3f}" for v in limits[:6]) + (" ..." if len(limits) > 6 else "")
        handles.append(Line2D([], [], color="#555555", linestyle=":", linewidth=1.0, label=f"λmax = {shown}"))
    square = len(comps) == 4 and len(facets) == 1
    ncols, nrows = (2, 2) if square else (len(comps), len(facets))
    w = 3.4
    width = 0.8 + ncols * w + (ncols - 1) * 0.85 + 0.2
    notes = [_wrap(f"{s}: {outcome_note(ds, s)}", width - 0.4) for s in names if outcome_note(ds, s)]
    lines = [0, *np.cumsum([n.count("\n") + 1 for n in notes])]  # note lines below each note
    below = _legend_height([h.get_label() for h in handles], width) + 0.16 * lines[-1]
    grid = _Grid(nrows, ncols, w, 2.3, left=0.8, wspace=0.85, hspace=0.8, top=0.8, bottom=0.45, below=below)
    xmax = 1.08 * max([*limits, *(float(np.max(v)) for v in lams.values() if v.size)], default=1.0)
    for r, (facet, members) in enumerate(facets):
        for c, comp in enumerate(comps):
            ax = grid.axes[c // 2][c % 2] if square else grid.axes[r][c]
            keys, curves = [], []
            for s in members:
                for j, sup in enumerate(supports):
                    keys.append((s, sup))
                    curves.append((lams[s], forces[s][comp][steps[s], j]))
            allv = np.concatenate([y for _, y in curves]) if curves else np.empty(0)
            scale = float(np.nanmax(np.abs(allv))) if np.isfinite(allv).any() else 1.0
            same: list[list[tuple[str, str]]] = []
            for g in group_identical(curves, atol=1e-6 * max(scale, 1e-12)):
                s, sup = keys[g[0]]
                j = supports.index(sup)
                x, y = curves[g[0]]
                ax.plot(x, y, linewidth=1.3, alpha=0.45 if faint[s] else 1.0, markersize=4,
                        markevery=(0.03 * (j % 2), 0.1), gid=f"reaction:{comp}:{s}:{sup}", **style(s, j))
                if len(g) > 1:
                    same.append([keys[i] for i in g])
            for v in limits:  # named in the legend, not over the curves
                ax.axvline(v, color="#555555", linestyle=":", linewidth=1.0, gid="lambda_max")
            _min_span(ax, allv)
            ax.grid(True, linewidth=0.3, alpha=0.6)
            ax.set_xlim(0.0, xmax)
            ax.set_ylabel(frame.labels[comp], fontsize=FONT)
            if (c >= 2) if square else r == len(facets) - 1:
                ax.set_xlabel("load multiplier λ (–)", fontsize=FONT)
            else:  # the panels below share this λ axis and name it
                ax.tick_params(labelbottom=False)
            title = facet
            if same:
                title += ("\n" if title else "") + _wrap("coincide: " + _coincide(same, len(members) == 1), w)
            ax.set_title(title, fontsize=FONT - 0.5, loc="left", y=1.0)
    grid.fig.suptitle(f"{_study(ds)}: forces on the supports", fontsize=FONT + 2, y=1 - 0.18 / grid.height)
    _bottom_legend(grid, handles, y=0.06 + 0.16 * lines[-1])
    for k, note in enumerate(notes):
        grid.fig.text(0.5, (0.06 + 0.16 * lines[k]) / grid.height, note, ha="center", va="bottom",
                      fontsize=FONT - 0.5, color=NOTE_COLOUR)
    return grid.fig


def _study(ds: xr.Dataset) -> str:
    return str(ds.attrs.get("study_name", "")) or "study"


# ---------------------------------------------------------------------------- small multiples
class _Sheet:
    """Panels of one drawing on a single equal-aspect axes (no ticks), panel ``(r, c)``
    shifted by :meth:`offset` (one axes however many panels keeps a grid fast); below them a
    scale bar and, for an axonometric camera, the global axes.

    Parameters
    ----------
    nrows, ncols : int
    lo, hi : (2,) array
        Screen box of one panel's content (m).
    width : float
        Width of a panel (inches).
    title : float
        Inches above each panel for its title.
    below : float
        Inches under the drawing for the figure legend.
    """

    GAP = 0.3  # inches between panels
    MIN_WIDTH = 5.0  # inches: room for the title and the legend

    def __init__(self, nrows: int, ncols: int, lo: NDArray, hi: NDArray, width: float, title: float,
                 below: float, camera: draw.Camera, top: float = 0.45, header: float = 0.0) -> None:
        self.lo, ext = np.asarray(lo, float), np.asarray(hi, float) - np.asarray(lo, float)
        self.k = width / ext[0]  # inches per metre
        gap, self.title_h = self.GAP / self.k, title / self.k
        self.cell = np.array([ext[0] + gap, ext[1] + self.title_h + gap])
        self.strip = 0.3 / self.k  # scale bar and axes
        data_w, data_h = ncols * self.cell[0], nrows * self.cell[1] + self.strip
        self.header_h = header / self.k
        data_h += self.header_h
        fw, fh = max(data_w * self.k + 0.2, self.MIN_WIDTH), data_h * self.k + top + below
        self.fig = Figure(figsize=(fw, fh))
        left = 0.5 * (fw - data_w * self.k)
        self.ax = self.fig.add_axes((left / fw, below / fh, data_w * self.k / fw, data_h * self.k / fh))
        self.ax.set_axis_off()
        self.ax.set_xlim(0.0, data_w)
        self.ax.set_ylim(-data_h + self.header_h, self.header_h)
        self.width, self.height, self.nrows, self.camera = fw, fh, nrows, camera
        self._scale_bar(ext)

    def offset(self, r: int, c: int) -> NDArray[np.float64]:
        """Screen shift of panel ``(r, c)``."""
        return np.array([c * self.cell[0] + 0.5 * self.GAP / self.k,
                         -(r + 1) * self.cell[1] + 0.5 * self.GAP / self.k]) - self.lo

    def title(self, r: int, c: int, text: str, colour: str = "black") -> None:
        x = (c + 0.5) * self.cell[0]
        y = -r * self.cell[1] - 0.2 * self.GAP / self.k
        self.ax.text(x, y, text, ha="center", va="top", fontsize=FONT, color=colour)

    def header(self, c: int, text: str, colour: str = "black") -> None:
        """Text above column ``c`` (in the header band)."""
        self.ax.text((c + 0.5) * self.cell[0], self.header_h, text, ha="center", va="top", fontsize=FONT,
                     color=colour)

    def note(self, r: int, c: int, text: str) -> None:
        """A framed message in the middle of panel ``(r, c)``."""
        x = (c + 0.5) * self.cell[0]
        y = -(r + 0.5) * self.cell[1]
        self.ax.text(x, y, text, ha="center", va="center", fontsize=FONT, color=NOTE_COLOUR,
                     bbox=dict(facecolor="white", edgecolor=NOTE_COLOUR, alpha=0.9))

    def _scale_bar(self, ext: NDArray) -> None:
        length = draw.nice(0.25 * ext[0])
        y = -self.nrows * self.cell[1] - 0.55 * self.strip
        x0 = 0.5 * self.GAP / self.k
        self.ax.plot([x0, x0 + length], [y, y], color="black", linewidth=2.0, solid_capstyle="butt", gid="scale_bar")
        self.ax.text(x0 + length + 0.1 / self.k, y, f"{length:g} m", va="center", fontsize=FONT - 0.5)
        x1 = x0 + length + 0.9 / self.k
        size = 0.16 / self.k
        names = self.camera.axis_names if self.camera.flat else ("x", "y", "z")
        cols = {"x": 0, "y": 1, "z": 2}
        for name in names:
            d = self.camera.basis[:2, cols[name]] * size
            if np.linalg.norm(d) < 0.1 * size:
                continue
            self.ax.annotate("", (x1 + d[0], y + d[1]), (x1, y),
                             arrowprops=dict(arrowstyle="-|>", color="#444444", linewidth=0.8, mutation_scale=6))
            self.ax.text(x1 + 1.35 * d[0], y + 1.35 * d[1], name, fontsize=FONT - 1, color="#444444", ha="center",
                         va="center")


# ---------------------------------------------------------------------------- states
@dataclass(frozen=True)
class _Scales:
    """One arrow scale (m per kN) and one torque scale (m per kN m) for a whole figure."""

    force: float
    torque: float
    fmax: float

    @classmethod
    def of(cls, arrays: _Arrays, states: Sequence[State], size: float) -> _Scales:
        fmax = tmax = 0.0
        for st in states:
            if st.step is None:
                continue
            _, res, tq = arrays.state(st)
            fmax = max(fmax, float(np.nanmax(np.linalg.norm(res, axis=1), initial=0.0)))
            tmax = max(tmax, float(np.nanmax(np.abs(tq), initial=0.0)))
        return cls(*arrow_scales(fmax, tmax, size), fmax)


def arrow_scales(fmax: float, tmax: float, size: float) -> tuple[float, float]:
    """The arrow scale (m per kN) and the torque-arc scale (m per kN m) of forces up to ``fmax``
    (kN) and torques up to ``tmax`` (kN m) on a structure of ``size`` (m): 0 when there is no
    force, or no torque above ``TORQUE_TOL * fmax * size``."""
    force = draw.nice(ARROW_FRACTION * size / fmax) if fmax > 0 else 0.0
    torque = draw.nice(TORQUE_FRACTION * size / tmax) if tmax > max(TORQUE_TOL * fmax * size, 0.0) else 0.0
    return force, torque


def displaced(asm: Assembly, vel: NDArray[np.float64]) -> tuple[list[NDArray[np.float64]], float]:
    """Each block's vertices moved by the mechanism ``vel`` (a row ``(v, w)`` per block),
    exaggerated so that the largest displacement is :data:`MECHANISM_FRACTION` of the
    assembly size, and that displacement (m; 0 for a mechanism that moves nothing).

    A vertex ``p`` of a block with centroid ``c`` moves to ``p + s (v + w x (p - c))``.
    """
    verts = [np.asarray(b.shape.vertices, float) for b in asm.blocks]
    disp = [vel[k, :3] + np.cross(vel[k, 3:], v - c) for k, (v, c) in enumerate(zip(verts, asm.centroids))]
    dmax = max(float(np.linalg.norm(d, axis=1).max()) for d in disp)
    scale = MECHANISM_FRACTION * asm.size / dmax if dmax > 0 else 0.0
    return [v + scale * d for v, d in zip(verts, disp)], scale * dmax


class _Arrays:
    """Pressure points, resultants and torques of the scenarios of a figure, read once."""

    def __init__(self, ds: xr.Dataset, names: Sequence[str]) -> None:
        self.index = {s: k for k, s in enumerate(names)}

        def read(name: str, dims: list[str]) -> NDArray[np.float64]:
            return np.stack([np.asarray(value(ds, name, s, dims), float) for s in names])

        self.pp = read("pressure_point", ["step", "interface", "xyz"])
        self.res = read("resultant", ["step", "interface", "xyz"])
        self.tq = read("torque", ["step", "interface"])

    def state(self, st: State) -> tuple[NDArray, NDArray, NDArray]:
        i = self.index[st.scenario]
        return self.pp[i, st.step], self.res[i, st.step], self.tq[i, st.step]


def _camera(ds: xr.Dataset, names: Sequence[str], asm: Assembly) -> draw.Camera:
    """Elevation when every scenario is planar, else the axonometric camera of the assembly
    turned to show what happens across its plane."""
    if all(is_planar(ds, s) for s in names):
        return draw.Camera.elevation()
    return draw.Camera.for_assembly(asm, across=True)


def _state_panel(ax: Axes, off: NDArray, ds: xr.Dataset, asm: Assembly, art: draw.BlockArt, arrays: _Arrays,
                 st: State, camera: draw.Camera, scales: _Scales, chain: list[int] | None, head: float) -> None:
    """Draw one state (an optimal step) shifted by ``off``."""
    art.draw(ax, off)
    pp, res, tq = arrays.state(st)
    ok = np.all(np.isfinite(pp), axis=1) & np.all(np.isfinite(res), axis=1)
    if _thinned(asm, camera):  # the far half is seen through the near one: leave it out
        ok &= camera.depth(np.nan_to_num(pp)) >= camera.depth(asm.centroids[list(asm.free_indices)].mean(axis=0))
    mag = np.where(ok, np.linalg.norm(np.nan_to_num(res), axis=1), -1.0)
    shown = np.zeros(len(ok), bool)
    shown[np.argsort(-mag, kind="stable")[: min(MAX_ARROWS, int(ok.sum()))]] = True

    def xy(p: NDArray) -> NDArray:
        return camera.project(p) + off

    if chain is not None:
        line = xy(np.where(ok[chain, None], pp[chain], np.nan))
        ax.plot(line[:, 0], line[:, 1], color=THRUST_LINE_COLOUR, linewidth=0.9, alpha=0.8, zorder=3,
                gid="thrust_line")
    if shown.any():
        vec = res[shown] * scales.force
        draw.arrows(ax, xy(pp[shown] - 0.5 * vec), xy(pp[shown] + 0.5 * vec), FORCE_COLOUR, head, linewidth=1.5,
                    gid="resultants")
        c = xy(pp[shown])
        ax.plot(c[:, 0], c[:, 1], linestyle="none", marker="o", markersize=2.2, color=FORCE_COLOUR, zorder=5,
                gid="pressure_points")
    loads = declared_loads(ds, st.scenario)
    if loads is not None and scales.force > 0:  # each arrow ends where its load acts
        p, f, live = loads
        f = np.where(live[:, None], st.lam * f, f)
        keep = np.linalg.norm(f, axis=1) > 0
        vec = f[keep] * scales.force
        draw.arrows(ax, xy(p[keep] - vec), xy(p[keep]), LOAD_COLOUR, head, linewidth=1.8, gid="loads")
    if scales.torque > 0:
        sig = shown & np.isfinite(tq) & (np.abs(np.nan_to_num(tq)) > TORQUE_TOL * scales.fmax * asm.size)
        if sig.any():
            normals = np.array([i.normal for i in asm.interfaces])[sig]
            arcs = draw.torque_arcs(pp[sig], normals, tq[sig], scales.torque)
            coll = LineCollection([xy(a) for a in arcs], colors=TORQUE_COLOUR, linewidths=1.0, zorder=4)
            coll.set_gid("torques")
            ax.add_collection(coll)
    if st.target == "max" and text(ds, "outcome", st.scenario, "limit") == "limit":
        _hinges(ax, ds, st.scenario, asm, camera, planar=is_planar(ds, st.scenario), offset=off)


def _thinned(asm: Assembly, camera: draw.Camera) -> bool:
    """Whether a panel draws only the near half's resultants (more than :data:`LARGE_AT`
    interfaces in an axonometric view)."""
    return len(asm.interfaces) > LARGE_AT and not camera.flat


def _hinges(ax: Axes, ds: xr.Dataset, scenario: str, asm: Assembly, camera: draw.Camera, planar: bool,
            offset: NDArray = np.zeros(2)) -> None:
    """Hinge lines of the mechanism (segments along the hinge axes, gid ``"hinges"``); in an
    elevation of a planar scenario, where they are seen end-on, a marker each."""
    if planar and camera == draw.Camera.elevation():
        mode = value(ds, "interface_mode", scenario).astype(str) if "interface_mode" in ds else np.array([])
        hp = np.asarray(value(ds, "hinge_point", scenario, ["interface", "xyz"]), float)
        turning = (mode == "hinge") & np.all(np.isfinite(hp), axis=1)
        ring = _ring_faces(ds, scenario, len(hp))
        xy = camera.project(hp[turning & ~ring]) + offset
        ax.plot(xy[:, 0], xy[:, 1], linestyle="none", marker="o", markersize=6, markerfacecolor="white",
                markeredgecolor=HINGE_COLOUR, markeredgewidth=1.6, zorder=6, gid="hinges")
        if (turning & ring).any():  # rings separating: many small turns along the faces between rings
            xy = camera.project(hp[turning & ring]) + offset
            ax.plot(xy[:, 0], xy[:, 1], linestyle="none", **RING_HINGE, zorder=5, gid="ring_hinges")
        return
    segs = hinge_segments(ds, scenario, asm)
    if segs.size:
        coll = LineCollection([camera.project(s) + offset for s in segs], colors=HINGE_COLOUR, linewidths=2.6,
                              zorder=6, capstyle="round")
        coll.set_gid("hinges")
        ax.add_collection(coll)


def _ring_faces(ds: xr.Dataset, scenario: str, n: int) -> NDArray[np.bool_]:
    """Which of the ``n`` interfaces of ``scenario`` are faces between rings (``interface_kind``
    ``"ring"``; none where the dataset has no kinds)."""
    if "interface_kind" not in ds:
        return np.zeros(n, dtype=bool)
    kinds = ds["interface_kind"]
    kinds = kinds.sel(scenario=scenario) if "scenario" in kinds.dims else kinds
    return np.asarray(kinds.values).astype(str) == "ring"


def _content_box(art: draw.BlockArt, pad: float) -> tuple[NDArray, NDArray]:
    return art.points.min(axis=0) - pad, art.points.max(axis=0) + pad


def _state_handles(scales: _Scales, chain: bool, hinges: bool, loads: bool = False, thinned: bool = False) -> list:
    h: list = [Patch(facecolor=draw.BLOCK_COLOUR, edgecolor=draw.EDGE_COLOUR, label="block"),
               Patch(facecolor=draw.SUPPORT_COLOUR, edgecolor=draw.EDGE_COLOUR, label="support")]
    if scales.force > 0:
        rule = f"\non the near half of the structure, the {MAX_ARROWS} largest per panel" if thinned else ""
        h.append(Line2D([], [], color=FORCE_COLOUR, linewidth=1.5, marker="o", markersize=3,
                        label=f"interface resultant at its pressure point (1 kN = {scales.force:.3g} m){rule}"))
    if scales.torque > 0:
        h.append(Line2D([], [], color=TORQUE_COLOUR, linewidth=1.0,
                        label=f"torque about the normal (arc radius: 1 kN m = {scales.torque:.3g} m)"))
    if loads:
        h.append(Line2D([], [], color=LOAD_COLOUR, linewidth=1.8, label="applied load (live ones × λ), same scale"))
    if chain:
        h.append(Line2D([], [], color=THRUST_LINE_COLOUR, linewidth=0.9, label="line of thrust"))
    if hinges:
        h.append(Line2D([], [], color=HINGE_COLOUR, linewidth=2.6, marker="o", markerfacecolor="white",
                        label="hinge at λmax"))
    return h


def states_figure(ds: xr.Dataset, panels: Sequence[tuple[str, object]], title: str = "") -> Figure:
    """Interface resultants, torques, lines of thrust and hinges of drawn states.

    Parameters
    ----------
    ds : xarray.Dataset
    panels : sequence of (scenario, target)
        One panel each (target: a multiplier or ``"max"``, :func:`tce.plot.data.find_state`),
        laid out as by :func:`tce.plot.data.state_pages`.
    title : str

    Returns
    -------
    Figure
        One axes holding every panel (shifted copies of the drawing). Arrows (gid
        ``"resultants"``, heads ``"resultants-heads"``) are centred on the projected
        pressure points (line ``"pressure_points"``), to the scale stated in the legend.
    """
    names = list(dict.fromkeys(s for s, _ in panels))
    asm = one_geometry(ds, names)
    targets = list(dict.fromkeys(t for _, t in panels))
    states = {(s, t): find_state(ds, s, t) for s, t in panels}
    arrays = _Arrays(ds, names)
    camera = _camera(ds, names, asm)
    chain = chain_interfaces(asm)
    scales = _Scales.of(arrays, list(states.values()), asm.size)
    art = draw.BlockArt.of(asm, camera)
    lo, hi = _content_box(art, 0.5 * scales.fmax * scales.force + 0.03 * asm.size)
    many = len(targets) > 1
    across = many and len(names) == 1  # one scenario: its states side by side
    grid = many and not across  # a column per scenario, a row per target: headers name them
    if across:
        cols, rows = min(len(targets), MAX_COLUMNS), math.ceil(len(targets) / MAX_COLUMNS)
    elif grid:
        cols, rows = len(names), len(targets)
    else:
        cols = min(len(names), 2)
        rows = math.ceil(len(names) / cols)
    width = 3.0 if camera.flat else LARGE_WIDTH if _thinned(asm, camera) else 3.2
    # what holds for every state of a scenario (outcome, non-unique) is said once, in its header
    common = {s: _common_note([states[(s, t)] for t in targets if (s, t) in states]) for s in names}
    heads = {s: s + ("\n" + _wrap(common[s], width) if common[s] else "") for s in names} if many else {}
    header_lines = max((h.count("\n") + 1 for h in heads.values()), default=0)
    # a panel's own note: what its scenario's header does not already say
    cell_notes = {k: "" if many and st.note == common[k[0]] else st.note for k, st in states.items()
                  if st.step is not None}
    cell_lines = 1 + max((_wrap(n, width).count("\n") + 1 for n in cell_notes.values() if n), default=0)
    has_loads = any(declared_loads(ds, s) is not None for s in names)
    handles = _state_handles(scales, chain is not None, any(t == "max" for t in targets), has_loads,
                             _thinned(asm, camera))
    below = _legend_height([x.get_label() for x in handles], max(cols * (width + _Sheet.GAP), _Sheet.MIN_WIDTH))
    sheet = _Sheet(rows, cols, lo, hi, width, 0.16 * cell_lines + 0.08, below, camera,
                   header=0.16 * header_lines + 0.05 if grid else 0.0)
    head = 0.04 * asm.size
    for s, t in panels:
        if across:
            r, c = divmod(targets.index(t), cols)
        elif grid:
            r, c = targets.index(t), names.index(s)
        else:
            r, c = divmod(names.index(s), cols)
        st = states[(s, t)]
        off = sheet.offset(r, c)
        if st.step is None:
            art.draw(sheet.ax, off)
            sheet.note(r, c, _wrap(f"{st.label}: {st.note}", 3.0))
        else:
            _state_panel(sheet.ax, off, ds, asm, art, arrays, st, camera, scales, chain, head)
        note = cell_notes.get((s, t), "")
        label = st.label if many else f"{s}: {st.label}"
        sheet.title(r, c, label + ("\n" + _wrap(note, width) if note else ""), NOTE_COLOUR if note else "black")
    for s in names if grid else []:
        sheet.header(names.index(s), heads[s], NOTE_COLOUR if common[s] else "black")
    where = "elevation" if camera == draw.Camera.elevation() else "axonometric view"
    what = f"{names[0]}: " if across else ""
    sub = "\n" + _wrap(common[names[0]], sheet.width) if across and common[names[0]] else ""
    sheet.fig.suptitle(title or f"{_study(ds)}: {what}internal stress states ({where}){sub}", fontsize=FONT + 2,
                       y=1 - 0.12 / sheet.height)
    _bottom_legend(sheet, handles)
    return sheet.fig


def _common_note(states: Sequence[State]) -> str:
    """The note every drawn state of a scenario shares ("" if they differ or have none)."""
    notes = {st.note for st in states if st.step is not None}
    return notes.pop() if len(notes) == 1 else ""


# ---------------------------------------------------------------------------- lines of thrust
def thrust_lines(ds: xr.Dataset, names: Sequence[str], targets: Sequence[object]) -> Figure:
    """One elevation per drawn state with the line of thrust of each scenario (Figs. 3b, 7).

    Only for a structure that is one line of blocks (:func:`tce.plot.data.chain_interfaces`).
    Lines carry the gid ``"thrust_line:<scenario>"``; coincident lines are drawn once (the
    first scenario's) and named together in the panel title; at lambda_max the hinges of
    the first scenario with a mechanism are marked (gid ``"hinges"``).

    Raises
    ------
    ValueError
        The structure is not one line of blocks.
    """
    names, targets = list(names), list(targets)
    asm = one_geometry(ds, names)
    chain = chain_interfaces(asm)
    if chain is None:
        raise ValueError("the structure is not one line of blocks: it has no line of thrust")
    camera = draw.Camera.elevation()
    styles = _Styles.of(ds, names)
    arrays = _Arrays(ds, names)
    art = draw.BlockArt.of(asm, camera)
    lo, hi = _content_box(art, 0.03 * asm.size)
    cols = min(len(targets), 2)
    rows = math.ceil(len(targets) / cols)
    handles = [Line2D([], [], color=styles.colours[s], linestyle=styles.styles[s], linewidth=1.4, marker="o",
                      markersize=2.5, label=s) for s in names]
    notes = [f"{s}: {n}" for s in names if (n := outcome_note(ds, s) or unique_note(ds, s))]
    width = 3.6
    fig_w = max(cols * (width + _Sheet.GAP), _Sheet.MIN_WIDTH)
    below = _legend_height([x.get_label() for x in handles], fig_w) + 0.16 * len(notes)
    sheet = _Sheet(rows, cols, lo, hi, width, 0.55, below, camera)
    for k, t in enumerate(targets):
        r, c = divmod(k, cols)
        off = sheet.offset(r, c)
        art.draw(sheet.ax, off)
        labels, keys, lines = set(), [], []
        for s in names:
            st = find_state(ds, s, t)
            if st.step is not None:
                labels.add(st.label)
                keys.append(s)
                lines.append(camera.project(arrays.state(st)[0][chain]) + off)
        groups = group_identical([(np.arange(2 * len(ln)), ln.ravel()) for ln in lines], atol=1e-6 * asm.size)
        for g in groups:
            s, line = keys[g[0]], lines[g[0]]
            sheet.ax.plot(line[:, 0], line[:, 1], color=styles.colours[s], linestyle=styles.styles[s], linewidth=1.4,
                          marker="o", markersize=2.5, zorder=4, gid=f"thrust_line:{s}")
        if t == "max":
            first = next((s for s in names if text(ds, "outcome", s, "limit") == "limit"), None)
            if first is not None:
                _hinges(sheet.ax, ds, first, asm, camera, planar=True, offset=off)
        same = "; ".join(join_names([keys[i] for i in g], 4) for g in groups if len(g) > 1)
        # no state drawn: each scenario's own note says why (its outcome, or the step's status)
        title = " / ".join(sorted(labels)) if labels else f"λ = {t}: no state drawn (see the notes)"
        sheet.title(r, c, title + ("\n" + _wrap("coincide: " + same, width) if same else ""))
    sheet.fig.suptitle(f"{_study(ds)}: lines of thrust (pressure points, elevation)", fontsize=FONT + 2,
                       y=1 - 0.12 / sheet.height)
    _bottom_legend(sheet, handles, y=0.06 + 0.16 * len(notes))
    for k, note in enumerate(notes):
        sheet.fig.text(0.5, (0.06 + 0.16 * k) / sheet.height, _wrap(note, sheet.width), ha="center",
                       fontsize=FONT - 0.5, color=NOTE_COLOUR)
    return sheet.fig


# ---------------------------------------------------------------------------- base interfaces
def base_figure(ds: xr.Dataset, names: Sequence[str], targets: Sequence[object]) -> Figure:
    """The support interfaces seen along their normals, with the pressure point of every
    scenario and drawn state (the paper's Fig. 9: base pressure points on the rocking edge).

    Horizontal interfaces are drawn in plan (x, y); others in their own frame (t1, t2).
    Points carry the gid ``"base:<interface>:<scenario>"``.
    """
    names, targets = list(names), list(targets)
    asm = one_geometry(ds, names)
    sup = set(asm.support_indices)
    itfs = [k for k, i in enumerate(asm.interfaces) if (i.a in sup) != (i.b in sup)]
    styles = _Styles.of(ds, names)
    cols = min(len(itfs), 4)
    rows = math.ceil(len(itfs) / cols)
    w = 2.6
    handles = [Line2D([], [], color=styles.colours[s], linestyle="none", marker="o", markersize=5, label=s)
               for s in names]
    handles += [Line2D([], [], color="#555555", linestyle="none", marker=MARKERS[k % len(MARKERS)], markersize=5,
                       markerfacecolor="none", label=f"state {t}") for k, t in enumerate(targets)] if len(targets) > 1 else []
    if "max" in targets:
        handles.append(Line2D([], [], color=HINGE_COLOUR, linewidth=3, alpha=0.5, label="hinge line at λmax"))
    width = 0.7 + cols * w + (cols - 1) * 0.7 + 0.2
    # a scenario none of whose drawn states has a solved step: why, under the legend
    asked = {s: [find_state(ds, s, t) for t in targets] for s in names}
    notes = [_wrap(f"{s}: no pressure point drawn: {sts[0].note}", width - 0.4)
             for s, sts in asked.items() if all(st.step is None for st in sts)]
    lines = sum(n.count("\n") + 1 for n in notes)
    grid = _Grid(rows, cols, w, w, left=0.7, wspace=0.7, hspace=0.8, top=0.7, bottom=0.45 + 0.14 * lines,
                 below=_legend_height([x.get_label() for x in handles], width))
    itf_names = [str(x) for x in ds["interface"].values]
    for n, k in enumerate(itfs):
        ax = grid.axes[n // cols][n % cols]
        itf = asm.interfaces[k]
        basis = np.array([[1.0, 0, 0], [0, 1.0, 0]]) if abs(itf.normal[2]) > 0.9 else itf.frame[1:]
        axes_names = ("x", "y") if abs(itf.normal[2]) > 0.9 else ("t1", "t2")
        poly = itf.points @ basis.T
        ax.add_patch(Polygon(poly, closed=True, facecolor=draw.SUPPORT_COLOUR, alpha=0.25, edgecolor=draw.EDGE_COLOUR))
        pts = [poly]
        if "max" in targets:
            for s in names:
                for seg in hinge_segments(ds, s, asm):
                    if np.allclose((seg - itf.points[0]) @ itf.normal, 0.0, atol=1e-9 * asm.size):
                        xy = seg @ basis.T
                        ax.plot(xy[:, 0], xy[:, 1], color=HINGE_COLOUR, linewidth=3, alpha=0.5, zorder=1,
                                gid="hinge", solid_capstyle="butt")
        for s in names:
            for j, st in enumerate(asked[s]):
                if st.step is None:
                    continue
                p = value(ds, "pressure_point", s, ["step", "interface", "xyz"])[st.step, k]
                if not np.all(np.isfinite(p)):
                    continue
                xy = p @ basis.T
                ax.plot(*xy, linestyle="none", marker=MARKERS[j % len(MARKERS)], markersize=6,
                        color=styles.colours[s], markerfacecolor="none" if j else styles.colours[s], alpha=0.85,
                        gid=f"base:{itf_names[k]}:{s}")
                pts.append(xy[None])
        allp = np.vstack(pts)
        mid = 0.5 * (allp.min(axis=0) + allp.max(axis=0))
        half = 0.58 * max(np.ptp(allp, axis=0).max(), 1e-9)  # square panel, equal scales
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[1] - half, mid[1] + half)
        ax.grid(True, linewidth=0.3, alpha=0.5)
        ax.set_xlabel(f"{axes_names[0]} (m)", fontsize=FONT - 0.5)
        ax.set_ylabel(f"{axes_names[1]} (m)", fontsize=FONT - 0.5)
        ax.set_title(f"interface {itf_names[k]}", fontsize=FONT, y=1.0)
    for n in range(len(itfs), rows * cols):
        grid.axes[n // cols][n % cols].set_axis_off()
    what = ", ".join("λmax" if t == "max" else f"λ = {t:g}" for t in targets)
    grid.fig.suptitle(f"{_study(ds)}: pressure points on the support interfaces at {what}", fontsize=FONT + 1.5,
                      y=1 - 0.15 / grid.height)
    _bottom_legend(grid, handles, y=0.04 + 0.14 * lines)
    if notes:
        grid.fig.text(0.2 / grid.width, (0.04 + 0.14 * lines) / grid.height, "\n".join(notes), ha="left", va="top",
                      fontsize=FONT - 0.5, color=NOTE_COLOUR, gid="no_state")
    return grid.fig


# ---------------------------------------------------------------------------- mechanism
def mechanism_view(ds: xr.Dataset, names: Sequence[str], drawn: Sequence[str] | None = None) -> Figure:
    """The collapse mechanism shared by ``names``: blocks displaced (exaggerated) over their
    original outlines, hinge lines marked.

    The title says "every scenario drawn" when ``names`` are all of ``drawn`` (default: every
    scenario of ``ds``; passed because a worker receives only the scenarios a figure reads).

    The blocks are :func:`displaced`; the title states the largest displacement drawn.

    Returns
    -------
    Figure
        One axes: displaced blocks (gid ``"blocks"``), ghosts (``"blocks-ghost"``), hinges
        (``"hinges"``).
    """
    names = list(names)
    s0 = names[0]
    asm = one_geometry(ds, names)
    moved, shown = displaced(asm, block_rows(ds, "mechanism", s0, asm))
    planar = is_planar(ds, s0)
    if planar:
        camera = draw.Camera.elevation()
    else:
        d = np.vstack(moved) - np.vstack([b.shape.vertices for b in asm.blocks])
        camera = draw.Camera.for_assembly(asm, across=bool(np.abs(d[:, 1]).sum() > np.abs(d[:, 0]).sum()))
    ghost = draw.BlockArt.of(asm, camera, ghost=True)
    art = draw.BlockArt.of(asm, camera, verts=moved)
    both = np.vstack([ghost.points, art.points])
    lo, hi = both.min(axis=0) - 0.03 * asm.size, both.max(axis=0) + 0.03 * asm.size
    handles = [Patch(facecolor="none", edgecolor="#9a9a9a", linestyle="--", label="original position"),
               Patch(facecolor=draw.BLOCK_COLOUR, edgecolor=draw.EDGE_COLOUR, label="displaced block"),
               Line2D([], [], color=HINGE_COLOUR, linewidth=2.6, marker="o", markerfacecolor="white", label="hinge")]
    if planar and "interface_mode" in ds:
        modes = value(ds, "interface_mode", s0).astype(str)
        if ((modes == "hinge") & _ring_faces(ds, s0, len(modes))).any():
            handles.append(Line2D([], [], linestyle="none", **RING_HINGE,
                                  label="turn on a face between rings (the rings separate)"))
    width = 5.0
    lmax = float(value(ds, "lambda_max", s0))
    lam = f"λmax = {lmax:.3f}" if math.isfinite(lmax) else "the direct limit"
    drawn = list(drawn) if drawn is not None else scenarios(ds)
    who = "every scenario drawn" if len(names) > 1 and set(names) == set(drawn) else join_names(names, 4)
    title = (_wrap(f"collapse mechanism at {lam}, shared by {who}", width) +
             f"\n(exaggerated: largest displacement drawn {shown:.2f} m)")
    sheet = _Sheet(1, 1, lo, hi, width, 0.16 * (title.count("\n") + 1) + 0.1,
                   _legend_height([h.get_label() for h in handles], width), camera)
    off = sheet.offset(0, 0)
    ghost.draw(sheet.ax, off)
    art.draw(sheet.ax, off)
    _hinges(sheet.ax, ds, s0, asm, camera, planar=planar, offset=off)
    sheet.title(0, 0, title)
    sheet.fig.suptitle(f"{_study(ds)}: collapse mechanism", fontsize=FONT + 2, y=1 - 0.12 / sheet.height)
    _bottom_legend(sheet, handles)
    return sheet.fig


# ---------------------------------------------------------------------------- transversal shift (Figs. 5-6)
def transversal_offsets(ds: xr.Dataset, st: State, asm: Assembly, chain: Sequence[int],
                        across: NDArray[np.float64]) -> tuple[list[NDArray], NDArray, NDArray]:
    """The joints of ``chain`` in their own planes and where the resultant crosses each.

    Each joint is seen along its normal: screen ``u`` runs across the joint in the plane of
    the structure (``across x normal``), screen ``y`` across the depth (along ``across``),
    both from the joint's centroid (m).

    Returns
    -------
    outlines : list of (k, 2) arrays
        Each joint's polygon ``(u, y)``.
    points : (n, 2) array
        The pressure point ``(u, y)`` of each joint (NaN when the state has none).
    shift : (n,) array
        ``y / (d/2)``: the pressure point's distance from the middle of the depth over half
        the joint's depth (``±1`` at the faces).
    """
    pp = np.asarray(value(ds, "pressure_point", st.scenario, ["step", "interface", "xyz"]), float)[st.step]
    outlines, points, shift = [], [], []
    for k in chain:
        itf = asm.interfaces[k]
        u = np.cross(across, itf.normal)
        u /= np.linalg.norm(u)
        c = itf.centroid
        poly = np.column_stack([(itf.points - c) @ u, (itf.points - c) @ across])
        lo, hi = poly[:, 1].min(), poly[:, 1].max()
        p = np.array([(pp[k] - c) @ u, (pp[k] - c) @ across])
        outlines.append(poly)
        points.append(p)
        shift.append((p[1] - 0.5 * (lo + hi)) / (0.5 * (hi - lo)))
    return outlines, np.array(points), np.array(shift)


def transversal_figure(ds: xr.Dataset, names: Sequence[str], targets: Sequence[object]) -> Figure:
    """The transversal (out-of-plane) shift of the pressure points along a line of blocks (Figs. 5-6).

    Top: one row per drawn state (``targets``: multipliers or ``"max"``), every joint seen
    along its normal (:func:`transversal_offsets`), to scale and side by side from the first
    support, with the pressure point and the middle of the depth dashed. Bottom: ``y/(d/2)``
    against the joint (``±1``: the faces), its extreme value in the legend.

    Returns
    -------
    Figure
        Pressure points in the joint rows (gid ``"transversal:<scenario>:<lambda>"``) and
        the curves of the bottom panel (gid ``"shift:<scenario>:<lambda>"``).

        When no drawn state has a solved step (every step unbounded, infeasible or
        numerical), a figure of words only: each state's note.

    Raises
    ------
    ValueError
        The structure is not one line of blocks, or its supports do not lie on a line.
    """
    names = list(names)
    asm = one_geometry(ds, names)
    chain = chain_interfaces(asm)
    frame = structure_frame(asm)
    if chain is None or frame.kind == "radial":
        raise ValueError("the transversal shift needs one line of blocks on supports along a line")
    across = next(iter(frame.across.values()))
    asked = [find_state(ds, s, t) for s in names for t in targets]
    states = [st for st in asked if st.step is not None]
    if not states:  # every step unbounded, infeasible or numerical: say so
        return _notes_figure(f"{_study(ds)}: transversal shift of the pressure points: no state drawn",
                             [f"{st.scenario}: {st.label}: {st.note}" for st in asked])
    drawn = [(st, *transversal_offsets(ds, st, asm, chain, across)) for st in states]
    pitch = 1.6 * max(float(np.ptp(o[:, 0])) for o in drawn[0][1])
    depth = max(float(np.ptp(o[:, 1])) for o in drawn[0][1])
    n = len(chain)
    inch = min(10.0 / (n * pitch), 1.1 / depth)  # inches per metre in the joint rows
    row_h = 1.24 * depth * inch + 0.35
    colours = _palette(len(drawn))
    width = max(n * pitch * inch + 1.4, 7.0)
    handles = [Line2D([], [], color=colours[i], marker=MARKERS[i % len(MARKERS)], linewidth=1.2, markersize=4,
                      label=f"{st.scenario}: {st.label}, max |y|/(d/2) = {np.nanmax(np.abs(sh)):.2f}")
               for i, (st, _, _, sh) in enumerate(drawn)]
    below = _legend_height([h.get_label() for h in handles], width)
    plot_h = 2.4
    height = 0.7 + len(drawn) * row_h + 0.55 + plot_h + 0.5 + below
    fig = Figure(figsize=(width, height))
    top = height - 0.7
    for i, (st, outlines, points, shift) in enumerate(drawn):
        y0 = top - (i + 1) * row_h
        ax = fig.add_axes((0.7 / width, y0 / height, n * pitch * inch / width, (row_h - 0.3) / height))
        ax.set_axis_off()
        placed = [poly + [j * pitch, 0.0] for j, poly in enumerate(outlines)]  # side by side, to scale
        ax.add_collection(PolyCollection(placed, closed=True, facecolors=draw.BLOCK_COLOUR,
                                         edgecolors=draw.EDGE_COLOUR, linewidths=0.5))
        ax.add_collection(LineCollection([[(p[:, 0].min(), 0.0), (p[:, 0].max(), 0.0)] for p in placed],
                                         colors="#777777", linewidths=0.5, linestyles="--"))
        xs = np.arange(n) * pitch + points[:, 0]
        ax.plot(xs, points[:, 1], linestyle="none", marker=MARKERS[i % len(MARKERS)], markersize=4,
                color=colours[i], zorder=5, clip_on=False, gid=f"transversal:{st.scenario}:{st.lam:g}")
        ax.set_xlim(-0.5 * pitch, (n - 0.5) * pitch)
        ax.set_ylim(-0.62 * depth, 0.62 * depth)
        ax.set_aspect("equal")
        ax.text(-0.5 * pitch, 0.62 * depth, f"{st.scenario}: {st.label}", fontsize=FONT,
                color=colours[i], va="bottom", ha="left")
    ax = fig.add_axes((0.7 / width, (0.5 + below) / height, n * pitch * inch / width, plot_h / height))
    joints = np.arange(1, n + 1)
    for i, (st, _, _, shift) in enumerate(drawn):
        ax.plot(joints, shift, color=colours[i], marker=MARKERS[i % len(MARKERS)], markersize=4, linewidth=1.2,
                gid=f"shift:{st.scenario}:{st.lam:g}")
    for y in (-1.0, 1.0):
        ax.axhline(y, color="#555555", linewidth=0.8, linestyle="--")
    ax.axhline(0.0, color="#999999", linewidth=0.5)
    ax.set_ylim(-1.15, 1.15)
    ax.set_xlim(0.5, n + 0.5)
    ax.set_xticks(joints)
    ax.tick_params(labelsize=FONT - 0.5)
    ax.set_xlabel("joint, from the first support", fontsize=FONT)
    k = int(np.argmax(np.abs(across)))
    towards = f"{'+' if across[k] > 0 else '-'}{'xyz'[k]}" if abs(abs(across[k]) - 1) < 1e-9 else "the across axis"
    ax.set_ylabel(f"y/(d/2): pressure point across the depth\n(±1: the faces; + towards {towards})", fontsize=FONT)
    ax.grid(True, linewidth=0.3, alpha=0.6)
    fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.04 / height),
               ncols=_legend_rows([h.get_label() for h in handles], width)[0], fontsize=FONT, frameon=False)
    fig.suptitle(f"{_study(ds)}: transversal shift of the pressure points", fontsize=FONT + 2, y=1 - 0.12 / height)
    fig.text(0.5, 1 - 0.36 / height, f"each joint seen along its normal, to scale (1 m = {inch:.3g} in): across the "
             "joint in the plane of the structure (horizontal) and across the depth (vertical; dashed: mid-depth)",
             ha="center", va="top", fontsize=FONT)
    return fig


# ---------------------------------------------------------------------------- sweeps
def summary_figure(ds: xr.Dataset) -> Figure:
    """lambda_max against each swept parameter, one row per settlement case.

    In the panel of parameter ``p``, one line per combination of the other swept
    parameters; identical lines, and settlement cases with identical answers, are drawn once
    and named together. A :data:`CATEGORICAL` parameter is drawn as points. The axis starts
    at 0, so that solver noise (1e-12) draws flat. Scenarios whose outcome is not ``limit``
    are markers at the foot of the panel, one shape per outcome.

    Raises
    ------
    ValueError
        Nothing is swept.
    """
    params = swept_parameters(ds)
    if not params:
        raise ValueError("nothing is swept: the summary needs a swept parameter")
    names = scenarios(ds)
    case = {s: (str(value(ds, "settlement", s)) if "settlement" in ds.coords else "") for s in names}
    lmax = {s: float(value(ds, "lambda_max", s)) for s in names}
    outcome = {s: text(ds, "outcome", s, "limit") for s in names}
    par = {s: {p: float(value(ds, p, s)) for p in params} for s in names}
    cases = list(dict.fromkeys(case.values()))
    # cases with identical answers for every parameter set share a row
    sig = {c: tuple(sorted((tuple(par[s][p] for p in params), round(lmax[s], 9) if math.isfinite(lmax[s]) else outcome[s])
                           for s in names if case[s] == c)) for c in cases}
    rows = [[cases[i] for i in g] for g in groups_of(cases, lambda a, b: sig[a] == sig[b])]
    w, h = 3.4, 2.3
    legends = len(params) > 1 or any(o != "limit" for o in outcome.values())  # else no room kept for one
    grid = _Grid(len(rows), len(params), w, h, left=0.75, right=2.3 if legends else 0.3,
                 wspace=2.6 if legends else 0.8, hspace=0.85, top=0.75, bottom=0.5)
    for r, row in enumerate(rows):
        for c, p in enumerate(params):
            ax = grid.axes[r][c]
            others = [q for q in params if q != p]
            lines: dict[tuple, list[str]] = {}
            for s in names:
                if case[s] == row[0]:
                    lines.setdefault(tuple(par[s][q] for q in others), []).append(s)
            keys = list(lines)
            curves = []
            for key in keys:
                ss = sorted(lines[key], key=lambda s: par[s][p])
                curves.append((np.array([par[s][p] for s in ss]), np.array([lmax[s] for s in ss])))
            groups = group_identical(curves, atol=1e-9)
            palette = _palette(len(groups))
            categorical = p in CATEGORICAL  # directions are cases, not a scale: points, no line between them
            bad: dict[str, str] = {}  # outcome -> marker
            for g, members in enumerate(groups):
                x, y = curves[members[0]]
                label = _combo_label(others, [keys[i] for i in members])
                ax.plot(x, y, color=palette[g], linestyle="none" if categorical else LINESTYLES[g % len(LINESTYLES)],
                        marker=MARKERS[g % len(MARKERS)] if categorical else "o", markersize=5 if categorical else 3.5,
                        linewidth=1.2, label=label, gid=f"summary:{p}:{g}")
                for xv, yv in zip(x, y) if categorical and len(groups) <= 3 else ():  # the value, above its point
                    if math.isfinite(yv):
                        ax.annotate(f"{yv:.4g}", (xv, yv), xytext=(0, 5 + 9 * g), textcoords="offset points",
                                    ha="center", va="bottom", fontsize=FONT - 1, color=palette[g])
                for i in members:  # a scenario without a limit: its curve's colour, at the foot of the panel
                    for s in lines[keys[i]]:
                        if outcome[s] != "limit":
                            mark = bad.setdefault(outcome[s], "xv+^"[len(bad) % 4])
                            ax.plot([par[s][p]], [0.03], transform=ax.get_xaxis_transform(), linestyle="none",
                                    marker=mark, markersize=6, color=palette[g], clip_on=False,
                                    gid=f"no_limit:{p}:{g}")
            for o, mark in bad.items():
                ax.plot([], [], linestyle="none", marker=mark, markersize=6, color="#555555",
                        label=f"{o}: no λmax\n(at the foot; the curve's colour)")
            finite = [v for v in lmax.values() if math.isfinite(v)]  # from 0: differences read against the value
            ax.set_ylim(0.0, 1.15 * max(finite) if finite and max(finite) > 0 else 1.0)
            if categorical:
                ticks = sorted({par[s][p] for s in names})
                ax.set_xticks(ticks, [f"{v:g}" for v in ticks])
                pad = 0.25 * (ticks[-1] - ticks[0]) if len(ticks) > 1 else 1.0
                ax.set_xlim(ticks[0] - pad, ticks[-1] + pad)
            what = "cases, not joined" if categorical else "points: scenarios"
            ax.set_xlabel(f"{p} ({SWEPT[p]}); {what}", fontsize=FONT)
            ax.set_ylabel("λmax (–)", fontsize=FONT)
            ax.grid(True, linewidth=0.3, alpha=0.6)
            ax.set_title(_wrap("settlement: " + join_names(row, 6), w), fontsize=FONT - 0.5, loc="left", y=1.0)
            if others or bad:
                ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=FONT - 1, frameon=False,
                          title=", ".join(others) if others else None, title_fontsize=FONT - 1)
    grid.fig.suptitle(f"{_study(ds)}: λmax of {len(names)} scenarios", fontsize=FONT + 2, y=1 - 0.18 / grid.height)
    return grid.fig


def _combo_label(others: Sequence[str], keys: Sequence[tuple]) -> str:
    """Legend text of one line standing for the parameter sets ``keys``."""
    if not others:
        return "λmax"
    if len(keys) == 1:
        return ", ".join(f"{v:g}" for v in keys[0])
    if len(others) == 1:
        vals = sorted(k[0] for k in keys)
        listed = ", ".join(f"{v:g}" for v in vals) if len(vals) <= 4 else f"{vals[0]:g} … {vals[-1]:g}"
        return f"{listed} ({len(vals)}, identical)"
    return f"{len(keys)} sets, identical"
