"""Results datasets (``docs/results.md``): one per scenario while running, one per study at the end.

Each finished scenario becomes a one-scenario :class:`xarray.Dataset`
(:func:`scenario_dataset`) written atomically to ``<study dir>/scenarios/`` by the process
that solved it (:func:`write_scenario`), so an interrupted run loses no finished scenario.
The study's ``results.nc`` is the concatenation of those files along ``scenario``, in the
study's order, with the load paths padded to a common number of steps
(:func:`merge_scenarios`).

Storage rules: every file is written atomically (:func:`tce.files.atomic_write`), so a
reader sees the previous file or the complete new one; a failed write raises
:class:`StorageError` naming the path and the cause and leaves no temporary behind. A
scenario file records the hash of its scenario's definition (:attr:`tce.study.Scenario.key`)
and of its own content; a rerun reuses it only when both match and it holds every variable
of :data:`SCENARIO_VARS` (:func:`load_finished`). One run at a time writes a study folder
(:func:`folder_lock`).
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import fcntl
import hashlib
import json
import logging
import os
import re
import socket
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from .. import __version__
from ..core.analysis import Analysis
from ..analysis.diagnose import no_limit_reason, unbounded_reason
from ..analysis.loadpath import LoadPathResult
from ..analysis.nonassoc import NonAssocResult
from ..core.model import InterfaceMap
from ..core.resultants import global_vertex_forces
from ..core.result import DOFS, WRENCH_COMPONENTS, XYZ
from ..core.solve import SOLVER_NAME, TCEResult
from ..files import atomic_write, storage_error, temporaries
from ..structures.arch import RING
from ..structures.assembly import Assembly
from .schema import Scenario, Study

__all__ = [
    "SCENARIO_VARS",
    "FolderLocked",
    "folder_lock",
    "load_finished",
    "merge_scenarios",
    "remove_temporaries",
    "scenario_dataset",
    "geometries",
    "scenario_path",
    "steps_dataset",
    "study_attrs",
    "write_atomic",
    "write_scenario",
]

log = logging.getLogger(__name__)

#: variables that measure cost, not the answer (they differ from run to run)
TIMING = ("solve_time", "wall_time")
#: data variables every scenario file holds (a file without one of them is solved again)
SCENARIO_VARS = (
    "lam", "tce", "eq_residual", "cone_residual", "status", "reaction", "resultant", "pressure_point",
    "torque", "lambda_max", "lambda_upper", "lambda_direct", "lambda_gap", "lambda_kinematic",
    "certificate_gap", "n_solves", "solve_time", "wall_time", "outcome", "model", "mechanism",
    "interface_mode", "hinge_point", "interface_a", "interface_b", "block_centroid", "block_support",
    "no_limit_reason", "unbounded_reason", "unique", "vertex_force", "vertex_point", "vertex_interface",
    "lambda_multiplies",
)
#: name of the lock file of a study folder
LOCK_NAME = ".tce-run.lock"
_FILL_TEXT = ""

#: name -> (units, long_name)
META: dict[str, tuple[str, str]] = {
    "lambda_max": ("1", "load multiplier at the limit (last admissible step of the bisection)"),
    "lambda_upper": ("1", "smallest load multiplier found inadmissible"),
    "lambda_direct": ("1", "load multiplier at the limit from the direct limit analysis"),
    "lambda_gap": ("1", "lambda_max minus lambda_direct"),
    "lambda_kinematic": ("1", "load multiplier from the virtual work of the loads on the mechanism"),
    "certificate_gap": ("1", "relative gap between kinematic and direct load multipliers"),
    "outcome": ("-", "how the load path ended (limit, capped, no_limit, unbounded, infeasible, numerical)"),
    "no_limit_reason": ("-", "why there is no finite limit, in words (empty unless the outcome is no_limit)"),
    "unbounded_reason": ("-", "which support motion the material cannot follow, and why, in words (empty unless the "
                         "outcome is unbounded)"),
    "model": ("-", "model solved (planar or spatial)"),
    "n_solves": ("-", "number of TCE solves of the load path"),
    "solve_time": ("s", "wall time inside the solver's solve calls, summed over the load path (set-up excluded)"),
    "wall_time": ("s", "wall-clock time of the whole load path (solves, set-up, checks, direct limit)"),
    "lam": ("1", "load multiplier of the step"),
    "status": ("-", "status of the step's TCE solve (optimal, infeasible, unbounded, numerical)"),
    "reaction": ("kN, kN m", "wrench each support exerts on the structure, global frame, about the support centroid"),
    "tce": ("kN m", "total complementary energy"),
    "eq_residual": ("1", "relative equilibrium residual"),
    "cone_residual": ("1", "relative contact-law violation"),
    "resultant": ("kN", "interface resultant force on block B, global frame"),
    "pressure_point": ("m", "interface pressure point"),
    "torque": ("kN m", "torque about the interface normal at the pressure point, on block B"),
    "unique": ("1", "1 if the step's force state is the unique minimiser, 0 if not (then the state stored is the "
               "canonical one: least unit-stiffness energy among the minimisers, tce.core.canonical), NaN if undecided"),
    "vertex_force": ("kN", "force at each interface vertex on block B, global frame"),
    "passive_force": ("kN", "sum of the fill's passive restraint forces on the ring (horizontal, into the ring; "
                      "tce.core.passive), NaN without a restraint (kp = 0) or unless optimal"),
    "vertex_point": ("m", "interface vertex position (in the scenario's own structure)"),
    "geometry": ("-", "index k of the scenario's structure: its blocks are the attr 'assembly' (k = 0) or 'assembly_<k>'"),
    "vertex_interface": ("-", "interface of the vertex, as 'A|B' block names"),
    "mechanism": ("m, rad", "collapse mechanism velocities at the limit (unit amplitude, supports zero)"),
    "interface_mode": ("-", "interface behaviour in the mechanism (hinge, sliding, opening, closed)"),
    "interface_kind": ("-", "what joint the interface is ('' an ordinary joint, 'ring' between two rings of a "
                       "multi-ring arch), whose contact law the material may set apart"),
    "ring_separation": ("1", "1 if the rings separate in the collapse mechanism (a face between rings slides, opens "
                        "or hinges), 0 if they act together, NaN without a mechanism"),
    "ring_separation_at": ("-", "where the rings separate: per mode (sliding, opening, hinge), how many faces between "
                           "rings move in the collapse mechanism and the x range of their centroids (empty if none)"),
    "hinge_point": ("m", "trace point of the hinge line (NaN if no hinge)"),
    "interface_a": ("-", "block A of the interface (the normal points from A into B)"),
    "interface_b": ("-", "block B of the interface"),
    "block_centroid": ("m", "block centroid (in the scenario's own structure)"),
    "block_support": ("-", "1 for support blocks, 0 for free blocks"),
    "load_point": ("m", "point of application of each declared load (a distributed load: each part's resultant)"),
    "load_force": ("kN", "force of each declared load, global frame (a scaled load: at lambda = 1)"),
    "load_scaled": ("1", "1 for a live load (multiplied by lambda), 0 for a fixed load"),
    # finite settlements ([settlement_path] only; tce.analysis.settlement_path, docs/settlements.md)
    "settlement_capacity": ("1", "settlement capacity: largest magnitude found standing, in multiples of the "
                            "scenario's settlement vectors (NaN unless the outcome is collapse, snap_through "
                            "or contact_lost)"),
    "settlement_upper": ("1", "smallest magnitude found not standing (NaN if none)"),
    "settlement_outcome": ("-", "how the settlement path ended (collapse, snap_through, contact_lost, "
                           "no_collapse, infeasible, incompatible, numerical, no_motion)"),
    "settlement_message": ("-", "what decided the settlement path's outcome"),
    "settlement_hinge_sequence": ("-", "interfaces that start rotating (hinge) or close again, with the magnitude"),
    "settlement_n_solves": ("-", "linear programs solved along the settlement path"),
    "settlement_reaction": ("kN, kN m", "wrench each support exerts on the structure at each magnitude, global "
                            "frame, about the support's current centroid"),
    "settlement_lambda_max": ("1", "lambda_max of the lateral pattern on the deformed structure (NaN unless "
                              "lambda = true, and where withheld as a spurious strength or HiGHS failed: "
                              "settlement_message says where)"),
    "settlement_hinge": ("-", "1 for the interfaces that rotate in the mechanism at each magnitude"),
    "settlement_open": ("-", "number of open ends (0, 1 or 2) of each interface at each magnitude"),
    "settlement_displacement": ("m, rad", "displacement (ux, uy, uz) of each block's centroid and its rotation "
                                "vector (rx, ry, rz) from the reference placement, along dof"),
    "settlement_hinge_point": ("m", "current position of each hinge (NaN for interfaces that do not rotate)"),
    "settlement_step": ("-", "standing configuration of the settlement path, in order of magnitude"),
    "settlement_magnitude": ("1", "settlement magnitude, in multiples of the scenario's settlement vectors"),
    "live_at": ("1", "settlement magnitude at which the live loads are applied to the deformed structure "
                "([settlement_path] live_at)"),
    "settlement_live_step": ("1", "magnitude of the path's standing configuration used (the last at or below live_at; "
                             "NaN where nothing stands)"),
    "settlement_live_lambda": ("1", "lambda_max of the live loads on the deformed structure (their critical position "
                               "searched again with [loads] critical_position)"),
    "settlement_live_x": ("m", "critical position of the moving loads on the deformed structure (NaN without a search)"),
    "settlement_live_status": ("-", "status of that limit or search (optimal, unbounded, infeasible, numerical), "
                               "not_standing beyond the path's last standing magnitude, no_motion"),
    "settlement_live_gap": ("m", "widest opening of a contact point counted as a contact on the deformed structure "
                            "(within contact_gap: the motion that closes it is neglected)"),
    # coordinates
    "scenario": ("-", "scenario name"),
    "step": ("-", "load-path step, sorted by load multiplier"),
    "support": ("-", "support block name"),
    "component": ("-", "wrench component"),
    "interface": ("-", "interface, as 'A|B' block names"),
    "xyz": ("-", "global axis"),
    "block": ("-", "block name"),
    "dof": ("-", "rigid-body velocity component"),
    "vertex": ("-", "interface vertex (every vertex of the model's interfaces)"),
    "load": ("-", "applied load (point loads, then the parts of distributed loads)"),
    "settlement": ("-", "settlement case ([scenarios.NAME] of the study)"),
    "alpha": ("degree", "direction of the lateral loads, from +x towards +y"),
    "friction": ("1", "friction coefficient (NaN: unlimited)"),
    "magnitude": ("1", "scale factor applied to every settlement"),
    "inner_radius": ("m", "intrados radius"),
    "thickness": ("m", "thickness"),
    "depth": ("m", "depth"),
    "radius": ("m", "mid-surface radius"),
    "load_x": ("m", "plan abscissa of the reference of the moving loads (vehicles, scaled on_top point loads)"),
    "load_notes": ("-", "wheels dropped because they lie off the deck, one line per vehicle (empty: none)"),
    "lambda_multiplies": ("-", "what lambda multiplies and what is applied fixed, in words "
                          "(tce.core.loads.LoadPattern.multiplies)"),
    # critical position search ([loads] critical_position; tce.analysis.critical)
    "critical_x": ("m", "reference position of the moving loads of least direct lambda_max (the load path runs there)"),
    "critical_lambda": ("1", "least direct lambda_max over the positions (at critical_x)"),
    "critical_status": ("-", "status of the critical-position search (optimal, unbounded, infeasible, numerical)"),
    "critical_ties": ("-", "other positions with the same least lambda_max (m, comma-separated; empty: none)"),
    "critical_solves": ("-", "direct limit solves made by the critical-position search"),
    "critical_xtol": ("m", "tolerance of the critical-position search on the position"),
    "scan": ("-", "position evaluated by the critical-position search"),
    "scan_x": ("m", "reference position evaluated by the critical-position search"),
    "scan_lambda": ("1", "direct lambda_max at scan_x (inf: carried at any multiplier)"),
    # assessment ([assessment]; tce.analysis.assessment)
    "adequacy_factor": ("1", "multiplier of the factored live load at collapse under the factored dead load (>= 1: adequate)"),
    "adequacy_status": ("-", "status of the factored direct limit (optimal, unbounded, infeasible, numerical)"),
    "assessed_vehicles": ("-", "the live vehicles assessed, with their total loads"),
    "dead_factor": ("1", "partial factor on every fixed load (self-weight included) of the assessment"),
    "live_factor": ("1", "partial factor on the live loads of the assessment"),
    "cohesion": ("kN/m^2", "cohesion of the joints"),
    "tensile_strength": ("kN/m^2", "tensile strength of the joints"),
    "compressive_strength": ("kN/m^2", "compressive strength of the joints (per contact vertex)"),
    # non-associative bracket (flow = "non-associative" only; tce.analysis.nonassoc)
    "lambda_assoc": ("1", "associative lambda_max of the direct limit analysis (upper end of the bracket)"),
    "lambda_nonassoc": ("1", "non-associative estimate of lambda_max (Gilbert et al. 2006 scheme; NaN unless converged)"),
    "nonassoc_status": ("-", "status of the non-associative scheme (converged, not_converged, dilatant, infeasible, ...)"),
    "nonassoc_iterations": ("-", "non-associative iterations made"),
    "nonassoc_converged": ("-", "1 when the scheme reached a fixed point, else 0"),
    "nonassoc_admissibility": ("1", "violation of the Coulomb law by the final state, over the total weight"),
    "nonassoc_dilatancy": ("1", "largest opening of a loaded sliding contact in the final mechanism (0: none)"),
    "nonassoc_consistency": ("1", "at the contacts sliding in the final mechanism, the largest |fn - fn_used| "
                             "and shortfall of the shear below its Coulomb capacity, over the total weight"),
}


# ----------------------------------------------------------------------------- building
def _text(values: object) -> np.ndarray:
    """Strings as an object array (variable-length in netCDF; never truncated by concat)."""
    return np.asarray(values, dtype=object)


def _per_scenario(scalars: dict[str, object]) -> dict[str, tuple]:
    """Variables ``(scenario,)`` of one scenario's scalars."""
    return {k: (("scenario",), np.asarray([v])) for k, v in scalars.items()}


def _interface_names(a: Assembly) -> list[str]:
    """The interfaces of ``a`` as ``'A|B'`` block names."""
    return [f"{a.names[i.a]}|{a.names[i.b]}" for i in a.interfaces]


def _step_fields(step: TCEResult, slots: np.ndarray, n_itf: int) -> dict[str, np.ndarray]:
    """Per-step arrays of one TCE answer (NaN unless optimal), interfaces in assembly order."""
    n_sup = step.support_wrenches.shape[0]
    out = {
        "reaction": np.full((n_sup, 6), np.nan),
        "resultant": np.full((n_itf, 3), np.nan),
        "pressure_point": np.full((n_itf, 3), np.nan),
        "torque": np.full(n_itf, np.nan),
        "vertex_force": np.full((len(step.interface_map.vertex_points), 3), np.nan),
    }
    if step.ok:
        out["reaction"] = step.support_wrenches
        out["resultant"][slots] = step.resultants
        out["pressure_point"][slots] = step.pressure_points
        out["torque"][slots] = step.torques
        out["vertex_force"] = global_vertex_forces(step.interface_map, step.vertex_forces)
    return out


def _passive_force(step: TCEResult) -> float:
    """Sum of the fill's passive restraint forces of a state (kN; NaN without a restraint or
    unless optimal): :attr:`tce.core.solve.TCEResult.restraint_forces`."""
    p = step.restraint_forces
    return float(p.sum()) if p is not None and step.ok else float("nan")


def _path_vars(path: Sequence[TCEResult], slots: np.ndarray, n_itf: int) -> dict[str, tuple]:
    """Load-path variables ``(scenario, step, ...)`` of one scenario."""
    per_step = [_step_fields(s, slots, n_itf) for s in path]
    stack = {k: np.stack([p[k] for p in per_step])[None] for k in per_step[0]}
    scalar = {k: [getattr(s, k) for s in path] for k in ("lam", "tce", "eq_residual", "cone_residual")}
    dims = ("scenario", "step")
    out: dict[str, tuple] = {k: (dims, np.asarray([v], dtype=float)) for k, v in scalar.items()}
    out["status"] = (dims, _text([[s.status for s in path]]))
    out["unique"] = (dims, np.asarray([[np.nan if s.unique is None else float(s.unique) for s in path]]))
    out["passive_force"] = (dims, np.asarray([[_passive_force(s) for s in path]], dtype=float))
    out["vertex_force"] = (dims + ("vertex", "xyz"), stack["vertex_force"])
    out["reaction"] = (dims + ("support", "component"), stack["reaction"])
    out["resultant"] = (dims + ("interface", "xyz"), stack["resultant"])
    out["pressure_point"] = (dims + ("interface", "xyz"), stack["pressure_point"])
    out["torque"] = (dims + ("interface",), stack["torque"])
    return out


def steps_dataset(scenario: str, steps: Sequence[TCEResult], n_interfaces: int) -> xr.Dataset:
    """Per-step variables (``lam``, ``status``, ``reaction``, ...) of ``steps`` as a
    one-scenario dataset, ``step`` in the given order (for states solved after a run)."""
    slots = np.asarray(steps[0].interfaces, dtype=int)
    ds = xr.Dataset(_path_vars(steps, slots, n_interfaces), coords={"scenario": [scenario]})
    return _label(ds)


def _limit_vars(lp: LoadPathResult, slots: np.ndarray, n_itf: int, n_blocks: int) -> dict[str, tuple]:
    """Scalars and mechanism of the scenario's limit."""
    lim = lp.limit
    mech = lim.mechanism
    modes = np.full(n_itf, _FILL_TEXT, dtype=object)
    hinge = np.full((n_itf, 3), np.nan)
    vel = np.full((n_blocks, 6), np.nan)
    if mech is not None:
        modes[slots] = mech.modes
        hinge[slots] = mech.hinge_points
        vel = mech.velocities
    scalars = {
        "lambda_max": lp.lambda_max,
        "lambda_upper": lp.lambda_upper,
        "lambda_direct": lp.lambda_direct,
        "lambda_gap": lp.gap,
        "lambda_kinematic": lim.lambda_kinematic,
        "certificate_gap": lim.certificate_gap,
        "n_solves": lp.n_solves,
        "solve_time": lp.solve_time,
        "wall_time": lp.wall_time,
    }
    out = _per_scenario(scalars)
    out["outcome"] = (("scenario",), _text([lp.outcome]))
    out["model"] = (("scenario",), _text([lp.steps[0].model]))
    out["mechanism"] = (("scenario", "block", "dof"), vel[None])
    out["interface_mode"] = (("scenario", "interface"), modes[None])
    out["hinge_point"] = (("scenario", "interface", "xyz"), hinge[None])
    return out


def _ring_vars(a: Assembly, modes: np.ndarray) -> dict[str, tuple]:
    """Whether the rings of a multi-ring arch separate in the mechanism (``modes``: each
    interface's, ``""`` without a mechanism): ``ring_separation``, ``ring_separation_at`` (per
    mode, how many faces between rings move and the x range of their centroids) and the
    interface kinds; nothing for an assembly without faces between rings."""
    kinds = a.interface_table.kind
    ring = np.flatnonzero(kinds == RING)
    if not len(ring):
        return {}
    x = a.interface_table.centroid[:, 0]
    moving = [k for k in ring if modes[k] not in ("closed", _FILL_TEXT)]
    decided = any(modes[k] != _FILL_TEXT for k in ring)
    parts = []
    for m in ("sliding", "opening", "hinge"):
        at = [k for k in moving if modes[k] == m]
        if at:
            parts.append(f"{m} at {len(at)} faces, x = {x[at].min():.3g} to {x[at].max():.3g} m")
    where = "; ".join(parts) + (f" (of {len(ring)} faces between rings)" if parts else "")
    return {
        "interface_kind": (("interface",), _text(kinds.tolist())),
        "ring_separation": (("scenario",), np.asarray([float(bool(moving)) if decided else np.nan])),
        "ring_separation_at": (("scenario",), _text([where])),
    }


def _static_vars(analysis: Analysis, imap: InterfaceMap) -> dict[str, tuple]:
    """Variables of the assembly and of the interface vertices of ``imap``: the coordinates
    (``vertex_point``, ``block_centroid``) per scenario, since a geometry sweep gives each
    scenario its own; names and support flags (the same for every scenario) without."""
    a = analysis.assembly
    names = _interface_names(a)
    owner = np.asarray(imap.interfaces, dtype=int)[imap.vertex_slot]
    return {
        "vertex_point": (("scenario", "vertex", "xyz"), imap.vertex_points[None]),
        "vertex_interface": (("vertex",), _text([names[k] for k in owner])),
        "interface_a": (("interface",), _text([a.names[i.a] for i in a.interfaces])),
        "interface_b": (("interface",), _text([a.names[i.b] for i in a.interfaces])),
        "block_centroid": (("scenario", "block", "xyz"), a.centroids[None]),
        "block_support": (("block",), np.asarray([int(b.support) for b in a.blocks])),
    }


def _load_vars(lp: LoadPathResult, analysis: Analysis) -> tuple[dict[str, tuple], dict[str, tuple]]:
    """Variables and coordinate of the declared point and distributed loads (for arrows);
    empty for the paper's pattern alone."""
    applied = analysis.applied_loads(loads=lp.loads)
    if not len(applied.blocks):
        return {}, {}
    data = {
        "load_point": (("scenario", "load", "xyz"), applied.points[None]),
        "load_force": (("scenario", "load", "xyz"), applied.forces[None]),
        "load_scaled": (("scenario", "load"), applied.scaled.astype(float)[None]),
    }
    if lp.loads is not None and lp.loads.vehicle:
        data["load_notes"] = (("scenario",), _text(["\n".join(applied.notes)]))
    return data, {"load": (("load",), np.arange(len(applied.blocks)))}


def _coords(sc: Scenario, analysis: Analysis, n_steps: int) -> dict[str, tuple]:
    a = analysis.assembly
    coords: dict[str, tuple] = {
        "scenario": (("scenario",), _text([sc.name])),
        "step": (("step",), np.arange(n_steps)),
        "support": (("support",), _text(a.support_names)),
        "component": (("component",), _text(WRENCH_COMPONENTS)),
        "interface": (("interface",), _text(_interface_names(a))),
        "xyz": (("xyz",), _text(XYZ)),
        "block": (("block",), _text(a.names)),
        "dof": (("dof",), _text(DOFS)),
        "settlement": (("scenario",), _text([sc.settlement])),
    }
    for k, v in sc.params.items():
        coords[k] = (("scenario",), np.asarray([v], dtype=float))
    return coords


def _label(ds: xr.Dataset) -> xr.Dataset:
    """Give every variable and coordinate its ``units`` and ``long_name``."""
    for name in list(ds.variables):
        units, long_name = META.get(str(name), ("-", str(name)))
        ds[name].attrs.update(units=units, long_name=long_name)
    return ds


def _nonassoc_vars(na: NonAssocResult) -> dict[str, tuple]:
    """The associative/non-associative bracket of the scenario."""
    scalars = {
        "lambda_assoc": na.lambda_assoc,
        "lambda_nonassoc": na.lambda_nonassoc,
        "nonassoc_iterations": na.iterations,
        "nonassoc_converged": int(na.converged),
        "nonassoc_admissibility": na.admissibility,
        "nonassoc_dilatancy": na.dilatancy,
        "nonassoc_consistency": na.consistency,
    }
    out = _per_scenario(scalars)
    out["nonassoc_status"] = (("scenario",), _text([na.status]))
    return out


def scenario_dataset(
    sc: Scenario,
    lp: LoadPathResult,
    analysis: Analysis,
    nonassoc: NonAssocResult | None = None,
    settlement: xr.Dataset | None = None,
) -> xr.Dataset:
    """The one-scenario dataset of a load path (``docs/results.md``).

    Parameters
    ----------
    sc : Scenario
        The scenario that was run; its :attr:`~tce.study.Scenario.key` is kept in the
        attrs (``scenario_key``) so that a rerun can tell whether it is still valid.
    analysis : Analysis
        The analysis that ran it (for the assembly and the model's interfaces).
    nonassoc : NonAssocResult, optional
        The non-associative bracket (materials with ``flow = "non-associative"``): adds
        ``lambda_assoc``, ``lambda_nonassoc`` and the ``nonassoc_*`` variables.
    settlement : xarray.Dataset, optional
        The finite-settlement variables (``[settlement_path]``:
        :func:`tce.study.settlement.settlement_vars`), merged in.
    """
    path = lp.path
    n_itf = len(analysis.assembly.interfaces)
    step_slots = np.asarray(path[0].interfaces, dtype=int)
    limit_slots = np.asarray(analysis.model(lp.limit.model).interfaces, dtype=int)
    data = _path_vars(path, step_slots, n_itf)
    data.update(_limit_vars(lp, limit_slots, n_itf, len(analysis.assembly.blocks)))
    data.update(_ring_vars(analysis.assembly, data["interface_mode"][1][0]))
    data.update(_static_vars(analysis, path[0].interface_map))
    data["no_limit_reason"] = (("scenario",), _text([no_limit_reason(analysis, lp)]))
    data["unbounded_reason"] = (("scenario",), _text([unbounded_reason(analysis, lp)]))
    data["lambda_multiplies"] = (("scenario",), _text([lp.loads.multiplies]))
    if nonassoc is not None:
        data.update(_nonassoc_vars(nonassoc))
    loads, load_coord = _load_vars(lp, analysis)
    data.update(loads)
    ds = xr.Dataset(data, coords=_coords(sc, analysis, len(path)) | load_coord)
    if settlement is not None:
        ds = ds.merge(settlement)
    ds.attrs["scenario_key"] = sc.key
    return _label(ds)


# ----------------------------------------------------------------------------- files
class FolderLocked(RuntimeError):
    """Another run holds the study folder."""


def scenario_path(directory: Path, sc: Scenario) -> Path:
    """File of one finished scenario: a readable slug of its name plus a short hash."""
    slug = re.sub(r"[^A-Za-z0-9_.=-]+", "_", sc.name).strip("_.")[:80]
    digest = hashlib.sha256(sc.name.encode()).hexdigest()[:8]
    return directory / f"{slug}-{digest}.nc"


def write_atomic(ds: xr.Dataset, path: Path, engine: str | None = None) -> Path:
    """Write ``ds`` to ``path`` as netCDF, whole or not at all (:func:`tce.files.atomic_write`).
    ``engine`` is xarray's writer (default: netCDF-4).

    Raises
    ------
    StorageError
        The file cannot be written (no temporary file is left).
    """
    try:
        with atomic_write(path) as tmp:
            ds.to_netcdf(tmp, engine=engine)
    except (OSError, RuntimeError) as exc:
        raise storage_error(path, exc) from None
    return path


def remove_temporaries(directory: Path, pid: int | None = None) -> list[Path]:
    """Remove the temporary files :func:`write_atomic` left in ``directory`` (a writer
    killed mid-write): those of process ``pid``, or all (the caller holds the folder's lock)."""
    gone = []
    for tmp in temporaries(directory, pid):
        with contextlib.suppress(OSError):
            tmp.unlink()
            gone.append(tmp)
    return gone


def content_digest(ds: xr.Dataset) -> str:
    """SHA-256 of a dataset's variables (names, dimensions, types and values), not its attrs.

    Text is hashed as text and integers as 64-bit integers whatever their width: a scenario
    file (netCDF-3) reads its strings back as objects and its integers as 32-bit ones."""
    h = hashlib.sha256()
    for name in sorted(map(str, ds.variables)):
        v = ds[name].variable
        kind = "text" if v.dtype.kind in "OUS" else "int" if v.dtype.kind in "iu" else v.dtype.str
        h.update(f"{name}|{v.dims}|{kind}|{v.shape}|".encode())
        if kind == "text":
            h.update("\x00".join(map(str, v.values.ravel())).encode())
        elif kind == "int":
            h.update(np.ascontiguousarray(v.values, dtype=np.int64).tobytes())
        else:
            h.update(np.ascontiguousarray(v.values).tobytes())
    return h.hexdigest()


#: xarray's writer of the scenario files: netCDF-3 (scipy), cheaper than netCDF-4 and read by
#: every netCDF tool; the study's ``results.nc`` stays netCDF-4
SCENARIO_ENGINE = "scipy"


def write_scenario(ds: xr.Dataset, directory: Path, sc: Scenario) -> Path:
    """Write one scenario's dataset (:func:`scenario_dataset`) with its content digest."""
    ds = ds.copy()
    ds.attrs["content_sha256"] = content_digest(ds)
    return write_atomic(ds, scenario_path(directory, sc), engine=SCENARIO_ENGINE)


def load_finished(directory: Path, scenarios: Iterable[Scenario]) -> dict[str, xr.Dataset]:
    """Scenario datasets already written under ``directory`` that can be trusted.

    A file is used only when it can be read, was written for the same definition
    (:attr:`~tce.study.Scenario.key`), holds every variable of :data:`SCENARIO_VARS` and
    still has the content it was written with (truncated, corrupted or edited files are
    solved again, and overwritten then).
    """
    found: dict[str, xr.Dataset] = {}
    for sc in scenarios:
        path = scenario_path(directory, sc)
        if not path.exists():
            continue
        try:
            ds = xr.load_dataset(path)
        except Exception as exc:  # noqa: BLE001 - the netCDF library raises many kinds on a damaged file
            log.warning("ignoring unreadable scenario file %s (%s): solving %r again", path, exc, sc.name)
            continue
        missing = [v for v in SCENARIO_VARS if v not in ds.data_vars]
        if ds.attrs.get("scenario_key") != sc.key:
            log.info("scenario %r changed since %s was written: solving it again", sc.name, path)
        elif missing or ds.attrs.get("content_sha256") != content_digest(ds):
            log.warning(
                "ignoring scenario file %s (%s): solving %r again",
                path, f"no {missing}" if missing else "its content was changed", sc.name,
            )
        else:
            found[sc.name] = ds
    return found


@contextlib.contextmanager
def folder_lock(directory: Path) -> Iterator[Path]:
    """Hold ``directory/.tce-run.lock`` while the block runs: one run per study folder.

    The lock is an exclusive :func:`fcntl.flock` on the file, released by the system however
    its holder ends (a stale lock is taken over). The file records the holder's pid, host and
    start time for the message of a run that finds it held.

    Raises
    ------
    FolderLocked
        Another process holds the lock.
    StorageError
        The lock file cannot be written.
    """
    path = directory / LOCK_NAME
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)  # a planted link is refused
        except OSError as exc:
            raise storage_error(path, exc) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.read(fd, 4096).decode(errors="replace").strip() or "unknown"
            os.close(fd)
            raise FolderLocked(
                f"{directory}: another run is writing this folder ({holder}); "
                "fix: wait for it to end, or give another --out"
            ) from None
        try:
            same = os.fstat(fd).st_ino == os.stat(path).st_ino
        except FileNotFoundError:
            same = False
        if same:  # not unlinked by the previous holder between our open and flock
            break
        os.close(fd)
    try:
        old = os.read(fd, 4096).decode(errors="replace").strip()
        if old:
            log.info("taking over the lock of a run that ended without releasing it (%s)", old)
        record = f"pid {os.getpid()} on {socket.gethostname()} since {_dt.datetime.now().isoformat(timespec='seconds')}"
        os.ftruncate(fd, 0)
        os.pwrite(fd, record.encode(), 0)
        os.fsync(fd)
    except OSError as exc:  # a full disk: the lock is ours, remove it with its empty record
        with contextlib.suppress(OSError):
            os.unlink(path)
        os.close(fd)
        raise storage_error(path, exc) from None
    try:
        yield path
    finally:
        with contextlib.suppress(OSError):
            os.unlink(path)
        os.close(fd)


def _text_as_object(ds: xr.Dataset) -> xr.Dataset:
    """Every text variable and coordinate as an object array, so concatenation never truncates."""
    text = {k: v for k, v in ds.variables.items() if v.dtype.kind in "USOT"}
    return ds.assign_coords({k: (v.dims, _text(v.values)) for k, v in text.items() if k in ds.coords}).assign(
        {k: (v.dims, _text(v.values), v.attrs) for k, v in text.items() if k not in ds.coords}
    )


def _pad(ds: xr.Dataset, n_steps: int) -> xr.Dataset:
    """Extend the ``step`` dimension to ``n_steps`` (NaN for numbers, "" for text)."""
    ds = _text_as_object(ds)
    fill = {k: (_FILL_TEXT if v.dtype.kind in "USO" else np.nan) for k, v in ds.data_vars.items() if "step" in v.dims}
    return ds.reindex(step=np.arange(n_steps), fill_value=fill)


def geometries(study: Study) -> tuple[list[dict], list[int]]:
    """The distinct structures of a study's scenarios, in the order they first appear, and
    the index of each scenario's (in :meth:`Study.scenarios` order).

    Scenarios share a structure when their built assemblies are the same
    (:attr:`Scenario.assembly_digest`); a geometry sweep (``thickness``, ``inner_radius``,
    ``depth``, ``radius``) gives one per swept value.
    """
    seen: dict[str, int] = {}
    structures: list[dict] = []
    index = []
    for sc in study.scenarios():
        if sc.assembly_digest not in seen:
            seen[sc.assembly_digest] = len(structures)
            structures.append(sc.structure)
        index.append(seen[sc.assembly_digest])
    return structures, index


def study_attrs(study: Study, models: Iterable[str]) -> dict[str, str]:
    """Global attrs: study text, versions, solver, models, assemblies and material.

    ``assembly`` is the structure of geometry 0 (the first scenario's); a geometry sweep
    adds ``assembly_1``, ``assembly_2``, ... for the others (the ``geometry`` variable
    names each scenario's)."""
    structures, _ = geometries(study)
    assembly = study.assembly(structures[0])
    extra = {f"assembly_{k}": json.dumps(study.assembly(s).to_dict()) for k, s in enumerate(structures) if k}
    return extra | {
        "study": study.text,
        "study_name": study.name,
        "tce_version": __version__,
        "solver": SOLVER_NAME,
        "model": ", ".join(sorted(set(models))),
        "assembly": json.dumps(assembly.to_dict()),
        "material": json.dumps(study.material()),
        "loads": json.dumps(study.spec.loads.model_dump()),
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }


def merge_scenarios(study: Study, parts: dict[str, xr.Dataset]) -> xr.Dataset:
    """The study dataset: ``parts`` (one dataset per scenario name) in the study's order.

    Variables without a ``scenario`` dimension (names and support flags, the same for every
    scenario) are taken from the first scenario. Each scenario keeps its own coordinates
    (``vertex_point``, ``block_centroid``); ``geometry`` and the ``assembly``/``assembly_<k>``
    attrs give each its own blocks (:func:`geometries`).
    """
    order = [sc.name for sc in study.scenarios()]
    missing = [n for n in order if n not in parts]
    if missing:
        raise ValueError(f"cannot merge: scenarios not solved: {missing}")
    n_steps = max(parts[n].sizes["step"] for n in order)
    ds = _stacked([parts[n] for n in order], n_steps)
    if ds is None:  # the parts' other dimensions differ (a geometry sweep): let xarray align them
        ds = xr.concat([_pad(parts[n], n_steps) for n in order], dim="scenario", data_vars="minimal",
                       coords="minimal", compat="override", join="outer", combine_attrs="drop")
    ds["geometry"] = (("scenario",), np.asarray(geometries(study)[1], dtype=np.int64))
    ds.attrs = study_attrs(study, ds["model"].values.tolist())
    return _label(ds)


def _plain_text(values: np.ndarray) -> np.ndarray:
    """Text as an object array of Python ``str`` (an answer kept in memory may hold
    ``numpy.str_``, one read back from its file ``str``; netCDF cannot write a mix)."""
    return np.asarray(values).astype(str).astype(object)


def _stacked(parts: list[xr.Dataset], n_steps: int) -> xr.Dataset | None:
    """The one-scenario datasets ``parts`` stacked along ``scenario`` with numpy: ``step``
    padded to ``n_steps`` (NaN for numbers, "" for text), text as object arrays, variables
    without ``scenario`` from the first part; None when the parts' other index coordinates
    differ (then only an outer join can stack them).

    The same dataset as :func:`xarray.concat` of the :func:`_pad`-ded parts (tested), without
    xarray's alignment and copy of every part.
    """
    first = parts[0]
    for name, index in first.indexes.items():
        if name not in ("scenario", "step") and any(not p.indexes[name].equals(index) for p in parts[1:]):
            return None
    coords: dict[str, xr.Variable] = {}
    data: dict[str, xr.Variable] = {}
    for name, var in first.variables.items():
        text = var.dtype.kind in "USOT"
        if name == "step":
            new = xr.Variable(("step",), np.arange(n_steps, dtype=var.dtype), dict(var.attrs))
        elif "scenario" not in var.dims:
            values = _plain_text(var.values) if text else var.values.astype(np.int64) if var.dtype.kind in "iu" else var.values
            new = xr.Variable(var.dims, values, dict(var.attrs))
        else:
            dims = var.dims
            at = dims.index("scenario")
            shape = [len(parts) if d == "scenario" else n_steps if d == "step" else var.sizes[d] for d in dims]
            ints = var.dtype.kind in "iu"  # int32 when read back from a scenario file: int64 always
            dtype = object if text else (np.float64 if "step" in dims else np.int64) if ints else var.dtype
            out = np.full(shape, _FILL_TEXT if text else np.nan, dtype=dtype) if "step" in dims else np.empty(shape, dtype)
            for i, part in enumerate(parts):
                v = part.variables[name]
                where = [slice(None)] * len(dims)
                where[at] = slice(i, i + 1)
                if "step" in dims:
                    where[dims.index("step")] = slice(0, v.sizes["step"])
                out[tuple(where)] = _plain_text(v.values) if text else v.values
            new = xr.Variable(dims, out)
        (coords if name in first.coords else data)[name] = new
    return xr.Dataset(data, coords=coords)
