"""What the figures, the interactive view and the VTK export read from a results dataset.

Everything here reads a results dataset (``docs/results.md``) and returns plain numbers,
arrays and strings; nothing draws. The geometry comes from the attr ``assembly`` (or
``assembly_<k>`` for geometry k) and the drawing choices from the ``[plots]`` table of the
study text ``ds.attrs["study"]``, so a results file copied anywhere redraws the same figures.

Conventions
-----------
- Units as in the dataset: m, kN, kN m; lambda is dimensionless.
- **Forces on the supports.** The figures plot the force and moment each support
  *receives from the structure* (the paper's "thrust exerted on the supports"), i.e. minus
  the dataset's ``reaction``, in the frame of the structure (:class:`StructureFrame`):
  ``H`` along the span (positive when it pushes the support outward), ``S`` across the
  span, ``V`` vertical (positive downward: the load on the support) and ``M`` the moment
  about the span axis (right-hand rule), about the support centroid.
- A drawn **state** is one step of one scenario, asked for by load multiplier or
  ``"max"`` (:func:`find_state`); two multipliers are the same step within
  :data:`tce.study.names.LAMBDA_TOL`.
"""

from __future__ import annotations

import json
import math
import tomllib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from ..structures.assembly import Assembly
from ..study.outcomes import outcome_words, status_words
from ..study.names import PLOT_KINDS, same_lambda, slug

__all__ = [
    "PlotSpec",
    "PlotSpecError",
    "State",
    "StructureFrame",
    "CAPACITY_WORDS",
    "SAMPLE_WORDS",
    "UNCERTAINTY_KINDS",
    "assembly",
    "capacity_label",
    "chain_interfaces",
    "counts_note",
    "dominant_variable",
    "find_state",
    "geometry",
    "geometry_groups",
    "group_identical",
    "groups_of",
    "has_uncertainty",
    "hinge_segments",
    "join_names",
    "mechanism_groups",
    "one_geometry",
    "optimal_steps",
    "outcome_note",
    "plot_spec",
    "sample_counts",
    "scenarios",
    "settlement_parameter",
    "slug",
    "state_pages",
    "structure_frame",
    "study_cap",
    "support_forces",
    "sweep_axes",
    "swept_parameters",
    "uncertainty_variables",
    "unique_note",
]

Target = float | str  # a load multiplier or "max"

#: swept coordinates that may lie along ``scenario``, in the order studies expand them, with units
SWEPT = {"alpha": "degree", "friction": "–", "cohesion": "kN/m²", "tensile_strength": "kN/m²",
         "compressive_strength": "kN/m²", "magnitude": "× the settlements", "inner_radius": "m", "thickness": "m",
         "depth": "m", "radius": "m"}
#: figure kinds drawn by default (``base`` is asked for by name; those of :data:`UNCERTAINTY_KINDS`
#: where the results hold samples)
DEFAULT_KINDS = tuple(k for k in PLOT_KINDS if k != "base")
#: the figures of an ``[uncertainty]`` study (:mod:`tce.plot.uncertainty`)
UNCERTAINTY_KINDS = ("fragility", "capacity_samples", "sensitivity", "convergence")

#: note of a state flagged non-unique (``unique == 0``)
NOT_UNIQUE = "not unique: of the many optimal states, the canonical one (least unit-stiffness energy) is drawn"


# ---------------------------------------------------------------------------- dataset access
@lru_cache(maxsize=8)
def _assembly_from_json(text: str) -> Assembly:
    return Assembly.from_dict(json.loads(text))


def geometry(ds: xr.Dataset, scenario: str | None = None) -> int:
    """Index of the structure a scenario was solved on (0 without a ``geometry`` variable)."""
    if scenario is None or "geometry" not in ds:
        return 0
    return int(value(ds, "geometry", scenario))


def assembly(ds: xr.Dataset, scenario: str | None = None) -> Assembly:
    """The assembly a scenario was solved on (default: the first scenario's), parsed once
    per text."""
    k = geometry(ds, scenario)
    key = "assembly" if k == 0 else f"assembly_{k}"
    try:
        data = ds.attrs[key]
    except KeyError:
        raise ValueError(f"the dataset has no {key!r} attribute: geometry cannot be drawn") from None
    return _assembly_from_json(data if isinstance(data, str) else json.dumps(data))


def geometry_groups(ds: xr.Dataset, names: Sequence[str]) -> list[list[str]]:
    """``names`` split into groups solved on the same structure, in order of first appearance
    (a figure draws one structure)."""
    groups: dict[int, list[str]] = {}
    for s in names:
        groups.setdefault(geometry(ds, s), []).append(s)
    return list(groups.values())


def one_geometry(ds: xr.Dataset, names: Sequence[str]) -> Assembly:
    """The one structure the scenarios ``names`` were solved on.

    Raises
    ------
    ValueError
        They were solved on different structures (draw each of :func:`geometry_groups`).
    """
    groups = geometry_groups(ds, names)
    if len(groups) > 1:
        raise ValueError(
            f"the scenarios {list(names)} were solved on {len(groups)} different structures: draw each group "
            f"of geometry_groups() on its own blocks"
        )
    return assembly(ds, names[0] if names else None)


def scenarios(ds: xr.Dataset) -> list[str]:
    """Scenario names in dataset order."""
    return [str(s) for s in ds["scenario"].values]


def value(ds: xr.Dataset, name: str, scenario: str, dims: Sequence[str] | None = None) -> NDArray:
    """``ds[name]`` of the scenario labelled ``scenario`` as an ndarray, its other dimensions
    in the order ``dims`` (default: their stored order)."""
    one = ds[name].sel(scenario=scenario)
    return (one if dims is None else one.transpose(*dims)).values


def block_rows(ds: xr.Dataset, name: str, scenario: str, asm: Assembly) -> NDArray[np.float64]:
    """``ds[name]`` (dimensions ``scenario, block, ...``) of one scenario, a row per block of
    ``asm`` in its order (KeyError for a block ``ds`` does not hold)."""
    rows = ds[name].sel(scenario=scenario, block=list(asm.names))
    return np.asarray(rows.transpose("block", ...).values, float)


def text(ds: xr.Dataset, name: str, scenario: str, default: str = "") -> str:
    """A per-scenario string variable (``default`` when absent)."""
    return str(value(ds, name, scenario)) if name in ds else default


def is_planar(ds: xr.Dataset, scenario: str) -> bool:
    """True when the scenario ran on the planar model."""
    return text(ds, "model", scenario) == "planar"


def optimal_steps(ds: xr.Dataset, scenario: str) -> NDArray[np.int64]:
    """Indices of the optimal steps of a scenario, sorted by lambda."""
    lam = value(ds, "lam", scenario).astype(float)
    ok = np.flatnonzero((value(ds, "status", scenario).astype(str) == "optimal") & np.isfinite(lam))
    return ok[np.argsort(lam[ok], kind="stable")]


def swept_parameters(ds: xr.Dataset, names: Sequence[str] | None = None) -> list[str]:
    """Swept coordinates along ``scenario`` that take more than one value among ``names``."""
    out = []
    for p in SWEPT:
        if p in ds.coords and ds[p].dims == ("scenario",):
            v = np.asarray((ds[p] if names is None else ds[p].sel(scenario=list(names))).values, dtype=float)
            if len({round(x, 12) if math.isfinite(x) else "nan" for x in v}) > 1:
                out.append(p)
    return out


# ---------------------------------------------------------------------------- what to draw
class PlotSpecError(ValueError):
    """A ``[plots]`` value (or its replacement) that cannot be drawn; ``key`` names it."""

    def __init__(self, key: str, message: str) -> None:
        super().__init__(f"{key}: {message}")
        self.key = key
        self.message = message


@dataclass(frozen=True)
class PlotSpec:
    """What a results file draws: states, scenarios and kinds (the study's ``[plots]``).

    Attributes
    ----------
    steps : tuple
        Load multipliers and ``"max"``.
    scenarios : tuple of str
        Scenarios drawn in the per-scenario figures, the thrust curves and the view.
    kinds : tuple of str
        Figure kinds (:data:`tce.study.names.PLOT_KINDS`).
    """

    steps: tuple[Target, ...]
    scenarios: tuple[str, ...]
    kinds: tuple[str, ...]


def plot_spec(
    ds: xr.Dataset,
    steps: Sequence[Target] | None = None,
    scenarios_: Sequence[str] | None = None,
    kinds: Sequence[str] | None = None,
) -> PlotSpec:
    """The study's ``[plots]`` table, with any of its keys replaced by the arguments.

    Parameters
    ----------
    ds : xarray.Dataset
        Its ``study`` attr holds the study text (absent or without ``[plots]``: defaults).
    steps, scenarios_, kinds : sequence, optional
        Replace ``[plots] steps``, ``scenarios`` (names or shell patterns), ``kinds``.

    Raises
    ------
    PlotSpecError
        A value is invalid or a scenario entry matches no scenario; ``key`` names the key.
    """
    table = {}
    if ds.attrs.get("study"):
        try:
            table = dict(tomllib.loads(str(ds.attrs["study"])).get("plots", {}))
        except tomllib.TOMLDecodeError:
            table = {}
    for key, given in (("steps", steps), ("scenarios", scenarios_), ("kinds", kinds)):
        if given is not None:
            table[key] = list(given)
    from pydantic import ValidationError

    from ..study.sections import PlotsSection  # pydantic: imported where a spec is made

    try:
        section = PlotsSection.model_validate(table)
    except ValidationError as exc:
        err = exc.errors()[0]
        key = str(err["loc"][0]) if err["loc"] else "plots"
        raise PlotSpecError(key, f"{err['msg']} (got {err.get('input')!r})") from None
    names = scenarios(ds)
    bad = section.unmatched(names)
    if bad:
        raise PlotSpecError("scenarios", f"no scenario named {bad[0]!r}; use one of {names[:8]}"
                            f"{' ...' if len(names) > 8 else ''}")
    drawn = section.select(names)
    if section.scenarios is None and "load_x" in ds.coords:  # a load-position sweep: its critical positions
        from ..study.positions import critical_positions  # the solvers: imported for a load-position sweep only

        chosen = {c.scenario or c.scenarios[0] for c in critical_positions(ds)}  # no finite limit: the first
        drawn = [s for s in names if s in chosen]
    return PlotSpec(
        steps=tuple(section.steps),
        scenarios=tuple(drawn),
        kinds=tuple(section.kinds
                    or (k for k in DEFAULT_KINDS if k not in UNCERTAINTY_KINDS or has_uncertainty(ds))),
    )


@dataclass(frozen=True)
class State:
    """One drawn state: the step of ``scenario`` asked for by ``target``.

    Attributes
    ----------
    scenario : str
    target : float or "max"
    step : int or None
        Index along ``step`` of an optimal step; None when there is no admissible state
        to draw (``note`` says why).
    lam : float
        Multiplier of the state (NaN when ``step`` is None and ``target`` is ``"max"``).
    note : str
        Why nothing is drawn, or what to know about what is (non-unique, outcome).
    """

    scenario: str
    target: Target
    step: int | None
    lam: float
    note: str = ""

    @property
    def label(self) -> str:
        """``λ = 0.100`` (``= λmax`` at the limit)."""
        if not math.isfinite(self.lam):
            return "λmax"
        return f"λ = {self.lam:.3f}" + (" = λmax" if self.target == "max" else "")


def find_state(ds: xr.Dataset, scenario: str, target: Target) -> State:
    """The step of ``scenario`` at multiplier ``target`` (or at lambda_max for ``"max"``).

    ``"max"`` is the optimal step at ``lambda_max`` (without a limit: the last optimal step).
    A multiplier that was not solved, whose step is not optimal or that lies above the
    smallest one found inadmissible gives a state without a step, its note saying why.
    """
    lam = value(ds, "lam", scenario).astype(float)
    status = value(ds, "status", scenario).astype(str)
    ok = optimal_steps(ds, scenario)
    outcome = text(ds, "outcome", scenario, "limit")
    lmax = float(value(ds, "lambda_max", scenario))
    if target == "max":
        if math.isfinite(lmax):
            at = [k for k in ok if same_lambda(lam[k], lmax)]
            if at:
                return State(scenario, target, int(at[-1]), float(lam[at[-1]]), _notes(ds, scenario, at[-1]))
        if outcome in ("no_limit", "capped") and ok.size:
            k = int(ok[-1])
            return State(scenario, float(lam[k]), k, float(lam[k]), _notes(ds, scenario, k))
        return State(scenario, target, None, float("nan"), outcome_note(ds, scenario) or "no λmax")
    target = float(target)
    hits = [k for k in range(len(lam)) if math.isfinite(lam[k]) and same_lambda(lam[k], target)]
    if hits:
        k = hits[0]
        if status[k] == "optimal":
            return State(scenario, target, k, float(lam[k]), _notes(ds, scenario, k))
        return State(scenario, target, None, target, status_words(status[k], lam="λ", at=target))
    upper = float(value(ds, "lambda_upper", scenario)) if "lambda_upper" in ds else float("nan")
    if not ok.size:
        return State(scenario, target, None, target, outcome_note(ds, scenario) or "no admissible state")
    if math.isfinite(upper) and target >= upper:
        return State(scenario, target, None, target, f"no admissible state above λmax = {lmax:.3f}")
    return State(scenario, target, None, target, "not solved (tce plot solves it on demand)")


#: passive restraint (kN) below which a state's note does not mention it (solver round-off)
PASSIVE_SHOWN = 1e-6


def _notes(ds: xr.Dataset, scenario: str, step: int) -> str:
    notes = [outcome_note(ds, scenario)]
    if "unique" in ds and float(value(ds, "unique", scenario, ["step"])[step]) == 0.0:
        notes.append(NOT_UNIQUE)
    if "passive_force" in ds:
        passive = float(value(ds, "passive_force", scenario, ["step"])[step])
        if math.isfinite(passive) and passive > PASSIVE_SHOWN:
            notes.append(f"the fill's passive restraint pushes {passive:.3g} kN horizontally on the ring "
                         "(its pieces are not drawn)")
    return "; ".join(n for n in notes if n)


def outcome_note(ds: xr.Dataset, scenario: str) -> str:
    """What a reader must know about a scenario whose outcome is not ``limit`` ("" if it is):
    :func:`tce.study.outcomes.outcome_words` with the dataset's ``no_limit_reason`` or
    ``unbounded_reason``, or the study's cap and the direct limit for ``capped``."""
    outcome = text(ds, "outcome", scenario, "limit")
    reason = text(ds, f"{outcome}_reason", scenario) if outcome in ("no_limit", "unbounded") else ""
    direct = float(value(ds, "lambda_direct", scenario)) if "lambda_direct" in ds else math.nan
    return outcome_words(outcome, direct=direct, cap=study_cap(ds), reason=reason, lam="λ")


def study_cap(ds: xr.Dataset) -> float | None:
    """The ``[loads] lambda_cap`` of the study stored in ``ds`` (None: none given)."""
    try:
        return json.loads(ds.attrs["loads"]).get("lambda_cap")
    except (KeyError, TypeError, ValueError):
        return None


def unique_note(ds: xr.Dataset, scenario: str) -> str:
    """:data:`NOT_UNIQUE` when every optimal step of the scenario is flagged non-unique."""
    if "unique" not in ds:
        return ""
    ok = optimal_steps(ds, scenario)
    u = value(ds, "unique", scenario).astype(float)[ok]
    return NOT_UNIQUE if ok.size and np.all(u == 0.0) else ""


# ---------------------------------------------------------------------------- what each figure holds
MAX_COLUMNS = 4  # state panels per row
MAX_ROWS = 6  # rows of state panels per page


def state_pages(names: Sequence[str], targets: Sequence[object]) -> list[list[tuple[str, object]]]:
    """Panels ``(scenario, target)`` of :func:`states_figure`, split into pages.

    Several targets: one column per scenario (at most :data:`MAX_COLUMNS` a page), one row
    per target. One target: the scenarios in two columns (at most :data:`MAX_ROWS` rows a
    page).
    """
    names, targets = list(names), list(targets)
    per = MAX_COLUMNS if len(targets) > 1 else 2 * MAX_ROWS
    return [[(s, t) for s in names[i:i + per] for t in targets] for i in range(0, len(names), per)]


def mechanism_groups(ds: xr.Dataset, names: Sequence[str]) -> list[list[str]]:
    """Scenarios of ``names`` grouped by identical collapse mechanism (those without one left
    out; the direct limit does not see settlements)."""
    mech = []
    for s in names:
        if "mechanism" not in ds:
            break
        v = np.asarray(value(ds, "mechanism", s, ["block", "dof"]), float)
        if np.all(np.isfinite(v)) and np.any(v):
            mech.append((s, v, value(ds, "interface_mode", s).astype(str)))
    groups = groups_of(mech, lambda a, b: np.allclose(a[1], b[1], rtol=1e-6, atol=1e-9 * np.abs(a[1]).max())
                       and np.array_equal(a[2], b[2]))
    return [[mech[i][0] for i in g] for g in groups]


# ---------------------------------------------------------------------------- frame of the structure
@dataclass(frozen=True)
class StructureFrame:
    """Horizontal directions in which support forces are read.

    Attributes
    ----------
    outward : dict
        Support name -> unit horizontal vector of ``H`` (along the span, pointing away
        from the structure; for a single support, the structure's long axis).
    across : dict
        Support name -> unit horizontal vector of ``S`` (``e_z x outward`` for radial
        supports; one direction for all the supports of a line-like structure).
    moment_axis : dict
        Support name -> axis of ``M``: the span (line, single) or the tangential
        direction (radial), so that ``M`` is the moment that rocks the structure over
        its supports.
    kind : {"line", "radial", "single"}
        Supports on one line (an arch: the span), around a centre (a dome), or one.
    labels : dict
        Axis label of each component ``H``, ``S``, ``V``, ``M`` with its sign.
    """

    outward: dict[str, NDArray[np.float64]]
    across: dict[str, NDArray[np.float64]]
    moment_axis: dict[str, NDArray[np.float64]]
    kind: str
    labels: dict[str, str]


def _axis_name(v: NDArray[np.float64]) -> str:
    for k, name in enumerate("xyz"):
        if abs(abs(v[k]) - 1.0) < 1e-9:
            return ("+" if v[k] > 0 else "-") + name
    return f"{math.degrees(math.atan2(v[1], v[0])):.0f}° from +x"


def _positive(v: NDArray[np.float64]) -> NDArray[np.float64]:
    """``v`` with its largest component positive."""
    return v if v[np.argmax(np.abs(v))] > 0 else -v


def structure_frame(asm: Assembly) -> StructureFrame:
    """The frame of :class:`StructureFrame` for an assembly.

    ``line``: support centroids on one horizontal line (second singular value of their plan
    positions below 1e-6 of the first); the span is that line, its largest component
    positive, each ``H`` pointing away from the free blocks' centroid. ``radial``: three or
    more supports off a line, directions from that centroid. ``single``: the span is the
    principal horizontal axis of the free blocks' centroids (x when they have none).
    """
    cen = asm.centroids
    free = list(asm.free_indices)
    w = asm.weights[free]
    centre = (w[:, None] * cen[free]).sum(axis=0) / w.sum() if free else cen.mean(axis=0)
    sup = list(asm.support_names)
    p = {s: cen[asm.index[s]][:2] for s in sup}
    ez = np.array([0.0, 0.0, 1.0])

    def horizontal(v2: NDArray[np.float64]) -> NDArray[np.float64]:
        v = np.array([v2[0], v2[1], 0.0])
        return v / np.linalg.norm(v)

    def principal(points: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        d = points - points.mean(axis=0)
        _, sv, vt = np.linalg.svd(d, full_matrices=False)
        return vt[0], sv

    vertical = "V vertical (kN)\n+ presses the support down"
    if len(sup) >= 2:
        axis, sv = principal(np.array(list(p.values())))
        if len(sv) < 2 or sv[1] <= 1e-6 * sv[0]:
            e = _positive(horizontal(axis))
            out = {s: (e if (p[s] - centre[:2]) @ e[:2] >= 0 else -e) for s in sup}
            across = np.cross(ez, e)
            span = _axis_name(e)[1:]
            labels = {"H": f"H along the span {span} (kN)\n+ pushes the support outward",
                      "S": f"S across the span (kN)\n+ towards {_axis_name(across)}", "V": vertical,
                      "M": f"M about the span axis (kN m)\n+ right-handed about {_axis_name(e)}"}
            return StructureFrame(out, {s: across for s in sup}, {s: e for s in sup}, "line", labels)
        out = {s: horizontal(p[s] - centre[:2]) for s in sup}
        tangential = {s: np.cross(ez, out[s]) for s in sup}
        labels = {"H": "H radial (kN)\n+ pushes the support outward",
                  "S": "S tangential (kN)\n+ counter-clockwise in plan", "V": vertical,
                  "M": "M about the tangential axis (kN m)\n+ tips the support outward"}
        return StructureFrame(out, tangential, tangential, "radial", labels)
    pts = cen[free][:, :2] if len(free) >= 2 else np.zeros((2, 2))
    axis, sv = principal(pts)
    e = _positive(horizontal(axis)) if sv[0] > 0 and (len(sv) < 2 or sv[1] < 0.99 * sv[0]) else np.array([1.0, 0, 0])
    across = np.cross(ez, e)
    labels = {"H": f"H along the structure (kN)\n+ towards {_axis_name(e)}",
              "S": f"S across the structure (kN)\n+ towards {_axis_name(across)}", "V": vertical,
              "M": f"M about the long axis (kN m)\n+ right-handed about {_axis_name(e)}"}
    return StructureFrame({s: e for s in sup}, {s: across for s in sup}, {s: e for s in sup}, "single", labels)


def support_forces(ds: xr.Dataset, scenario: str, frame: StructureFrame) -> dict[str, NDArray[np.float64]]:
    """Forces and moment each support receives from the structure, in ``frame``.

    Returns
    -------
    dict
        ``"H"``, ``"S"``, ``"V"``, ``"M"``: arrays ``(n_steps, n_supports)`` (kN, kN m),
        supports in dataset order: minus ``reaction`` read along ``frame.outward``,
        ``frame.across``, ``-e_z`` (so the weight on a support is positive) and
        ``frame.moment_axis``. NaN where the step is not optimal.
    """
    sup = [str(s) for s in ds["support"].values]
    r = np.asarray(value(ds, "reaction", scenario, ["step", "support", "component"]), float)
    f, m = -r[..., :3], -r[..., 3:]

    def along(vec: NDArray[np.float64], axes: dict[str, NDArray[np.float64]]) -> NDArray[np.float64]:
        return np.einsum("ksj,sj->ks", vec, np.stack([axes[s] for s in sup]))

    return {"H": along(f, frame.outward), "S": along(f, frame.across), "V": -f[..., 2],
            "M": along(m, frame.moment_axis)}


# ---------------------------------------------------------------------------- geometry helpers
def chain_interfaces(asm: Assembly) -> list[int] | None:
    """Interfaces along the structure's single line of blocks, from one end to the other.

    A line of blocks (an arch, a column) is a connected path without cycle: every block
    touches at most two others. Returns the interface indices from the first support (or
    the path's first end), or None when it is not a line (no line of thrust exists).
    """
    n = len(asm.blocks)
    adj: dict[int, list[tuple[int, int]]] = {k: [] for k in range(n)}
    for i, itf in enumerate(asm.interfaces):
        if itf.a != itf.b:
            adj[itf.a].append((itf.b, i))
            adj[itf.b].append((itf.a, i))
    if n < 2 or len(asm.interfaces) != n - 1 or any(len(v) > 2 for v in adj.values()):
        return None
    ends = [k for k in range(n) if len(adj[k]) == 1]
    if len(ends) != 2:
        return None
    start = min(ends, key=lambda k: (not asm.blocks[k].support, k))
    order, prev, node = [], -1, start
    while True:
        nxt = [(b, i) for b, i in adj[node] if b != prev]
        if not nxt:
            break
        prev, (node, i) = node, nxt[0]
        order.append(i)
    return order if len(order) == n - 1 else None


def hinge_segments(ds: xr.Dataset, scenario: str, asm: Assembly) -> NDArray[np.float64]:
    """Hinge lines of the collapse mechanism, clipped to their interfaces, ``(n, 2, 3)`` (m).

    A hinging interface (``interface_mode == "hinge"``) turns about the line through its
    ``hinge_point`` along ``w_B - w_A`` (``mechanism``), clipped to the interface polygon;
    one whose relative rotation vanishes is skipped.
    """
    if "interface_mode" not in ds or "mechanism" not in ds:
        return np.empty((0, 2, 3))
    mode = value(ds, "interface_mode", scenario).astype(str)
    hp = np.asarray(value(ds, "hinge_point", scenario, ["interface", "xyz"]), float)
    vel = block_rows(ds, "mechanism", scenario, asm)
    if not np.all(np.isfinite(vel)):
        return np.empty((0, 2, 3))
    segs = []
    for k in np.flatnonzero((mode == "hinge") & np.all(np.isfinite(hp), axis=1)):
        itf = asm.interfaces[k]
        axis = vel[itf.b, 3:] - vel[itf.a, 3:]
        norm = np.linalg.norm(axis)
        if norm <= 1e-12 * max(np.abs(vel[:, 3:]).max(), 1e-300):
            continue
        seg = _chord(itf.points, itf.normal, hp[k], axis / norm)
        if seg is not None:
            segs.append(seg)
    return np.array(segs).reshape(-1, 2, 3)


def _chord(poly: NDArray[np.float64], normal: NDArray[np.float64], p0: NDArray[np.float64],
           a: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """The part of the line ``p0 + t a`` inside the convex polygon ``poly`` (in its plane)."""
    a = a - (a @ normal) * normal
    if np.linalg.norm(a) < 1e-9:
        return None
    a = a / np.linalg.norm(a)
    c = poly.mean(axis=0)
    tol = 1e-6 * float(np.ptp(poly, axis=0).max())  # a hinge on an edge of the polygon is inside it
    lo, hi = -np.inf, np.inf
    m = len(poly)
    for j in range(m):
        q, r = poly[j], poly[(j + 1) % m]
        inward = np.cross(normal, r - q)
        if inward @ (c - q) < 0:
            inward = -inward
        num, den = inward @ (p0 - q), inward @ a  # inside: num + t den >= 0
        if abs(den) < 1e-9 * np.linalg.norm(inward):  # the line runs along this edge
            if num < -tol * np.linalg.norm(inward):
                return None
            continue
        t = -num / den
        lo, hi = (max(lo, t), hi) if den > 0 else (lo, min(hi, t))
    if not (np.isfinite(lo) and np.isfinite(hi)) or hi - lo <= 1e-12:
        return None
    return np.array([p0 + lo * a, p0 + hi * a])


# ---------------------------------------------------------------------------- curves
def group_identical(curves: Sequence[tuple[NDArray, NDArray]], atol: float) -> list[list[int]]:
    """Groups of curves ``(x, y)`` that coincide: same x, y within ``atol`` everywhere.

    Returns indices into ``curves``, each group and the groups in input order.
    """
    return groups_of(curves, lambda a, b: len(a[0]) == len(b[0]) and np.allclose(a[0], b[0], rtol=0, atol=1e-12)
                     and np.allclose(a[1], b[1], rtol=0, atol=atol, equal_nan=True))


def groups_of(items: Sequence[Any], same: Callable[[Any, Any], bool]) -> list[list[int]]:
    """Indices of ``items`` in groups: each item joins the first group whose first item is
    ``same`` as it, else starts one (groups and their members in input order)."""
    groups: list[list[int]] = []
    for i, item in enumerate(items):
        group = next((g for g in groups if same(items[g[0]], item)), None)
        if group is None:
            groups.append([i])
        else:
            group.append(i)
    return groups


def join_names(names: Iterable[str], limit: int = 4) -> str:
    """``a, b, c`` (``a, b, … (+3)`` beyond ``limit``)."""
    names = list(names)
    head = ", ".join(names[:limit])
    return head + (f", … (+{len(names) - limit})" if len(names) > limit else "")


# ---------------------------------------------------------------------------- uncertainty studies
#: what a sample's status stands for in the failure probability
#: (:func:`tce.analysis.reliability.outcome_value`), in the order they are counted
SAMPLE_WORDS = {"optimal": "a finite capacity", "unbounded": "no finite limit (+inf: survives)",
                "infeasible": "nothing stands (-inf: fails)", "numerical": "undecided (NaN: left out of the estimate)"}
#: what each ``capacity_kind`` measures: the intensity ``x`` of ``P(capacity < x)``
CAPACITY_WORDS = {"lambda_max": "the load multiplier λ of the scenario's loads",
                  "adequacy_factor": "the adequacy factor (multiplier of the factored live load)",
                  "settlement_capacity": "the settlement magnitude (× the scenario's settlement vectors)"}


def has_uncertainty(ds: xr.Dataset) -> bool:
    """Whether ``ds`` holds the samples of an ``[uncertainty]`` study (``sample_capacity``)."""
    return "sample_capacity" in ds


def capacity_label(kind: str) -> str:
    """What the capacity of ``kind`` measures (:data:`CAPACITY_WORDS`; an unknown kind named as is)."""
    return CAPACITY_WORDS.get(kind, kind)


def uncertainty_variables(ds: xr.Dataset) -> dict[str, dict[str, Any]]:
    """The random variables' specs (attr ``uncertainty_variables``, JSON), key -> spec, in
    the order of the ``variable`` coordinate (:func:`tce.study.uncertainty.study_attrs`)."""
    try:
        specs = json.loads(str(ds.attrs.get("uncertainty_variables", "{}")))
    except ValueError:
        specs = {}
    keys = [str(v) for v in ds["variable"].values] if "variable" in ds.coords else list(specs)
    return {k: dict(specs.get(k, {})) for k in keys}


def sample_counts(ds: xr.Dataset, scenario: str) -> dict[str, int]:
    """The number of samples of ``scenario`` per status word (``sample_status``), those of
    :data:`SAMPLE_WORDS` first, in its order, then any other word; words with no sample left out."""
    words, counts = np.unique(value(ds, "sample_status", scenario).astype(str), return_counts=True)
    found = dict(zip(words.tolist(), counts.tolist()))
    order = [w for w in SAMPLE_WORDS if w in found] + sorted(w for w in found if w not in SAMPLE_WORDS)
    return {w: int(found[w]) for w in order}


def counts_note(ds: xr.Dataset, scenario: str) -> str:
    """The samples of ``scenario`` that did not end ``optimal``, counted with what they stand
    for (``"12 unbounded: no finite limit (+inf: survives); 3 numerical: ..."``); "" when
    every sample did."""
    counts = sample_counts(ds, scenario)
    total = sum(counts.values())
    others = {w: n for w, n in counts.items() if w != "optimal"}
    if len(others) == 1 and "optimal" not in counts:
        (word,) = others
        return f"all {total} samples {word}: {SAMPLE_WORDS.get(word, 'counted apart')}"
    return "; ".join(f"{n} of {total} {w}: {SAMPLE_WORDS.get(w, 'counted apart')}" for w, n in others.items())


def dominant_variable(ds: xr.Dataset, scenario: str) -> tuple[str, float] | None:
    """The variable of largest ``|sensitivity|`` for ``scenario`` and its sensitivity (None
    when every sensitivity is NaN: no decided sample, or a constant capacity)."""
    if "sensitivity" not in ds:
        return None
    s = np.asarray(value(ds, "sensitivity", scenario, ["variable"]), dtype=float)
    if not np.isfinite(s).any():
        return None
    k = int(np.nanargmax(np.abs(s)))
    return str(ds["variable"].values[k]), float(s[k])


def sweep_axes(ds: xr.Dataset, names: Sequence[str]) -> list[str]:
    """Numeric coordinates along ``scenario`` that take more than one value among ``names``:
    the swept parameters (:func:`swept_parameters`, in their order) then any other (``load_x``)."""
    out = swept_parameters(ds, names)
    for p, coord in ds.coords.items():
        if p in out or p == "scenario" or coord.dims != ("scenario",) or coord.dtype.kind not in "fiu":
            continue
        v = np.asarray(coord.sel(scenario=list(names)).values, dtype=float)
        if len(np.unique(v[np.isfinite(v)])) > 1:
            out.append(str(p))
    return out


#: the components of a support motion in a study file, in order (docs/conventions.md)
MOTION = ("ux", "uy", "uz", "rx", "ry", "rz")


def settlement_parameter(ds: xr.Dataset, names: Sequence[str]) -> tuple[str, dict[str, float]] | None:
    """The one number the settlement cases of ``names`` differ by: ``("right uz (m)",
    {scenario: value})`` when at least two distinct cases (``[scenarios.NAME]`` of the study
    text) move the supports alike but for one component of one support (a support not named
    does not move); None otherwise."""
    if "settlement" not in ds.coords:
        return None
    try:
        tables = tomllib.loads(str(ds.attrs.get("study", ""))).get("scenarios", {})
    except tomllib.TOMLDecodeError:
        return None
    case = {s: str(value(ds, "settlement", s)) for s in names}
    motions = {c: {k: v for k, v in tables.get(c, {}).items() if isinstance(v, list) and len(v) == len(MOTION)}
               for c in set(case.values())}
    if len(motions) < 2:
        return None
    supports = sorted({k for m in motions.values() for k in m})
    entries = {(sup, j): {c: float(m.get(sup, [0.0] * len(MOTION))[j]) for c, m in motions.items()}
               for sup in supports for j in range(len(MOTION))}
    differ = [key for key, by_case in entries.items() if len(set(by_case.values())) > 1]
    if len(differ) != 1:
        return None
    (sup, j), = differ
    return f"{sup} {MOTION[j]} ({'m' if j < 3 else 'rad'})", {s: entries[(sup, j)][case[s]] for s in names}
