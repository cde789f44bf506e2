"""Interactive 3D view of a results dataset: one self-contained HTML file that works offline.

:func:`view_html` returns an HTML page with plotly.js inlined (from the installed ``plotly``
package; no network) and the figure as data: the blocks (a shaded
mesh with edges), the interface resultants centred on their pressure points (hover for the
interface, the force and the torque), the torques about the interface normals (arcs), the
loads (self-weight and lateral load lambda W at each block centroid, declared loads, live
ones times lambda) and the collapse mechanism (displaced edges and hinge lines). A scenario
selector and a slider over the optimal steps choose the state; the caption gives lambda,
the status and the notes (non-unique state, outcome other than ``limit``). All forces share
one arrow scale, stated on the page.
"""

from __future__ import annotations

import html
import importlib.util
import json
import math
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from . import draw
from ..structures.assembly import Assembly
from ..structures.geometry import lateral_direction
from .data import (
    NOT_UNIQUE, assembly, block_rows, geometry, hinge_segments, optimal_steps, outcome_note, scenarios, value,
)
from .figures import TORQUE_TOL, arrow_scales, displaced
from .load_arrows import declared_loads

__all__ = ["plotly_js", "view_html"]

DIGITS = 5  # coordinates rounded to 10 micrometres in the page


@lru_cache(maxsize=1)
def plotly_js() -> bytes:
    """The minified plotly.js of the installed ``plotly`` package (UTF-8 bytes, read once).

    Raises
    ------
    RuntimeError
        The ``plotly`` package (a dependency of tce) is not installed.
    """
    spec = importlib.util.find_spec("plotly")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError("the interactive view needs the plotly package: pip install plotly")
    path = Path(next(iter(spec.submodule_search_locations))) / "package_data" / "plotly.min.js"
    return path.read_bytes()


def _lines(segments: Sequence[NDArray[np.float64]] | NDArray[np.float64]) -> dict[str, list]:
    """Polylines as one plotly line trace's ``x, y, z`` (``None`` between polylines).

    ``segments`` is a sequence of ``(k, 3)`` polylines, or one ``(m, 3)`` array whose NaN
    rows already separate them.
    """
    if isinstance(segments, np.ndarray):
        pts = segments
    elif len(segments):
        gap = np.full((1, 3), np.nan)
        pts = np.concatenate([part for seg in segments for part in (np.asarray(seg, float).reshape(-1, 3), gap)])
    else:
        pts = np.empty((0, 3))
    return {k: [None if v != v else v for v in col] for k, col in zip("xyz", np.round(pts, DIGITS).T.tolist())}


def _arrow_polylines(start: NDArray[np.float64], end: NDArray[np.float64], head: float) -> NDArray[np.float64]:
    """Shaft and a wire-cone head (four lines from the tip) of each arrow, as one ``(15 n, 3)``
    array: 15 rows per arrow, NaN rows between the lines (all NaN for an arrow of no length)."""
    start, end = np.asarray(start, float).reshape(-1, 3), np.asarray(end, float).reshape(-1, 3)
    d = end - start
    n = np.linalg.norm(d, axis=1)
    keep = np.isfinite(n) & (n > 1e-12)
    u = np.where(keep[:, None], d, [[0.0, 0.0, 1.0]]) / np.where(keep, n, 1.0)[:, None]
    ref = np.where(np.abs(u[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    p = np.cross(u, ref)
    p /= np.linalg.norm(p, axis=1)[:, None]
    q = np.cross(u, p)
    h = np.minimum(head, 0.4 * np.where(keep, n, 0.0))[:, None]
    back = end - h * u
    gap = np.full_like(start, np.nan)
    rows = [start, end, gap]
    for v in (p, q, -p, -q):
        rows += [end, back + 0.35 * h * v, gap]
    out = np.stack(rows, axis=1)
    out[~keep] = np.nan
    return out.reshape(-1, 3)


def _mesh(asm: Assembly) -> tuple[dict, dict]:
    """The blocks as one Mesh3d (fan-triangulated faces, supports grey) and their edges."""
    x, i, j, k, colours, edges = [], [], [], [], [], []
    for b in asm.blocks:
        base = len(x)
        x += np.round(b.shape.vertices, DIGITS).tolist()
        colour = draw.SUPPORT_COLOUR if b.support else draw.BLOCK_COLOUR
        for face in b.shape.faces:
            for m in range(1, len(face) - 1):
                i.append(base + face[0])
                j.append(base + face[m])
                k.append(base + face[m + 1])
                colours.append(colour)
            edges.append(b.shape.vertices[list(face) + [face[0]]])
    v = np.array(x)
    mesh = dict(type="mesh3d", x=v[:, 0].tolist(), y=v[:, 1].tolist(), z=v[:, 2].tolist(), i=i, j=j, k=k,
                facecolor=colours, opacity=0.45, flatshading=True, name="blocks", showlegend=True, hoverinfo="skip")
    return mesh, dict(type="scatter3d", mode="lines", name="block edges", line=dict(color="#4a4a4a", width=2),
                      hoverinfo="skip", showlegend=False, **_lines(edges))


def _scales(ds: xr.Dataset, names: Sequence[str], size: float) -> tuple[float, float]:
    """One arrow scale (m per kN) and one torque scale (m per kN m) for every state shown."""
    fmax = tmax = 0.0
    for s in names:
        ok = optimal_steps(ds, s)
        if not ok.size:
            continue
        res = np.asarray(value(ds, "resultant", s, ["step", "interface", "xyz"]), float)[ok]
        tq = np.asarray(value(ds, "torque", s, ["step", "interface"]), float)[ok]
        fmax = max(fmax, float(np.nanmax(np.linalg.norm(res, axis=-1), initial=0.0)))
        tmax = max(tmax, float(np.nanmax(np.abs(tq), initial=0.0)))
    return arrow_scales(fmax, tmax, size)


def _split(rows: NDArray[np.float64], counts: NDArray[np.int64], per: int) -> list[dict[str, list]]:
    """Cut the polyline rows of consecutive groups (``counts`` items of ``per`` rows each)
    into one trace each."""
    edges = np.concatenate([[0], np.cumsum(counts * per)])
    return [_lines(rows[edges[k]:edges[k + 1]]) for k in range(len(counts))]


def _states(pp: NDArray, res: NDArray, tq: NDArray, lam: NDArray, itf_names: list[str], normals: NDArray,
            centres: NDArray, weights: NDArray, alpha: float, force: float, torque: float, tol: float,
            head: float, declared: tuple[NDArray, NDArray, NDArray] | None = None) -> list[dict]:
    """Dynamic traces of the steps ``(k, ...)`` of one scenario: resultants, pressure points,
    torques, lateral loads (computed for all steps at once, then cut per step)."""
    ok = np.all(np.isfinite(pp), axis=2) & np.all(np.isfinite(res), axis=2)
    vec = res[ok] * force
    arrows = _split(_arrow_polylines(pp[ok] - 0.5 * vec, pp[ok] + 0.5 * vec, head),
                    ok.sum(axis=1), 15)
    # loads at each step: the lateral lambda W at the block centroids (when the pattern has a
    # lateral part), then the declared loads (live ones x lambda), each ending where it acts
    direction = lateral_direction(alpha) if np.isfinite(alpha) else np.zeros(3)
    lateral = lam[:, None, None] * weights[None, :, None] * direction[None, None, :] * force
    starts = np.broadcast_to(centres, lateral.shape)
    ends = starts + lateral
    if declared is not None:
        p, f, flag = declared
        f_k = np.where(flag[None, :, None], lam[:, None, None] * f[None], f[None]) * force
        starts = np.concatenate([starts, np.broadcast_to(p, f_k.shape) - f_k], axis=1)
        ends = np.concatenate([ends, np.broadcast_to(p, f_k.shape)], axis=1)
    live = (np.linalg.norm(ends - starts, axis=2) > 0) & (force > 0)
    loads = _split(_arrow_polylines(starts[live], ends[live], head), live.sum(axis=1), 15)
    sig = ok & np.isfinite(tq) & (np.abs(np.nan_to_num(tq)) > tol)
    norm = np.linalg.norm(np.nan_to_num(res), axis=2)
    out = []
    for k in range(len(lam)):
        arcs = draw.torque_arcs(pp[k][sig[k]], normals[sig[k]], tq[k][sig[k]], torque) if torque > 0 else []
        hover = [f"{itf_names[m]}<br>R = ({res[k, m, 0]:.4g}, {res[k, m, 1]:.4g}, {res[k, m, 2]:.4g}) kN, "
                 f"|R| = {norm[k, m]:.4g} kN<br>torque {tq[k, m]:.3g} kN m" for m in np.flatnonzero(ok[k])]
        p = np.round(pp[k][ok[k]], DIGITS)
        out.append(dict(lam=float(lam[k]), res=arrows[k], tq=_lines(arcs), lat=loads[k],
                        pts=dict(x=p[:, 0].tolist(), y=p[:, 1].tolist(), z=p[:, 2].tolist(), text=hover)))
    return out


def _mechanism(ds: xr.Dataset, s: str) -> dict:
    """Displaced block edges (exaggerated as in :func:`tce.plot.figures.mechanism_view`) and hinges."""
    asm = assembly(ds, s)
    if "mechanism" not in ds:
        return dict(edges=_lines([]), hinges=_lines([]), text="")
    vel = block_rows(ds, "mechanism", s, asm)
    if not (np.all(np.isfinite(vel)) and np.any(vel)):
        return dict(edges=_lines([]), hinges=_lines([]), text="no collapse mechanism")
    moved, shown = displaced(asm, vel)
    edges = [v[list(f) + [f[0]]] for b, v in zip(asm.blocks, moved) for f in b.shape.faces]
    return dict(edges=_lines(edges), hinges=_lines(list(hinge_segments(ds, s, asm))),
                text=f"mechanism exaggerated: largest displacement drawn {shown:.2f} m")


def _structure(asm: Assembly, force: float) -> dict:
    """What the page draws of one structure: its blocks, their edges and the self-weight arrows."""
    mesh, edges = _mesh(asm)
    free = list(asm.free_indices)
    centres, weights = asm.centroids[free], asm.weights[free]
    dead = _arrow_polylines(centres, centres - weights[:, None] * np.array([0, 0, 1.0]) * force, 0.03 * asm.size)
    return dict(mesh=mesh, edges=edges, dead=_lines(dead))


def view_data(ds: xr.Dataset, names: Sequence[str] | None = None) -> dict:
    """The data of the page, as plain JSON-able values: ``structures`` holds the blocks of each
    structure the scenarios were solved on, which each scenario's ``structure`` indexes."""
    names = list(names or scenarios(ds))
    asm0 = assembly(ds, names[0] if names else None)
    force, torque = _scales(ds, names, asm0.size)
    itf_names = [str(x) for x in ds["interface"].values]
    drawn: dict[int, int] = {}  # geometry of the dataset -> index in `structures`
    structures = []
    out = []
    for s in names:
        g = geometry(ds, s)
        asm = assembly(ds, s)
        if g not in drawn:
            drawn[g] = len(structures)
            structures.append(_structure(asm, force))
        normals = np.array([i.normal for i in asm.interfaces])
        free = list(asm.free_indices)
        centres, weights = asm.centroids[free], asm.weights[free]
        head = 0.03 * asm.size
        ok = optimal_steps(ds, s)
        pp = np.asarray(value(ds, "pressure_point", s, ["step", "interface", "xyz"]), float)
        res = np.asarray(value(ds, "resultant", s, ["step", "interface", "xyz"]), float)
        tq = np.asarray(value(ds, "torque", s, ["step", "interface"]), float)
        lam = np.asarray(value(ds, "lam", s), float)
        unique = np.asarray(value(ds, "unique", s), float) if "unique" in ds else np.full(len(lam), np.nan)
        alpha = float(value(ds, "alpha", s)) if "alpha" in ds.coords else 0.0
        fmax = float(np.nanmax(np.linalg.norm(res[ok], axis=-1), initial=0.0)) if ok.size else 0.0
        tol = TORQUE_TOL * fmax * asm.size
        outcome = outcome_note(ds, s)
        steps = _states(pp[ok], res[ok], tq[ok], lam[ok], itf_names, normals, centres, weights, alpha, force, torque,
                        tol, head, declared_loads(ds, s))
        for st, k in zip(steps, ok):
            st["note"] = "; ".join(n for n in (outcome, NOT_UNIQUE if unique[k] == 0.0 else "") if n)
        lmax = float(value(ds, "lambda_max", s))
        at_max = [n for n, st in enumerate(steps) if math.isfinite(lmax) and abs(st["lam"] - lmax) <= 1e-12]
        out.append(dict(name=s, structure=drawn[g], steps=steps, start=at_max[-1] if at_max else max(len(steps) - 1, 0),
                        lmax=lmax if math.isfinite(lmax) else None, outcome=outcome,
                        mechanism=_mechanism(ds, s)))
    return dict(title=str(ds.attrs.get("study_name", "")) or "tce results", structures=structures, scenarios=out,
                scale=f"arrows: 1 kN = {force:.3g} m" + (f"; torque arcs: radius 1 kN m = {torque:.3g} m" if torque
                                                          else ""))


_PAGE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}: tce view</title>
<style>
 body {{ font: 14px sans-serif; margin: 0; }}
 #bar {{ display: flex; flex-wrap: wrap; gap: 1em; align-items: center; padding: 6px 10px; background: #f3f0ea; }}
 #step {{ width: 22em; }}
 #note {{ color: #8a4b00; }}
 #plot {{ width: 100vw; height: calc(100vh - 90px); }}
</style>
<script>{plotly}</script>
</head><body>
<div id="bar">
 <b>{title}</b>
 <label>scenario <select id="scenario"></select></label>
 <label>load multiplier <input type="range" id="step" min="0" max="0" step="1" value="0"></label>
 <span id="lam"></span>
 <label><input type="checkbox" id="mech"> collapse mechanism (at λmax)</label>
 <span id="scale"></span>
 <span id="note"></span>
</div>
<div id="plot"></div>
<script type="application/json" id="data">{data}</script>
<script>
"use strict";
const D = JSON.parse(document.getElementById("data").textContent);
const sel = document.getElementById("scenario"), slider = document.getElementById("step");
const mech = document.getElementById("mech");
const line = (name, colour, width, legend) => ({{type: "scatter3d", mode: "lines", name: name,
  line: {{color: colour, width: width}}, hoverinfo: "skip", showlegend: legend, x: [], y: [], z: []}});
const S0 = D.structures[0];
const traces = [
  Object.assign({{}}, S0.mesh), Object.assign({{}}, S0.edges),
  line("interface resultant at pressure point", "#c0141e", 5, true),
  {{type: "scatter3d", mode: "markers", name: "pressure point", marker: {{size: 3, color: "#c0141e"}},
    hoverinfo: "text", text: [], x: [], y: [], z: []}},
  line("torque about the normal", "#000000", 3, true),
  line("live loads (lateral λ W, applied loads)", "#0072B2", 4, true),
  Object.assign(line("self-weight W", "#009E73", 3, true), S0.dead),
  line("collapse mechanism (exaggerated)", "#555555", 2, true),
  line("hinge", "#0072B2", 9, true),
];
const layout = {{margin: {{l: 0, r: 0, t: 10, b: 0}}, legend: {{x: 0, y: 1}},
  scene: {{aspectmode: "data", xaxis: {{title: {{text: "x (m)"}}}}, yaxis: {{title: {{text: "y (m)"}}}},
          zaxis: {{title: {{text: "z (m)"}}}}, camera: {{eye: {{x: 1.2, y: -2.2, z: 0.9}}}}}}}};
function state() {{
  const sc = D.scenarios[sel.value], st = sc.steps[slider.value];
  if (!st) {{
    document.getElementById("lam").textContent = "no state to show";
    document.getElementById("note").textContent = sc.outcome;
    Plotly.restyle("plot", {{x: [[], [], [], []], y: [[], [], [], []], z: [[], [], [], []]}}, [2, 3, 4, 5]);
    return;
  }}
  const atMax = sc.lmax !== null && Math.abs(st.lam - sc.lmax) <= 1e-12;
  document.getElementById("lam").textContent = "λ = " + st.lam.toFixed(4) + (atMax ? " = λmax" : "");
  document.getElementById("note").textContent = [st.note, mech.checked ? sc.mechanism.text : ""]
    .filter(Boolean).join("; ");
  Plotly.restyle("plot", {{x: [st.res.x, st.pts.x, st.tq.x, st.lat.x], y: [st.res.y, st.pts.y, st.tq.y, st.lat.y],
    z: [st.res.z, st.pts.z, st.tq.z, st.lat.z], text: [null, st.pts.text, null, null]}}, [2, 3, 4, 5]);
}}
function mechanism() {{
  const m = D.scenarios[sel.value].mechanism, on = mech.checked;
  Plotly.restyle("plot", {{x: [on ? m.edges.x : [], on ? m.hinges.x : []], y: [on ? m.edges.y : [],
    on ? m.hinges.y : []], z: [on ? m.edges.z : [], on ? m.hinges.z : []]}}, [7, 8]);
  state();
}}
function scenario() {{
  const sc = D.scenarios[sel.value], g = D.structures[sc.structure];
  // each scenario on its own blocks (a geometry sweep solves each on another structure)
  Plotly.restyle("plot", {{x: [g.mesh.x], y: [g.mesh.y], z: [g.mesh.z], i: [g.mesh.i], j: [g.mesh.j],
    k: [g.mesh.k], facecolor: [g.mesh.facecolor]}}, [0]);
  Plotly.restyle("plot", {{x: [g.edges.x, g.dead.x], y: [g.edges.y, g.dead.y], z: [g.edges.z, g.dead.z]}}, [1, 6]);
  slider.max = Math.max(sc.steps.length - 1, 0);
  slider.value = sc.start;
  mechanism();
}}
D.scenarios.forEach((sc, k) => sel.add(new Option(sc.name, k)));
document.getElementById("scale").textContent = D.scale;
Plotly.newPlot("plot", traces, layout, {{responsive: true, displaylogo: false}}).then(scenario);
sel.addEventListener("change", scenario);
slider.addEventListener("input", state);
mech.addEventListener("change", mechanism);
</script>
</body></html>
"""


def view_html(ds: xr.Dataset, names: Sequence[str] | None = None) -> bytes:
    """The interactive view of ``names`` (default: every scenario) as one HTML page.

    Parameters
    ----------
    ds : xarray.Dataset
    names : sequence of str, optional

    Returns
    -------
    bytes
        A self-contained page (plotly.js inlined, data as JSON), UTF-8, a few MB; built as
        bytes around plotly.js as read, since a text page would copy it twice.
    """
    data = json.dumps(view_data(ds, names), separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
    title = html.escape(str(ds.attrs.get("study_name", "")) or "tce results")
    head, tail = _PAGE.split("{plotly}")
    return b"".join([head.format(title=title, data=data).encode("utf-8"), plotly_js(),
                     tail.format(title=title, data=data).encode("utf-8")])
