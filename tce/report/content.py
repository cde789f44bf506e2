"""What the calculation report says, read from a results dataset (``docs/results.md``).

:func:`report_content` gathers, as plain values the template prints: the study (name,
description, text), the structure (parameters, counts, weight, extent), the material and its
contact law, the loads, scenarios and sweep, the method with its references, the results table
(every number ``tce show`` prints, in the same format), the critical positions of a
load-position sweep, the warnings and the provenance. Nothing here draws or writes.
"""

from __future__ import annotations

import hashlib
import json
import math
import platform
import re
import tomllib
from dataclasses import dataclass, field
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .. import __version__
from ..plot.data import (
    assembly,
    capacity_label,
    counts_note,
    dominant_variable,
    geometry_groups,
    has_uncertainty,
    outcome_note,
    scenarios,
    uncertainty_variables,
)
from ..study.positions import critical_positions
from ..study.names import LAMBDA_TOL, same_lambda

__all__ = ["SHOW_COLUMNS", "Content", "fmt", "lambda_multiplies", "live_settlement_rows", "report_content",
           "small_displacement_note", "settlement_rows", "settlement_units", "uncertainty_content",
           "uncertainty_rows"]

#: the columns of ``tce show`` (:func:`tce.cli._show`), in its order, with the report's headings
SHOW_COLUMNS = {
    "lambda_max": "λmax", "lambda_direct": "λ direct", "lambda_gap": "gap", "outcome": "outcome", "model": "model",
    "n_solves": "solves", "solve_time": "solve time (s)", "wall_time": "wall time (s)",
}
#: the bracket and check columns of the second results table, with their headings
CHECK_COLUMNS = {"lambda_upper": "λ upper (first inadmissible)", "lambda_kinematic": "λ kinematic",
                 "certificate_gap": "certificate gap", "lambda_assoc": "λ associative",
                 "lambda_nonassoc": "λ non-associative", "nonassoc_status": "non-associative status",
                 "nonassoc_iterations": "iterations"}
#: a relative certificate gap above this is reported as a warning (the limit and its mechanism disagree)
CERTIFICATE_TOL = 1e-6


def fmt(value: object) -> str:
    """A number as ``tce show`` prints it (six significant figures; ``NaN``, ``inf``)."""
    if isinstance(value, (float, np.floating)):
        v = float(value)
        return "NaN" if math.isnan(v) else f"{v:.6g}"
    if isinstance(value, (np.integer, int)) and not isinstance(value, bool):
        return str(int(value))
    return str(value)


@dataclass
class Content:
    """Everything the report prints (see the module docstring); figures are added by the caller."""

    study: dict[str, Any]
    structure: dict[str, Any]
    material: dict[str, Any]
    loads: dict[str, Any]
    method: list[str]
    references: list[str]
    results: dict[str, Any]
    settlement: dict[str, Any]
    uncertainty: dict[str, Any]
    warnings: list[str]
    provenance: dict[str, Any]
    figures: list[dict[str, str]] = field(default_factory=list)


def _table(section: object) -> list[tuple[str, str]]:
    """A TOML table as ``(key, value)`` rows (nested tables and arrays as JSON)."""
    if not isinstance(section, dict):
        return []
    return [(k, v if isinstance(v, str) else json.dumps(v)) for k, v in section.items()]


def _geometry(ds: xr.Dataset, names: list[str], section: dict) -> dict[str, Any]:
    """One structure of the study: the scenarios ``names`` solved on it, its ``[structure]``
    parameters with the swept ones at that structure's values, its counts, weight and extent."""
    from ..study.schema import GEOMETRY_SWEEPS  # the study's parser: not needed by `tce show`

    asm = assembly(ds, names[0])
    k = ds.indexes["scenario"].get_loc(names[0])
    swept = [key for key in GEOMETRY_SWEEPS if key in ds.coords and ds[key].dims == ("scenario",)]
    section = {**section, **{key: None for key in swept if key not in section}}
    weights = sorted({round(float(b.unit_weight), 9) for b in asm.blocks})
    dx, dy, dz = asm.extent
    return {
        "scenarios": ", ".join(names),
        "parameters": [(f"{key} (swept)" if key in swept else key,
                        fmt(ds[key].values[k]) if key in swept else value) for key, value in _table(section)],
        "blocks": len(asm.blocks),
        "free_blocks": len(asm.free_indices),
        "supports": ", ".join(asm.support_names),
        "interfaces": len(asm.interfaces),
        "unit_weight": ", ".join(f"{w:g}" for w in weights) + " kN/m³",
        "weight": f"{asm.total_weight:.6g} kN",
        "extent": f"{dx:.4g} × {dy:.4g} × {dz:.4g} m (x × y × z)",
        "assembly": asm,
    }


def _structure(ds: xr.Dataset, toml: dict) -> dict[str, Any]:
    """The structure type and one :func:`_geometry` per structure the scenarios were solved on
    (several for a geometry sweep, in order of first appearance)."""
    section = dict(toml.get("structure", {}))
    kind = section.pop("type", "?")
    return {"type": kind,
            "geometries": [_geometry(ds, names, section) for names in geometry_groups(ds, scenarios(ds))]}


def _material(ds: xr.Dataset, toml: dict) -> dict[str, Any]:
    from ..study.schema import build_material  # the study's parser: not needed by `tce show`

    mat = build_material(json.loads(ds.attrs.get("material", "{}")))
    swept = {k: sorted({fmt(v) for v in np.atleast_1d(ds[k].values)}) for k in
             ("friction", "cohesion", "tensile_strength", "compressive_strength") if k in ds.coords}
    return {
        "describe": mat.describe(),
        "parameters": (_table(toml.get("material", {})) or [("(none)", "the defaults: Heyman, rigid, no tension")])
                      + [(f"[{key}] {k}", v) for key in ("ring_interface", "backing_interface")
                         for k, v in _table(toml.get(key))]
                      + [(f"[defects] {k}", v) for k, v in _table(toml.get("defects"))],
        "swept": [(k, ", ".join(v)) for k, v in swept.items()],
        "heyman": mat.heyman,
        "nonassociative": mat.flow == "non-associative",
        "rigid": mat.rigid,
    }


def ring_separation(ds: xr.Dataset) -> list[str]:
    """Whether the rings of a multi-ring arch separate at the limit, one line per scenario
    (``ring_separation``, ``ring_separation_at``); empty for a study without rings."""
    if "ring_separation" not in ds:
        return []
    out = []
    for k, name in enumerate(ds["scenario"].values):
        flag = float(ds["ring_separation"].values[k])
        if flag != flag:
            words = "undecided (no collapse mechanism)"
        elif flag:
            words = f"the rings separate at the limit ({ds['ring_separation_at'].values[k]})"
        else:
            words = "the rings act together at the limit (no face between rings moves)"
        out.append(f"{name}: {words}")
    return out


def lambda_multiplies(ds: xr.Dataset) -> list[str]:
    """What lambda multiplies (:attr:`tce.core.loads.LoadPattern.multiplies`): one line when
    every scenario has the same loads, else ``scenario: ...`` per scenario; empty if not recorded."""
    if "lambda_multiplies" not in ds:
        return []
    words = [str(w) for w in ds["lambda_multiplies"].values]
    return [words[0]] if len(set(words)) == 1 else [f"{n}: {w}" for n, w in zip(ds["scenario"].values, words)]


def _loads(ds: xr.Dataset, toml: dict) -> dict[str, Any]:
    loads = dict(toml.get("loads", {}))
    points = loads.pop("point", [])
    distributed = loads.pop("distributed", [])
    vehicles = loads.pop("vehicle", [])
    scenarios = []
    for name, table in toml.get("scenarios", {}).items():
        moves = [(k, v) for k, v in table.items() if isinstance(v, list)]
        rest = [(k, v) for k, v in table.items() if not isinstance(v, list)]
        scenarios.append({
            "name": name,
            "moves": ", ".join(f"{k} = {json.dumps(v)}" for k, v in moves) or "none (supports fixed)",
            "other": ", ".join(f"{k} = {json.dumps(v)}" for k, v in rest),
        })
    return {
        "settings": _table(loads),
        "points": [_table(p) for p in points],
        "distributed": [_table(d) for d in distributed],
        "vehicles": [_table(v) for v in vehicles],
        "live": lambda_multiplies(ds)
        or ["not recorded in these results (written by an earlier tce): see [loads] below"],
        "scenarios": scenarios,
        "sweep": _table(toml.get("sweep", {})),
        "n_scenarios": int(ds.sizes["scenario"]),
    }


#: a citation ``[n]`` in the method's text (and the label that starts a reference)
_CITATION = re.compile(r"\[(\d+)\]")


def _method(ds: xr.Dataset, material: dict, toml: dict) -> tuple[list[str], list[str]]:
    """Paragraphs on the method and assumptions, and the references they cite."""
    refs = ["[1] 3D exploration of internal stresses due to lateral loads and foundation movements in a semicircular "
            "arch (the TCE method implemented by tce; docs/conventions.md).",
            "[2] J. Heyman, The stone skeleton, International Journal of Solids and Structures 2 (1966) 249-279."]
    text = [
        "The structure is a set of rigid blocks in unilateral contact (masonry as Heyman idealised it [2]); contact "
        "forces act at the vertices of the interfaces (normal force ≥ 0 unless a tensile strength is given; "
        "friction cone ||f_t|| ≤ μ f_n + c A). "
        "Every free block is in equilibrium under self-weight, the fixed loads and λ times the live loads; support "
        "blocks may move (six components about their centroid) [1].",
        "Among all admissible force states the one minimising the Total Complementary Energy is the answer: a linear "
        "program for a planar scene, a second-order cone program in 3D, solved by Clarabel; a support motion that "
        "the material cannot accommodate makes the problem unbounded [1].",
        "A load path raises λ in steps and bisects between the last admissible and the first inadmissible "
        "multiplier; λmax is the last admissible one and the bracket [λmax, λ upper] is reported. The direct limit "
        "analysis (one conic program) gives λ direct and the collapse mechanism; their difference (gap) is a check.",
    ]
    if material["heyman"]:
        text.append("Friction is unlimited (Heyman's assumptions: no tensile strength, unlimited compressive strength, "
                    "no sliding) [2].")
    else:
        refs.append("[3] D. Cocchetti, E. Rizzi, Non-symmetrical collapse mode of circular arches with friction, "
                    "2020 (the arch with finite friction).")
        text.append("Sliding is limited by Coulomb friction; with associative flow the limit theorems hold (sliding "
                    "with dilatancy) [3].")
    if material["nonassociative"]:
        refs.append("[4] M. Gilbert, C. Casapulla, H.M. Ahmed, Limit analysis of masonry block structures with "
                    "non-associative frictional joints using linear programming, Computers & Structures 84 (2006).")
        text.append("The flow rule is non-associative: the associative λ is an upper bound and the iterative scheme "
                    "of Gilbert et al. gives the non-associative estimate; both are reported [4].")
    moves = any(t.values() for t in toml.get("scenarios", {}).values() if isinstance(t, dict))
    if moves:
        refs.append("[5] J. Ochsendorf, The masonry arch on spreading supports, The Structural Engineer 84 (2006); "
                    "S. Coccia, C. Di Carlo, F. Rinaldi, on arches under support settlements.")
        text.append("Support settlements are prescribed motions of the support blocks, imposed before the lateral "
                    "load is raised [5].")
    if not material["rigid"]:
        text.append("The contacts are compliant (normal and shear stiffness per unit area): the force state is "
                    "unique.")
    else:
        text.append("The contacts are rigid: the minimisers of the energy form a face of the admissible set ("
                    + ("often a segment or more where a support moves, every admissible state where none does"
                       if moves else "every admissible state, no support moving")
                    + "); the state shown is the canonical one, the face's state of least complementary strain "
                      "energy (docs/conventions.md), and an optimum that is not unique is flagged below.")
    if "load_x" in ds.coords:
        text.append("The moving live loads are placed at every position of the sweep; the critical position is the "
                    "one with the smallest λmax (an influence line, as bridge assessment does).")
    return _numbered(text, refs)


def _numbered(text: list[str], refs: list[str]) -> tuple[list[str], list[str]]:
    """``text`` and ``refs`` with the citations ``[n]`` renumbered 1, 2, ... in order of first
    citation, the references sorted so and those never cited left out."""
    order: dict[str, str] = {}
    for paragraph in text:
        for n in _CITATION.findall(paragraph):
            order.setdefault(n, str(len(order) + 1))

    def renumber(paragraph: str) -> str:
        return _CITATION.sub(lambda m: f"[{order[m.group(1)]}]", paragraph)

    cited = [r for r in refs if _CITATION.match(r).group(1) in order]  # type: ignore[union-attr]
    return [renumber(p) for p in text], sorted((renumber(r) for r in cited), key=lambda r: int(_CITATION.match(r)[1]))


def _results(ds: xr.Dataset) -> dict[str, Any]:
    coords = [k for k, v in ds.coords.items() if v.dims == ("scenario",) and k not in ("scenario",)
              and len(np.unique(v.values.astype(str))) > 1]
    extra = [k for k in ("lambda_upper", "lambda_kinematic", "certificate_gap") if k in ds]
    nonassoc = [k for k in ("lambda_assoc", "lambda_nonassoc", "nonassoc_status", "nonassoc_iterations") if k in ds]
    rows = []
    for i, name in enumerate(ds["scenario"].values):
        row = {"scenario": str(name)}
        row.update({k: fmt(ds[k].values[i]) for k in coords})
        row.update({k: fmt(ds[k].values[i]) for k in SHOW_COLUMNS})
        row.update({k: fmt(ds[k].values[i]) for k in extra + nonassoc})
        row["reason"] = str(ds["no_limit_reason"].values[i]) if "no_limit_reason" in ds else ""
        rows.append(row)
    finite = [(float(v), str(s)) for s, v in zip(ds["scenario"].values, ds["lambda_max"].values) if np.isfinite(v)]
    critical = []
    if "load_x" in ds.coords:
        for c in critical_positions(ds):
            critical.append({"group": c.group or "all", "scenario": c.scenario or "none",
                             "load_x": fmt(c.load_x) if c.scenario else "–",
                             "lambda_max": fmt(c.lambda_max) if c.scenario else "no finite λmax",
                             "ties": ", ".join(fmt(t) for t in getattr(c, "ties", ()))})
    return {
        "assessment": _assessment(ds),
        "search": _search(ds),
        "rings": ring_separation(ds),
        "notes": [f"{name}: {line}" for name, notes in zip(ds["scenario"].values, ds["load_notes"].values)
                  for line in str(notes).splitlines()] if "load_notes" in ds else [],
        "coords": coords,
        "columns": SHOW_COLUMNS,
        "checks": {"lambda_max": "λmax", **{k: CHECK_COLUMNS.get(k, k) for k in extra + nonassoc}},
        "rows": rows,
        "smallest": _smallest(finite),
        "outcomes": {o: int((ds["outcome"].values == o).sum()) for o in np.unique(ds["outcome"].values.astype(str))},
        "critical": critical,
    }


def _smallest(finite: list[tuple[float, str]]) -> tuple[str, str] | None:
    """The smallest lambda_max and who has it: ``"scenario a"``, or every scenario tied with it
    (:func:`tce.study.names.same_lambda`, within 1e-9 relative) named (None when none is finite)."""
    if not finite:
        return None
    low = min(lam for lam, _ in finite)
    tied = [name for lam, name in finite if same_lambda(lam, low)]
    if len(tied) == 1:
        return fmt(low), f"scenario {tied[0]}"
    return fmt(low), f"scenarios {', '.join(tied)}, tied within {LAMBDA_TOL:g} relative"


def _assessment(ds: xr.Dataset) -> list[dict[str, str]]:
    """The adequacy factor of each scenario (``[assessment]``), in the formats of ``tce show``."""
    if "adequacy_factor" not in ds:
        return []
    rows = []
    for k, name in enumerate(ds["scenario"].values):
        x = float(ds["critical_x"].values[k]) if "critical_x" in ds else math.nan
        lam, af = float(ds["lambda_max"].values[k]), float(ds["adequacy_factor"].values[k])
        status = str(ds["adequacy_status"].values[k])
        verdict = {"optimal": "adequate" if af >= 1.0 else "NOT adequate",
                   "unbounded": "adequate (carried at any multiplier)"}.get(status, f"no adequacy factor ({status})")
        rows.append({
            "scenario": str(name), "what": str(ds["assessed_vehicles"].values[k]) or "the live loads",
            "x": f"{x:.4g}" if math.isfinite(x) else "–",
            "collapse": f"{lam:.4g}" if math.isfinite(lam) else str(ds["outcome"].values[k]),
            "dead": f"{float(ds['dead_factor'].values[k]):g}", "live": f"{float(ds['live_factor'].values[k]):g}",
            "factor": f"{af:.4g}" if status == "optimal" else "–", "verdict": verdict,
        })
    return rows


def _search(ds: xr.Dataset) -> list[dict[str, str]]:
    """The critical position each scenario's search found (``[loads] critical_position``)."""
    if "critical_x" not in ds or "critical_status" not in ds:
        return []
    rows = []
    for k, name in enumerate(ds["scenario"].values):
        status = str(ds["critical_status"].values[k])
        ok = status == "optimal"
        rows.append({
            "scenario": str(name), "status": status,
            "x": fmt(float(ds["critical_x"].values[k])) if ok else "–",
            "xtol": f"{float(ds['critical_xtol'].values[k]):.2g}" if ok else "–",
            "lambda": fmt(float(ds["critical_lambda"].values[k])) if ok else "–",
            "solves": str(int(ds["critical_solves"].values[k])) if ok else "–",
            "ties": str(ds["critical_ties"].values[k]) if "critical_ties" in ds else "",
        })
    return rows


def settlement_units(ds: xr.Dataset) -> str:
    """The unit of the settlement capacity as the dataset states it: ``×`` the scenario's
    settlement vectors for a magnitude (units ``1``), else the stored unit (e.g. ``m``)."""
    units = str(ds["settlement_capacity"].attrs.get("units", "1"))
    return "× the scenario's settlement vectors" if units == "1" else units


def _hinge_events(text: str) -> list[tuple[str, list[tuple[str, list[str]]]]]:
    """The stored hinge sequence (``s=0: v06|v07 hinge; s=0: v18|v19 hinge; ...``) grouped by
    magnitude, then by event, in order: ``[("s=0", [("hinge", ["v06|v07", "v18|v19"])]), ...]``."""
    groups: list[tuple[str, list[tuple[str, list[str]]]]] = []
    for entry in filter(None, (e.strip() for e in text.split(";"))):
        where, _, what = entry.partition(": ")
        joint, _, event = what.rpartition(" ")
        if not groups or groups[-1][0] != where:
            groups.append((where, []))
        events = groups[-1][1]
        if events and events[-1][0] == event:
            events[-1][1].append(joint)
        else:
            events.append((event, [joint]))
    return groups


def settlement_rows(ds: xr.Dataset) -> list[dict[str, str]]:
    """The settlement path's answer per scenario (``[settlement_path]``), as ``tce show`` prints it.

    Each row holds, as text: ``scenario``; ``capacity`` (largest magnitude found standing, in
    :func:`settlement_units`; ``>= s`` with the last magnitude reached where the outcome is
    no_collapse, ``NaN`` where nothing stood); ``upper`` (smallest magnitude found not standing,
    ``–`` where none); ``outcome`` (as stored);
    ``snaps`` (number of magnitudes at which the structure snaps: falls to a new standing
    configuration);
    ``hinges`` (the joints that start rotating, close again or snap, in order, with the
    magnitude); ``lateral`` (lambda_max of the lateral pattern on the deformed structure at the
    capacity's step; ``–`` without a capacity, where not computed (``lambda = false``) or where
    its linear program did not end optimal); ``message`` (what decided the outcome, and why a
    lateral capacity is withheld; empty when nothing needs saying). Empty without
    ``[settlement_path]``.
    """
    if "settlement_capacity" not in ds:
        return []
    rows = []
    for k, name in enumerate(ds["scenario"].values):
        capacity = float(ds["settlement_capacity"].values[k])
        mags = np.asarray(ds["settlement_magnitude"].values[k], dtype=float)
        groups = _hinge_events(str(ds["settlement_hinge_sequence"].values[k]))
        hinges = "; ".join(f"{where}: " + ", ".join(f"{event} {' '.join(joints)}" for event, joints in events)
                           for where, events in groups)
        snaps = sum(any(event == "snap" for event, _ in events) for _, events in groups)
        outcome = str(ds["settlement_outcome"].values[k])
        upper = float(ds["settlement_upper"].values[k])
        if outcome == "no_collapse" and np.isfinite(mags).any():
            capacity = float(np.nanmax(mags))  # stood at every magnitude, the last included
        lateral = "–"
        if "settlement_lambda_max" in ds and math.isfinite(capacity):
            at = np.flatnonzero(mags == capacity)
            there = float(ds["settlement_lambda_max"].values[k][at[-1]]) if at.size else math.nan
            lateral = fmt(there) if math.isfinite(there) else lateral
        rows.append({
            "scenario": str(name), "capacity": (f">= {fmt(capacity)}" if outcome == "no_collapse" else fmt(capacity)),
            "upper": fmt(upper) if math.isfinite(upper) else "–", "outcome": outcome, "snaps": str(snaps),
            "hinges": hinges or "–", "lateral": lateral,
            "message": str(ds["settlement_message"].values[k]) if "settlement_message" in ds else "",
        })
    return rows


def live_settlement_rows(ds: xr.Dataset) -> list[dict[str, str]]:
    """The live loads' ``lambda_max`` on the deformed structure (``[settlement_path] live_at``),
    one row per scenario and magnitude, as ``tce show`` prints it.

    Each row holds, as text: ``scenario``; ``at`` (the magnitude asked, in
    :func:`settlement_units`); ``step`` (the path's standing magnitude used); ``lambda``
    (``lambda_max`` of the live loads there, ``–`` unless optimal); ``x`` (the critical
    position, m; ``–`` without a search); ``status``; ``gap`` (the widest opening counted as
    a contact, mm). Empty without ``live_at``.
    """
    if "settlement_live_lambda" not in ds:
        return []
    rows = []
    for k, name in enumerate(ds["scenario"].values):
        for j, at in enumerate(ds["live_at"].values):
            status = str(ds["settlement_live_status"].values[k, j])
            ok = status == "optimal"
            v = {key: float(ds[f"settlement_live_{key}"].values[k, j]) for key in ("step", "lambda", "x", "gap")}
            rows.append({
                "scenario": str(name), "at": fmt(float(at)), "step": fmt(v["step"]),
                "lambda": fmt(v["lambda"]) if ok else "–",
                "x": fmt(v["x"]) if ok and math.isfinite(v["x"]) else "–",
                "status": status,
                "gap": fmt(1e3 * v["gap"]) if math.isfinite(v["gap"]) else "–",
            })
    return rows


def small_displacement_note(ds: xr.Dataset) -> str:
    """One sentence where a scenario moves a support and no finite settlement is followed with
    the live loads (``[settlement_path] live_at``): ``lambda_max`` does not depend on the
    settlement's magnitude; "" otherwise."""
    text = str(ds.attrs.get("study", ""))
    toml = tomllib.loads(text) if text else {}
    if "settlement_live_lambda" in ds or not any(_moves_support(ds, toml, i) for i in range(ds.sizes["scenario"])):
        return ""
    return ("λmax does not depend on the support motions (rigid blocks, small displacements: the static theorem): "
            "a settlement changes the force state, not the collapse load, whatever its magnitude; the adequacy "
            "after a finite settlement is [settlement_path] live_at (docs/settlements.md)")


def _moves_support(ds: xr.Dataset, toml: dict, i: int) -> bool:
    """Whether scenario ``i`` moves a support: its settlement case (``[scenarios.NAME]`` of the
    study text ``toml``) has a nonzero motion and its ``magnitude`` (1 when not swept) is not 0."""
    case = toml.get("scenarios", {}).get(str(ds["settlement"].values[i]), {}) if "settlement" in ds.coords else {}
    moved = any(isinstance(v, list) and any(x != 0 for x in v) for v in case.values())
    return moved and ("magnitude" not in ds.coords or float(ds["magnitude"].values[i]) != 0.0)


#: sampling methods of ``[uncertainty] method``, in words
SAMPLING = {"mc": "plain Monte Carlo", "lhs": "Latin hypercube", "sobol": "scrambled Sobol"}
#: the status of FORM and of subset simulation that is an answer (tce.study.samples writes "converged" or why not)
ANSWERED = ("converged",)


def _probability(v: float) -> str:
    return "NaN" if math.isnan(v) else f"{v:.4g}"


def _beta(v: float) -> str:
    return "NaN" if math.isnan(v) else ("inf" if v == math.inf else "-inf" if v == -math.inf else f"{v:.4g}")


def uncertainty_rows(ds: xr.Dataset) -> list[dict[str, str]]:
    """The failure probability of each scenario of an ``[uncertainty]`` study, as ``tce show``
    prints it (empty without one).

    Each row holds, as text: ``scenario``; ``kind`` (``capacity_kind``); ``pf``, ``low``,
    ``high`` (the estimate of ``P(capacity < threshold)`` and its interval, 4 significant
    figures, ``NaN`` without a decided sample); ``beta`` (the reliability index
    ``-Phi^-1(pf)``, ``inf`` for ``pf = 0``); ``failed``, ``decided``, ``numerical`` (sample
    counts); ``samples`` (N); ``dominant`` (the variable of largest ``|sensitivity|`` with its
    value, ``undefined`` without a decided sample or variation); ``form`` and ``subset``
    (their estimate, accuracy, status and evaluations; "" where not computed); ``note`` (:func:`tce.plot.data.counts_note`).
    """
    if not has_uncertainty(ds):
        return []
    n = int(ds.sizes["sample"])
    rows = []
    for k, name in enumerate(scenarios(ds)):
        def num(var: str, k: int = k) -> float:  # NaN where the variable is absent
            return float(ds[var].values[k]) if var in ds else math.nan

        dom = dominant_variable(ds, name)
        form = subset = ""
        if "form_beta" in ds:
            status = str(ds["form_status"].values[k])
            form = (f"β {_beta(num('form_beta'))}, pf {_probability(num('form_pf'))}, " if status in ANSWERED else
                    "no estimate, ") + f"{status}, {int(ds['form_evaluations'].values[k])} evaluations"
        if "subset_pf" in ds:
            status = str(ds["subset_status"].values[k])
            subset = (f"pf {_probability(num('subset_pf'))} (c.o.v. {num('subset_cov'):.2g}), " if status in ANSWERED
                      else "no estimate, ") + f"{status}, {int(ds['subset_evaluations'].values[k])} evaluations"
        rows.append({
            "scenario": name, "kind": str(ds["capacity_kind"].values[k]) if "capacity_kind" in ds else "lambda_max",
            "pf": _probability(num("failure_probability")), "low": _probability(num("failure_low")),
            "high": _probability(num("failure_high")), "beta": _beta(num("reliability_index")),
            "failed": str(int(ds["n_failed"].values[k])), "decided": str(int(ds["n_decided"].values[k])),
            "numerical": str(int(ds["n_numerical"].values[k])), "samples": str(n),
            "dominant": f"{dom[0]} ({dom[1]:+.2f})" if dom else "undefined", "form": form, "subset": subset,
            "note": counts_note(ds, name),
        })
    return rows


def uncertainty_content(ds: xr.Dataset) -> dict[str, Any]:
    """What the report's Uncertainty section says (empty without ``[uncertainty]``): the
    sampling (``method``, ``seed``, ``samples``), the ``threshold`` and what failure means
    (``failure``), the ``interval``, the ``variables`` (key, distribution, its parameters as
    text), the ``sensitivity`` method, the :func:`uncertainty_rows` and the row of the
    ``largest`` failure probability (None when no scenario has one)."""
    if not has_uncertainty(ds):
        return {}
    a = ds.attrs
    threshold = float(a.get("uncertainty_threshold", math.nan))
    kinds = list(dict.fromkeys(str(k) for k in ds["capacity_kind"].values)) if "capacity_kind" in ds else \
        ["lambda_max"]
    measures = "; ".join(f"{kind}: {capacity_label(kind)}" for kind in kinds) if len(kinds) > 1 else \
        capacity_label(kinds[0])
    interval = str(a.get("uncertainty_interval", "clopper-pearson"))
    method = str(a.get("uncertainty_method", "?"))
    rows = uncertainty_rows(ds)
    pf = np.asarray(ds["failure_probability"].values, dtype=float)
    return {
        "method": SAMPLING.get(method, method),
        "seed": str(a.get("uncertainty_seed", "?")),
        "samples": str(int(ds.sizes["sample"])),
        "threshold": f"{threshold:g}",
        "failure": f"the capacity below {threshold:g}, the capacity being {measures}",
        "interval": f"{100 * float(a.get('uncertainty_confidence', 0.95)):g} % "
                    f"{'Wilson' if interval == 'wilson' else 'Clopper-Pearson'}",
        "variables": [(key, str(spec.get("distribution", "?")),
                       ", ".join(f"{k} = {v}" for k, v in spec.items() if k != "distribution") or "–")
                      for key, spec in uncertainty_variables(ds).items()],
        "sensitivity": str(a.get("sensitivity_method", "?")),
        "rows": rows,
        "largest": rows[int(np.nanargmax(pf))] if np.isfinite(pf).any() else None,
        "form": "form_beta" in ds,
        "subset": "subset_pf" in ds,
        "figures": [],
    }


def _uncertainty_warnings(ds: xr.Dataset) -> list[str]:
    """The scenarios of an ``[uncertainty]`` study whose samples did not all end ``optimal``,
    or whose FORM or subset estimate is not an answer."""
    out = []
    for r in uncertainty_rows(ds):
        if r["note"]:
            out.append(f"{r['scenario']}: samples: {r['note']}"
                       + ("; no decided sample: no failure probability" if r["decided"] == "0" else "") + ".")
        for what in ("form", "subset"):
            if r[what] and r[what].startswith("no estimate"):
                out.append(f"{r['scenario']}: {'FORM' if what == 'form' else 'subset simulation'}: {r[what]}.")
    return out


def _warnings(ds: xr.Dataset, toml: dict) -> list[str]:
    note = small_displacement_note(ds)
    out = [note + "."] if note else []
    for i, name in enumerate(ds["scenario"].values):
        note = outcome_note(ds, str(name))  # what the outcome means (docs/conventions.md), "" for limit
        if note:
            out.append(f"{name}: {note}.")
        if "unique" in ds:
            flat = np.asarray(ds["unique"].values[i], dtype=float)
            status = ds["status"].values[i].astype(str)
            n = int(((flat == 0) & (status == "optimal")).sum())
            if n:
                why = ("rigid contacts: the minimisers of the energy form a face" if _moves_support(ds, toml, i) else
                       "rigid contacts, no support motion: every admissible state minimises the energy")
                out.append(f"{name}: {n} optimal step(s) are not necessarily unique ({why}): the force state drawn "
                           "is the canonical one of many (docs/conventions.md).")
        if "nonassoc_status" in ds and str(ds["nonassoc_status"].values[i]) not in ("converged", ""):
            out.append(f"{name}: the non-associative scheme did not converge ({ds['nonassoc_status'].values[i]}): "
                       "only the associative upper bound holds.")
        gap = float(ds["certificate_gap"].values[i]) if "certificate_gap" in ds else 0.0
        if math.isfinite(gap) and gap > CERTIFICATE_TOL:
            out.append(f"{name}: the mechanism's kinematic multiplier differs from λ direct by {gap:.3g} (relative).")
    return out + _uncertainty_warnings(ds)


def _versions() -> list[tuple[str, str]]:
    out = [("python", platform.python_version())]
    for pkg in ("numpy", "scipy", "clarabel", "xarray", "matplotlib", "jinja2"):
        try:
            out.append((pkg, version(pkg)))
        except PackageNotFoundError:
            out.append((pkg, "not installed"))
    return out


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def report_content(ds: xr.Dataset, results: Path) -> Content:
    """The report's content for the results dataset ``ds`` read from ``results``.

    Parameters
    ----------
    results : Path
        The file ``ds`` was read from (its digest and name go into the provenance).
    """
    text = str(ds.attrs.get("study", ""))
    toml = tomllib.loads(text) if text else {}
    name = str(ds.attrs.get("study_name", results.parent.name))
    material = _material(ds, toml)
    method, refs = _method(ds, material, toml)
    return Content(
        study={"name": name, "description": toml.get("study", {}).get("description", ""), "text": text},
        structure=_structure(ds, toml),
        material=material,
        loads=_loads(ds, toml),
        method=method,
        references=refs,
        results=_results(ds),
        settlement={"units": settlement_units(ds), "rows": settlement_rows(ds), "live": live_settlement_rows(ds)}
        if "settlement_capacity" in ds else {},
        uncertainty=uncertainty_content(ds),
        warnings=_warnings(ds, toml),
        provenance={
            "tce_run": str(ds.attrs.get("tce_version", "?")),
            "tce_report": __version__,
            "solver": str(ds.attrs.get("solver", "?")),
            "created": str(ds.attrs.get("created", "?")),
            "versions": _versions(),
            "digests": [
                ("study text (SHA-256)", _digest(text.encode())),
                ("assembly (SHA-256 of the stored JSON)", _digest(str(ds.attrs.get("assembly", "")).encode())),
                (f"{results.name} (SHA-256)", _digest(results.read_bytes())),
            ],
            "rerun": f"tce run {name}.toml --out <folder>   # {name}.toml: the study text in the appendix",
            "results": str(results),
        },
    )
