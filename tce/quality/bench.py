"""``tce bench``: speed against error, measured in one run on one machine.

:func:`run_bench` times, as medians over repeated calls, and compares each answer with a
reference (the Clarabel-direct solve at tight tolerance, or a closed form):

``per_solve``
    One TCE solve of the paper's arch (:func:`tce.structures.arch.semicircular_arch`, friction 0.8,
    rigid, an in-plane scene: ``lam`` cycling over a few values in ``[0, 0.2]`` with the
    right support spreading 1 mm) by the Clarabel-direct path (:class:`tce.core.solve.TCESolver`,
    data built once, vectors updated per solve), by a cvxpy problem built per solve and by
    a parametrised cvxpy problem re-solved (:class:`tce.cvx.CvxTCE`), with every solver
    cvxpy offers for the class (CLARABEL, ECOS, SCS; HIGHS for the planar LP); for the 3D
    SOCP (spatial model) and the planar LP. A TCE solve has no lambda_max, so its
    ``error`` is that of the **in-plane support reactions** ``(Fx, Fz, My)`` (largest
    component, relative to the total weight) against the reference TCE solve at the same
    ``lam``; the out-of-plane components are not unique in 3D (a self-stress of the arch
    in torsion costs no energy) and are left out.
``pyramid``
    lambda_max of the spatial arch with the friction cone (friction 0.5, ``alpha = 45``,
    where sliding governs) by the direct SOCP and by inscribed/circumscribed pyramids of
    ``k`` sides (:mod:`tce.pyramid`): time against error and bracket width.
``limit_cost``
    The direct lambda_max of the paper's arch (3D and planar; without and with its
    mechanism) against one raw Clarabel set-up + solve of the same problem, and the load
    path (planar: 1 mm spreading; 3D SOCP: 1 mm transversal motion; step 0.02, atol 1e-6,
    direct bracket, no mechanism) against a hand-written bisection on a warm raw Clarabel
    solver of the same TCE data: without canonical states (the same work), and as the path
    runs by default, with the canonical state of every optimal step, against the raw
    bisection solving that QP too (:func:`_raw_canonical`), with the raw solver's settings and
    with tce's canonical settings (refined); interleaved call by call, CPU time, medians; the
    ratio in ``note``.
``load_path``
    Number of solves and time of the load path against the bisection tolerance, against
    the direct lambda_max.
``canonical``
    The same load paths with and without canonical states (:mod:`tce.core.canonical`),
    planar LP and 3D SOCP: the extra cost as a ratio, and how many steps were decided unique.
``discretisation``
    Arches of 8 to 400 voussoirs: time and error of lambda_90max against its closed form
    ``(d/2) / z_c`` (``z_c`` the voussoirs' centroid height) and of the minimum thickness
    against ``t/R = 0.1075``.
``scaling``
    Arches and domes of about 100, 1,000 and 10,000 blocks: time to build them (generation,
    checks, model; ``build_s``) and of one lambda_max solve, peak memory (resident set, in
    a fresh subprocess each), medians of repeats, with the fitted growth exponents.
``runs``
    ``tce run`` end to end on the paper's studies with and without figures; on Fig. 8 and
    Fig. 10 also the default choice of jobs against ``--jobs 1`` and ``--jobs 2``, and dask
    kept out against dask importable (variants interleaved, medians of repeats).
``sweeps``
    Whole runs, each a fresh ``tce run --fresh`` from compiled bytecode (:func:`run_env`;
    :func:`measured_run`: wall, CPU of every
    process, CPU per process, load average), variants interleaved, medians of three: the
    300-scenario sweep of the paper's arch (no figures) with ``--jobs 1``, ``--jobs 2`` and
    the default, against the CPU of the same load paths alone in this process
    (:func:`solving_cpu`) and by the CPU on the longest chain of processes
    (:func:`critical_cpu`); Fig. 7-8, 9 and 10 with ``--no-plots``, with figures
    (``--no-report``: drawn by :mod:`tce.plot.drawers`), with figures drawn in the run's own
    process (``--no-report --jobs 1``, as before the drawers) and as the default (figures,
    report and its PDF); the share of CPU in solving of each paper study.
``sweep3000``
    The share of CPU in solving of a 3,000-scenario sweep of the arch (one run).
``reduction``
    What the planar model, dropping the cone (Heyman) and dropping the quadratic term
    (rigid) save, each with its effect on the answer.
``plotting``
    For each shipped paper study, in a fresh process as ``tce run --jobs 2`` runs it: the
    wall time of solving and writing (``run_study``, worker start included)
    and of drawing every figure and the view (``write_figures``, matplotlib's import
    included), with their CPU times in ``note`` (``--quick``: one run, the workers' CPU
    counted with the solving); the full run repeats both in the same process (imports
    warm) and adds a 300-scenario sweep of the paper's arch (10 frictions x 5 settlement
    magnitudes x 6 settlement cases). The targets compare the cold wall times as a ratio.

``hot_path``
    The load path's inner solve (:meth:`tce.core.analysis.Analysis.path`: scene checked
    once, warm solver, ``b`` updated) against Clarabel's own ``update(b) + solve()`` on
    identical data, interleaved call by call in one loop so that both see the same machine;
    the ratio of the medians is in ``note``.

Every row has ``time_s`` (median end-to-end seconds, from Python), ``solver_time_s``
(wall time inside the solver's solve calls as tce records it; for cvxpy rows, the wall
time of ``Problem.solve``), ``ratio`` (``time_s`` over the Clarabel-direct 3D
per-solve row), ``error`` with ``error_of`` saying of what, and ``residual`` (largest
equilibrium residual relative to the total weight, or weight times size for moments).
"""

from __future__ import annotations

import argparse
import functools
import gc
import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..structures.arch import semicircular_arch
from ..structures.assembly import Assembly
from ..core.conic import Scaling
from ..core.limit import LimitSolver
from ..core.material import Material
from ..core.model import Model, build_model
from ..core.pyramid import pyramid_lambda_max
from ..core.solve import SolverOptions, TCESolver
from ..study.progress import Progress, track

__all__ = ["run_bench", "bench_command", "add_bench_arguments", "evaluate_targets", "growth_exponent"]

FRICTION = 0.8
LAMS = (0.0, 0.05, 0.1, 0.15, 0.2)
SETTLEMENT = {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}
THICKNESS_REF = 0.1075
IN_PLANE = [0, 2, 4]  # Fx, Fz, My of a support wrench: unique; Fy, Mx, Mz carry a free self-stress in 3D
COLUMNS = [
    "section", "case", "method", "solver", "model", "n_blocks", "n_solves", "time_s", "build_s", "solver_time_s",
    "ratio", "error", "error_of", "residual", "peak_mem_mb", "time_min_s", "note", "cpu_s",
]


# ---------------------------------------------------------------- helpers
def _timed(fn: Callable[[int], Any], repeats: int) -> tuple[float, list[Any], list[float]]:
    """Median wall time of ``fn(i)`` over ``repeats`` calls (after one warm-up call), the
    answers and the individual times."""
    fn(0)
    gc.collect()
    out, times = [], []
    for i in range(repeats):
        t0 = time.perf_counter()
        out.append(fn(i))
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out, times


def _row(section: str, case: str, method: str, **kw: Any) -> dict[str, Any]:
    row: dict[str, Any] = {c: np.nan for c in COLUMNS}
    row.update(section=section, case=case, method=method, solver="", model="", error_of="", note="")
    row.update(kw)
    return row


def _eq_residual(model: Model, forces: np.ndarray, lam: float, alpha: float) -> float:
    """Largest equilibrium residual of ``forces`` (kN) relative to ``W`` / ``W L``."""
    F = np.asarray(forces, dtype=float).ravel()
    r = model.A_eq @ F + model.b_dead + lam * model.b_lateral(alpha)
    return float(np.abs(r / Scaling.of(model).rows(model)).max(initial=0.0))


def _voussoir_centroid_height(assembly: Assembly) -> float:
    """Height of the free blocks' centroid above z = 0 (m)."""
    free = list(assembly.free_indices)
    w = assembly.weights[free]
    return float((w * assembly.centroids[free, 2]).sum() / w.sum())


def growth_exponent(n: Sequence[float], t: Sequence[float]) -> float:
    """Least-squares slope of ``log t`` against ``log n`` (NaN with fewer than 2 points)."""
    n_, t_ = np.asarray(n, dtype=float), np.asarray(t, dtype=float)
    ok = (n_ > 0) & (t_ > 0) & np.isfinite(t_)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(n_[ok]), np.log(t_[ok]), 1)[0])


# ---------------------------------------------------------------- per solve
def _per_solve(quick: bool) -> list[dict[str, Any]]:
    import cvxpy as cp

    from ..core.cvx import CvxTCE

    arch = semicircular_arch().validate()
    mat = Material(friction=FRICTION)
    rows: list[dict[str, Any]] = []
    reps = dict(direct=60 if quick else 200, param=8 if quick else 50, rebuilt=3 if quick else 20)
    installed = set(cp.installed_solvers())
    for kind in ("spatial", "planar"):
        model = build_model(arch, kind)
        W = model.assembly.total_weight
        ref_solver = TCESolver(model, mat, SolverOptions(tol=1e-12, residual_tol=1e-9))
        ref = {lam: ref_solver.solve(lam, 0.0, SETTLEMENT) for lam in LAMS}
        label = "3D SOCP" if kind == "spatial" else "planar LP"

        def score(lam: float, status: str, forces: np.ndarray, wrenches: np.ndarray) -> tuple[float, float]:
            if status != "optimal":
                return np.inf, np.inf
            diff = (wrenches - ref[lam].support_wrenches)[:, IN_PLANE]
            err = float(np.abs(diff).max() / W)
            return err, _eq_residual(model, forces, lam, 0.0)

        def add(method: str, solver: str, fn: Callable[[int], Any], n: int, wrench: Callable[[Any], np.ndarray]) -> None:
            med, res, times = _timed(fn, n)
            scores = [score(LAMS[i % len(LAMS)], r.status, r.forces, wrench(r)) for i, r in enumerate(res)]
            rows.append(
                _row(
                    "per_solve", f"arch 16 blocks, {label}", method, solver=solver, model=kind,
                    n_blocks=len(arch.blocks), n_solves=n, time_s=med, time_min_s=min(times),
                    solver_time_s=statistics.median(float(r.solve_time) for r in res),
                    error=max(s[0] for s in scores), error_of="in-plane support reactions / W",
                    residual=max(s[1] for s in scores),
                    note="" if all(r.status == "optimal" for r in res) else "not all optimal",
                )
            )

        variants = (
            ("clarabel-direct (warm, update)", None),
            ("clarabel-direct, with refinement", SolverOptions(refine=True)),
            ("clarabel-direct, tol 1e-8", SolverOptions(tol=1e-8, residual_tol=1e-7)),
        )
        for method, options in variants:
            direct = TCESolver(model, mat, options)
            add(method, "CLARABEL", lambda i, d=direct: d.solve(LAMS[i % len(LAMS)], 0.0, SETTLEMENT),
                reps["direct"], lambda r: r.support_wrenches)
        solvers = ["CLARABEL", "ECOS", "SCS"] + (["HIGHS"] if kind == "planar" else [])
        for name in [s for s in solvers if s in installed]:
            param = CvxTCE(model, mat)
            add("cvxpy parametrised, re-solved", name,
                lambda i, p=param, s=name: p.solve(LAMS[i % len(LAMS)], 0.0, SETTLEMENT, solver=s),
                reps["param"], lambda r: r.support_wrenches)
            add("cvxpy built per solve", name,
                lambda i, s=name: CvxTCE(model, mat).solve(LAMS[i % len(LAMS)], 0.0, SETTLEMENT, solver=s),
                reps["rebuilt"], lambda r: r.support_wrenches)
    return rows


# ---------------------------------------------------------------- hot path
def _hot_path(quick: bool) -> list[dict[str, Any]]:
    """tce's load-path solve against Clarabel's own update + solve, interleaved (module doc)."""
    from ..core.analysis import Analysis
    from ..core.problem import tce_b

    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    reps = 150 if quick else 1000
    for kind in ("spatial", "planar"):
        an = Analysis(arch, Material(friction=FRICTION), model=kind)
        solve = an.path(0.0, SETTLEMENT)
        solve(LAMS[0])
        solver = an.solver(kind)
        raw = solver._warm._solver  # the very Clarabel object tce's solve drives
        data = [tce_b(solver.formulation, solver.rhs(lam, 0.0)) for lam in LAMS]
        t_tce, t_raw, statuses = [], [], set()
        for i in range(reps):
            lam = LAMS[i % len(LAMS)]
            t0 = time.perf_counter()
            statuses.add(solve(lam).status)
            t1 = time.perf_counter()
            raw.update(b=data[i % len(LAMS)])
            raw.solve()
            t2 = time.perf_counter()
            t_tce.append(t1 - t0)
            t_raw.append(t2 - t1)
        m_tce, m_raw = statistics.median(t_tce), statistics.median(t_raw)
        label = "3D SOCP" if kind == "spatial" else "planar LP"
        common = dict(solver="CLARABEL", model=kind, n_blocks=len(arch.blocks), n_solves=reps)
        rows.append(_row("hot_path", f"arch 16 blocks, {label}", "tce load-path solve (Analysis.path)",
                         time_s=m_tce, time_min_s=min(t_tce), note=f"{m_tce / m_raw:.3f}x raw; statuses {sorted(statuses)}",
                         **common))
        rows.append(_row("hot_path", f"arch 16 blocks, {label}", "clarabel update(b) + solve (raw)",
                         time_s=m_raw, time_min_s=min(t_raw), **common))
    return rows


# ---------------------------------------------------------------- lambda_max rows
def _limit_rows(quick: bool) -> list[dict[str, Any]]:
    """Direct lambda_max (3D, planar) and the friction pyramids' bracket."""
    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    reps = 5 if quick else 30
    for kind, mu, alpha in (("spatial", FRICTION, 0.0), ("planar", FRICTION, 0.0), ("spatial", 0.5, 45.0)):
        model = build_model(arch, kind)
        ref = LimitSolver(model, Material(friction=mu), tol=1e-12).solve(alpha)
        solver = LimitSolver(model, Material(friction=mu))
        med, res, _ = _timed(lambda i: solver.solve(alpha), reps)
        case = f"arch lambda_max, mu={mu}, alpha={alpha:g}"
        rows.append(
            _row("pyramid" if alpha else "limit", case, "clarabel-direct lambda_max", solver="CLARABEL", model=kind,
                 n_blocks=len(arch.blocks), n_solves=reps, time_s=med, solver_time_s=res[-1].solve_time,
                 error=abs(res[-1].lambda_max - ref.lambda_max), error_of="lambda_max",
                 residual=_eq_residual(model, res[-1].forces, res[-1].lambda_max, alpha),
                 note=f"lambda_max={ref.lambda_max:.6f}")
        )
        if not alpha:
            continue
        for k in (4, 8, 16) if quick else (4, 8, 16, 32, 64):
            bounds = {}
            for side in ("inscribed", "circumscribed"):
                med, res, _ = _timed(lambda i: pyramid_lambda_max(model, mu, alpha, k, side), reps)  # noqa: B023
                bounds[side] = res[-1].lambda_max
                rows.append(
                    _row("pyramid", case, f"pyramid {side} k={k} (LP)", solver="CLARABEL", model=kind,
                         n_blocks=len(arch.blocks), n_solves=reps, time_s=med, solver_time_s=res[-1].solve_time,
                         error=abs(res[-1].lambda_max - ref.lambda_max), error_of="lambda_max",
                         residual=_eq_residual(model, res[-1].forces, res[-1].lambda_max, alpha))
                )
            rows[-1]["note"] = rows[-2]["note"] = f"bracket width {bounds['circumscribed'] - bounds['inscribed']:.3g}"
    return rows


# ---------------------------------------------------------------- the direct limit's cost
def _raw_bisection(raw: Any, b0: np.ndarray, b1: np.ndarray, step: float, atol: float,
                   after: Callable[[np.ndarray, float], Any] | None = None) -> tuple[float, int]:
    """The load path written by hand on a warm Clarabel solver: ``b = b0 + lam b1``, increments
    of ``step`` until Clarabel reports infeasible, then bisection to ``atol``; admissible means
    ``Solved``. ``after(x, lam)``, when given, is called with the solution of every admissible
    step (the canonical state's extra solve). Returns ``(lambda_max, solves)``."""
    lo, hi, k, n = 0.0, float("nan"), 0, 0

    def admissible(lam: float) -> bool:
        raw.update(b=b0 + lam * b1)
        sol = raw.solve()
        if str(sol.status) != "Solved":
            return False
        if after is not None:
            after(np.asarray(sol.x), lam)
        return True

    while True:
        n += 1
        if not admissible(k * step):
            hi = k * step
            break
        lo = k * step
        k += 1
    while hi - lo > atol:
        mid = 0.5 * (lo + hi)
        n += 1
        if admissible(mid):
            lo = mid
        else:
            hi = mid
    return lo, n


def _raw_canonical(f: Any, b0: np.ndarray, b1: np.ndarray, q: np.ndarray, settings: Any) -> Callable:
    """``after`` for :func:`_raw_bisection`: the canonical state of each admissible step
    (:mod:`tce.core.canonical`: least unit-stiffness energy on the optimal face, slack 1e-10
    of the optimum) on one warm raw Clarabel solver with ``settings``, written from the
    module's definition; its data are built once per path, by this call (inside the timing,
    as tce's canonical solver builds its own on a path's first optimal step). No residual
    check, no fallback: every QP's answer is taken.

    ``settings`` with the raw solver's (no iterative refinement) is cheaper per QP than tce's
    canonical solver, which refines (``SolverOptions.settings()``): measured on the paper's arch
    (one process, 20 repeats of a path's 14 QPs), 0.26 ms and 11.4 iterations per planar QP
    against 0.58 ms and 15.7 refined, and 13.5 ms and 151 iterations per 3D QP against 10.3 ms
    and 77 refined. The unrefined answers are other points: the canonical states of the paths
    of :func:`_limit_cost` move by up to 4.8e-9 W (planar) and 1.1e-4 W (3D)."""
    import clarabel

    from ..core.canonical import FACE_SLACK, canonical_problem
    from ..core.clarabel_solver import _cones

    p = canonical_problem(f, b0, q, 0.0)
    m, nz, h = f.A_eq.shape[0], f.law.n_zero, f.law_h
    state: dict[str, Any] = {}

    def after(x: np.ndarray, lam: float) -> None:
        value = float(q @ x)
        bound = value + FACE_SLACK * abs(value) + 1e-15 * float(np.abs(q) @ np.abs(x))
        b = b0 + lam * b1
        if "solver" not in state:
            state["solver"] = clarabel.DefaultSolver(p.P, p.q, p.A, np.concatenate([b[:m], h[:nz], [bound], h[nz:]]),
                                                     _cones(p), settings)
        else:
            state["solver"].update(b=np.concatenate([b[:m], h[:nz], [bound], h[nz:]]))
        state["solver"].solve()

    return after


def _limit_cost(quick: bool) -> list[dict[str, Any]]:
    """The direct lambda_max against one raw Clarabel set-up + solve of the same problem, and
    the planar load path against a hand-written bisection on raw Clarabel, interleaved call
    by call (CPU time, medians; ratios in ``note``)."""
    import clarabel

    from ..analysis.loadpath import load_path
    from ..core.analysis import Analysis
    from ..core.clarabel_solver import _cones
    from ..core.loads import scene_vectors
    from ..core.problem import limit_problem, tce_b, tce_problem

    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    reps = 150 if quick else 1000
    mat = Material(friction=FRICTION)
    clock = time.process_time
    for kind in ("spatial", "planar"):
        model = build_model(arch, kind)
        solver = LimitSolver(model, mat)
        _, b_fixed, b_live = scene_vectors(model, 0.0)
        p = limit_problem(solver.formulation, b_fixed, b_live)
        settings = solver.options.settings(refine=False, kkt=solver.formulation.kkt)
        calls = {
            "tce direct lambda_max (LimitSolver.solve, no mechanism)": lambda: solver.solve(0.0, mechanism=False),
            "tce direct lambda_max, with its mechanism": lambda: solver.solve(0.0),
            "clarabel set-up + solve (raw, same problem)":
                lambda: clarabel.DefaultSolver(p.P, p.q, p.A, p.b, _cones(p), settings).solve(),  # noqa: B023
        }
        times: dict[str, list[float]] = {k: [] for k in calls}
        for i in range(reps):
            for name in (list(calls) if i % 2 else list(calls)[::-1]):
                t0 = clock()
                calls[name]()
                times[name].append(clock() - t0)
        raw = statistics.median(times["clarabel set-up + solve (raw, same problem)"])
        label = "3D SOCP" if kind == "spatial" else "planar LP"
        for name, ts in times.items():
            med = statistics.median(ts)
            rows.append(_row("limit_cost", f"arch 16 blocks lambda_max, {label}", name, solver="CLARABEL", model=kind,
                             n_blocks=len(arch.blocks), n_solves=reps, time_s=med, time_min_s=min(ts),
                             note=f"{med / raw:.3f}x raw (CPU, interleaved)"))
    # the load path (direct bracket, no mechanism) against the hand-written bisection: without canonical
    # states (the same work as the raw bisection: the target), and as it runs by default, with the
    # canonical state of every optimal step, against the raw bisection doing that too, its QP solved
    # with the raw solver's settings (no iterative refinement) and with tce's canonical settings
    # (refined: the same solves as tce's; :func:`_raw_canonical`); the planar LP and the 3D SOCP
    U = np.zeros(6 * len(arch.support_names))
    i = 6 * arch.support_names.index("right")
    scenes = (("planar", "arch in plane, 1 mm spreading, step 0.02, atol 1e-6", SETTLEMENT, 0, 10 if quick else 60),
              ("spatial", "arch, 1 mm transversal motion (3D SOCP), step 0.02, atol 1e-6",
               {"right": [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]}, 1, 2 if quick else 10))
    atol, step = 1e-6, 0.02
    for kind, case, sett, component, repeats in scenes:
        model = build_model(arch, kind)
        U[:] = 0.0
        U[i + component] = sett["right"][component]
        f = LimitSolver(model, mat).formulation
        _, b_fixed, b_live = scene_vectors(model, 0.0)
        tp = tce_problem(f, tce_b(f, b_fixed), U)
        b0, b1 = tce_b(f, b_fixed), tce_b(f, b_fixed + b_live) - tce_b(f, b_fixed)
        for canonical in (False, True):
            opts = SolverOptions(canonical=canonical)
            settings = opts.settings(refine=False, kkt=f.kkt)
            raws = {"raw": settings, "raw, refined QP": opts.settings(kkt=f.kkt)} if canonical else {"raw": settings}
            times: dict[str, list[float]] = {k: [] for k in ("tce", *raws)}
            got: dict[str, Any] = {}
            loads = [os.getloadavg()[0]]
            for r in range(repeats):
                an = Analysis(arch, mat, model=kind, options=opts)
                # both start from the built, scaled operators: the raw one from tp, whose A is its
                # formulation's constraints (built on first use: 0.3-0.6 ms on the planar arch)
                an.formulation(kind).constraints
                names = list(times)
                for name in (names if r % 2 else names[::-1]):
                    t0 = clock()
                    if name == "tce":
                        got[name] = load_path(an, 0.0, sett, step=step, atol=atol, mechanism=False)
                    else:
                        raw = clarabel.DefaultSolver(tp.P, tp.q, tp.A, b0, _cones(tp), settings)
                        after = _raw_canonical(f, b0, b1, tp.q, raws[name]) if canonical else None
                        got[name] = _raw_bisection(raw, b0, b1, step, atol, after)
                    times[name].append(clock() - t0)
                loads.append(os.getloadavg()[0])
            mt = statistics.median(times["tce"])
            lp = got["tce"]
            what = "with canonical states (the default)" if canonical else "no canonical states"
            ratios = "; ".join(f"{mt / statistics.median(times[k]):.3f}x the {k} bisection" for k in raws)
            rows.append(_row("limit_cost", case, f"tce load path (direct bracket, no mechanism, {what})",
                             solver="CLARABEL", model=kind, n_blocks=len(arch.blocks), n_solves=lp.n_solves, time_s=mt,
                             time_min_s=min(times["tce"]),
                             note=f"{ratios} (CPU, interleaved, {repeats} runs, {_load([{'load': loads}])}); "
                                  f"lambda_max {lp.lambda_max:.7f}, "
                                  f"{lp.n_solves} TCE solves + 1 direct"))
            for k in raws:
                lam_raw, n_raw = got[k]
                raw_what = (("with the canonical QP of every admissible step" if k == "raw" else
                             "with the canonical QP of every admissible step, refined as tce's")
                            if canonical else "no canonical states")
                rows.append(_row("limit_cost", case, f"hand-written bisection on raw clarabel ({raw_what})",
                                 solver="CLARABEL", model=kind, n_blocks=len(arch.blocks), n_solves=n_raw,
                                 time_s=statistics.median(times[k]), time_min_s=min(times[k]),
                                 note=f"lambda_max {lam_raw:.7f}, {n_raw} solves"))
    return rows


# ---------------------------------------------------------------- load path
def _load_path(quick: bool) -> list[dict[str, Any]]:
    """Load paths to each tolerance, narrowed by the direct bracket and by plain bisection
    (interleaved, same run), with their solve counts and gaps to the direct lambda_max."""
    from ..core.analysis import Analysis
    from ..analysis.loadpath import load_path

    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    ref = LimitSolver(build_model(arch, "planar"), Material(friction=FRICTION), tol=1e-12).solve(0.0).lambda_max
    tols = (1e-2, 1e-4, 1e-6, 1e-8) if quick else (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
    brackets = ("direct", "bisection")
    for options in (None, SolverOptions(refine=True)):
        for atol in tols:
            times: dict[str, list[float]] = {b: [] for b in brackets}
            res: dict[str, Any] = {}
            for _ in range(1 if quick else 3):
                for b in brackets:
                    an = Analysis(arch, Material(friction=FRICTION), options=options)
                    t0 = time.perf_counter()
                    res[b] = load_path(an, 0.0, SETTLEMENT, step=0.02, atol=atol, bracket=b)
                    times[b].append(time.perf_counter() - t0)
            suffix = "" if options is None else ", with refinement"
            for b in brackets:
                r = res[b]
                name = "direct bracket" if b == "direct" else "bisection"
                rows.append(
                    _row("load_path", "arch in plane, 1 mm spreading, step 0.02", f"{name} atol={atol:g}{suffix}",
                         solver="CLARABEL", model=r.steps[-1].model, n_blocks=len(arch.blocks), n_solves=r.n_solves,
                         time_s=statistics.median(times[b]), solver_time_s=r.solve_time,
                         error=abs(r.lambda_max - ref), error_of="lambda_max",
                         residual=max(s.eq_residual for s in r.steps if s.ok),
                         note=f"{r.outcome}; gap to direct {r.gap:.2g}; {r.n_solves} solves "
                              f"(bisection {res['bisection'].n_solves}); includes the direct lambda_max solve")
                )
    return rows


# ---------------------------------------------------------------- canonical states
def _canonical(quick: bool) -> list[dict[str, Any]]:
    """The extra cost of canonical states (:mod:`tce.core.canonical`): the same load paths
    with and without them (interleaved, same run), planar LP and 3D SOCP; ``ratio`` is the
    median time with over the median time without."""
    from ..core.analysis import Analysis
    from ..analysis.loadpath import load_path

    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    scenes = (("arch in plane, 1 mm spreading (planar LP)", SETTLEMENT),
              ("arch, 1 mm transversal motion (3D SOCP)", {"right": [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]}))
    for case, sett in scenes:
        times: dict[bool, list[float]] = {True: [], False: []}
        res: dict[bool, Any] = {}
        for _ in range(1 if quick else 5):
            for on in (False, True):
                an = Analysis(arch, Material(friction=FRICTION), options=SolverOptions(canonical=on))
                t0 = time.perf_counter()
                res[on] = load_path(an, 0.0, sett, step=0.02, atol=1e-6)
                times[on].append(time.perf_counter() - t0)
        base = statistics.median(times[False])
        for on in (False, True):
            r = res[on]
            unique = [s.unique for s in r.steps if s.ok]
            rows.append(_row(
                "canonical", case, "canonical states" if on else "solver's states", solver="CLARABEL",
                model=r.steps[-1].model, n_blocks=len(arch.blocks), n_solves=r.n_solves,
                time_s=statistics.median(times[on]), solver_time_s=r.solve_time,
                ratio=statistics.median(times[on]) / base,
                note=f"{r.outcome}; steps decided unique: {sum(u is True for u in unique)}, not unique: "
                     f"{sum(u is False for u in unique)}, undecided: {sum(u is None for u in unique)}",
            ))
    return rows


# ---------------------------------------------------------------- discretisation
def _discretisation(quick: bool) -> list[dict[str, Any]]:
    try:
        from ..analysis.thickness import arch_minimum_thickness
    except ImportError:  # pragma: no cover - written by another issue
        arch_minimum_thickness = None
    rows: list[dict[str, Any]] = []
    for n in (8, 16, 32) if quick else (8, 16, 32, 64, 128, 256, 400):
        arch = semicircular_arch(voussoirs=n).validate()
        model = build_model(arch, "spatial")
        closed = (arch.meta["depth"] / 2) / _voussoir_centroid_height(arch)
        solver = LimitSolver(model, Material(friction=FRICTION))
        med, res, _ = _timed(lambda i: solver.solve(90.0), 3 if quick else 5)
        rows.append(
            _row("discretisation", f"arch {n} voussoirs", "lambda_90max (direct, 3D)", solver="CLARABEL",
                 model="spatial", n_blocks=len(arch.blocks), n_solves=1, time_s=med,
                 solver_time_s=res[-1].solve_time, error=abs(res[-1].lambda_max - closed),
                 error_of="lambda_90max vs (d/2)/z_c",
                 residual=_eq_residual(model, res[-1].forces, res[-1].lambda_max, 90.0))
        )
        if arch_minimum_thickness is not None and (n == 16 or not quick):
            with Progress(0, f"minimum thickness, {n} voussoirs", unit="solve") as bar:
                th = arch_minimum_thickness(1.0, n, tol=1e-5, progress=bar)
            rows.append(
                _row("discretisation", f"arch {n} voussoirs", "minimum thickness (bisection 1e-5)",
                     solver="CLARABEL", model="planar", n_blocks=n + 2, n_solves=th.n_solves, time_s=th.wall_time,
                     error=abs(th.ratio - THICKNESS_REF), error_of="t/R vs 0.1075", note=f"t/R={th.ratio:.5f}")
            )
    return rows


# ---------------------------------------------------------------- scaling
def scaling_case(structure: str, size: int, friction: float = FRICTION) -> dict[str, Any]:
    """Build one structure of ``size`` and time one lambda_max solve (run in a subprocess).

    ``structure`` is ``"arch"`` (``size`` voussoirs) or ``"dome"`` (``size`` sectors and
    courses). Returns wall times (s) of the assembly (generation and checks), the model and
    the solve, their process CPU times (``cpu_*``, s), sizes and the peak resident memory of
    the process (MB).
    """
    import resource

    from ..structures.dome import hemispherical_dome

    c0, t0 = time.process_time(), time.perf_counter()
    a = semicircular_arch(voussoirs=size) if structure == "arch" else hemispherical_dome(sectors=size, courses=size)
    a = a.validate()
    t1 = time.perf_counter()
    model = build_model(a, "spatial")
    c2, t2 = time.process_time(), time.perf_counter()
    res = LimitSolver(model, Material(friction=friction)).solve(90.0 if structure == "arch" else 0.0)
    c3, t3 = time.process_time(), time.perf_counter()
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux
    out = dict(n_blocks=len(a.blocks), n_vars=model.n_vars, status=res.status, lambda_max=res.lambda_max,
               t_assembly=t1 - t0, t_model=t2 - t1, t_build=t2 - t0, t_solve=t3 - t2, t_clarabel=res.solve_time,
               cpu_build=c2 - c0, cpu_solve=c3 - c2, iterations=res.iterations, peak_mem_mb=rss)
    if structure == "dome":
        # the same limit problem with iterative refinement (the former default), for comparison
        from ..core.clarabel_solver import SolverOptions as Options, solve_once
        from ..core.problem import Formulation, limit_problem

        f = Formulation(model, Material(friction=friction))
        c4 = time.process_time()
        sol = solve_once(limit_problem(f, model.b_dead, model.b_lateral(0.0)), Options(tol=1e-10, max_iter=500).settings(refine=True))
        out.update(cpu_solve_refine=time.process_time() - c4, t_solve_refine=sol.solve_time + sol.setup_time,
                   lambda_refine=float(sol.x[-1]) if sol.solved else float("nan"), iterations_refine=sol.iterations)
    return out


def _subprocess_case(structure: str, size: int, timeout: float) -> dict[str, Any] | None:
    root = str(Path(__file__).resolve().parent.parent)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([root, os.environ.get("PYTHONPATH", "")]))
    code = f"import json, tce.quality.bench as b; print(json.dumps(b.scaling_case({structure!r}, {size})))"
    try:
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                             timeout=timeout, check=True)
    except (subprocess.TimeoutExpired, subprocess.CalledProcessError):
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


#: sizes of the scaling section: about 100, 1,000 and 10,000 blocks (dome: sectors = courses)
SCALING_SIZES = {"arch": (98, 998, 9998), "dome": (10, 31, 100)}
QUICK_SCALING_SIZES = {"arch": (98, 298, 998), "dome": (6, 10, 16)}


def _scaling(quick: bool) -> list[dict[str, Any]]:
    """Build (assembly and model) and one lambda_max solve against size, medians of repeats
    (each in a fresh process, sizes interleaved), with fitted growth exponents."""
    rows: list[dict[str, Any]] = []
    sizes = QUICK_SCALING_SIZES if quick else SCALING_SIZES
    repeats = 1 if quick else 3
    for structure, ns in sizes.items():
        runs: dict[int, list[dict[str, Any]]] = {n: [] for n in ns}
        for _ in range(repeats):
            for n in ns:
                r = _subprocess_case(structure, n, timeout=120 if quick else 1800)
                if r is not None:
                    runs[n].append(r)
        got = []
        for n in ns:
            if not runs[n]:
                rows.append(_row("scaling", f"{structure} size {n}", "build + lambda_max (direct, 3D)", note="failed or timed out"))
                continue
            med = {k: statistics.median(r[k] for r in runs[n]) for k in runs[n][0]
                   if k.startswith(("t_", "cpu_", "peak_"))}
            r = runs[n][-1]
            got.append((r["n_blocks"], med))
            rows.append(
                _row("scaling", f"{structure} {r['n_blocks']} blocks", "build + lambda_max (direct, 3D)", solver="CLARABEL",
                     model="spatial", n_blocks=r["n_blocks"], n_solves=len(runs[n]), time_s=med["t_solve"],
                     build_s=med["t_build"], solver_time_s=med["t_clarabel"], peak_mem_mb=med["peak_mem_mb"],
                     note=f"{r['status']}, {r['n_vars']} unknowns, {r['iterations']} it; build/solve "
                          f"{med['t_build'] / med['t_solve']:.3f} (cpu {med['cpu_build']:.2f} / {med['cpu_solve']:.2f} s)")
            )
            if "t_solve_refine" in med:
                rows.append(
                    _row("scaling", f"{structure} {r['n_blocks']} blocks", "lambda_max with iterative refinement (former default)",
                         solver="CLARABEL", model="spatial", n_blocks=r["n_blocks"], n_solves=len(runs[n]),
                         time_s=med["t_solve_refine"], error=abs(r["lambda_refine"] - r["lambda_max"]),
                         error_of="lambda_max vs the default (no refinement)",
                         note=f"{r['iterations_refine']} it; cpu {med['cpu_solve_refine']:.2f} s, "
                              f"the default takes {med['cpu_solve'] / med['cpu_solve_refine']:.2f}x of it")
                )
        blocks = [b for b, _ in got]
        e_solve = growth_exponent(blocks, [m["t_solve"] for _, m in got])
        e_build = growth_exponent(blocks, [m["t_build"] for _, m in got])
        for row in rows:
            if row["case"].startswith(structure):
                row["note"] += f"; solve ~ n^{e_solve:.2f}, build ~ n^{e_build:.2f}"
    return rows


# ---------------------------------------------------------------- whole runs
#: the shipped studies that reproduce the paper's figures
PAPER_STUDIES = ("fig3_4_settlements", "fig5_6_transversal", "fig7_8_inplane", "fig9_outofplane", "fig10_dome")


def run_env() -> dict[str, str]:
    """The environment of the ``tce run`` processes the benchmarks time: tce running from its
    compiled bytecode, as an installed tce does (pip compiles a package as it installs it).

    Where ``PYTHONDONTWRITEBYTECODE`` is set (the machine the README's figures come from sets
    it), an editable install compiles every module of tce again in each process: 0.15-0.2 s of
    a one-second run of the paper's arch, which would hide that much of the time a run takes.
    The runs are timed without it, tce compiled once beforehand (:func:`_compile_tce`)."""
    env = dict(os.environ)
    if env.pop("PYTHONDONTWRITEBYTECODE", None) is not None:
        _compile_tce()
    return env


@functools.lru_cache(maxsize=1)
def _compile_tce() -> None:
    """Compile tce's modules once per process (``compileall``, which writes bytecode whatever
    ``PYTHONDONTWRITEBYTECODE`` says: into tce's ``__pycache__`` folders, which git ignores)."""
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(Path(__file__).resolve().parents[1])],
                   check=True, capture_output=True)


def _tce_run(study: Path, out: Path, args: Sequence[str], program: bool = True) -> float:
    """Wall time (s) of ``tce run STUDY --fresh ARGS`` in a fresh process. ``program=False``
    calls :func:`tce.cli.main` with explicit arguments, which leaves dask importable
    (what every run did before the program kept it out)."""
    if program:
        cmd = [sys.executable, "-m", "tce.cli"]
    else:
        cmd = [sys.executable, "-c", "import sys; from tce.cli import main; sys.exit(main(sys.argv[1:]))"]
    t0 = time.perf_counter()
    subprocess.run(cmd + ["-q", "run", str(study), "--out", str(out), "--fresh", *args], check=True,
                   capture_output=True, text=True, env=run_env())
    return time.perf_counter() - t0


def _runs(quick: bool) -> list[dict[str, Any]]:
    """End-to-end ``tce run`` of the paper's studies with and without figures, and, on Fig. 8
    and Fig. 10, the default choice of jobs against ``--jobs 1`` and ``--jobs 2`` and the
    program without dask against dask importable; variants interleaved, medians of repeats."""
    import tempfile

    root = Path(__file__).resolve().parents[2] / "studies"
    if not root.is_dir():
        return []
    rows: list[dict[str, Any]] = []
    repeats = 1 if quick else 3
    variants = {
        "default (no figures)": (["--no-plots"], True),
        "--jobs 1 (no figures)": (["--no-plots", "--jobs", "1"], True),
        "--jobs 2 (no figures)": (["--no-plots", "--jobs", "2"], True),
        "default, dask importable (no figures)": (["--no-plots"], False),
        "default, with figures": ([], True),
    }
    studies = ("fig7_8_inplane",) if quick else PAPER_STUDIES
    with tempfile.TemporaryDirectory() as tmp:
        for name in studies:
            chosen = variants if name in ("fig7_8_inplane", "fig10_dome") else {
                k: v for k, v in variants.items() if k in ("default (no figures)", "default, with figures")}
            if quick:
                chosen = {k: v for k, v in chosen.items() if "figures)" in k and "dask" not in k}
            times: dict[str, list[float]] = {k: [] for k in chosen}
            for _ in range(repeats):
                for label, (args, program) in chosen.items():
                    times[label].append(_tce_run(root / f"{name}.toml", Path(tmp), args, program))
            base = statistics.median(times["--jobs 1 (no figures)"]) if "--jobs 1 (no figures)" in times else None
            for label, ts in times.items():
                med = statistics.median(ts)
                rows.append(_row("runs", f"tce run {name}", label, n_solves=len(ts), time_s=med, time_min_s=min(ts),
                                 note="" if base is None else f"{med / base:.2f}x --jobs 1"))
    return rows


# ---------------------------------------------------------------- sweeps: whole runs in CPU time
#: Runs a command and prints the wall and CPU seconds of it and of every process it started
#: (Linux: this process becomes the child subreaper, so the fork server and the workers it
#: forked, re-parented here when their parent ends, are waited for and counted), the CPU of each
#: process (sampled from /proc every 50 ms: a process's last ticks may be missed) with its
#: parent, and the load average before and after.
_MEASURED = """
import ctypes, json, os, resource, subprocess, sys, threading, time
try:
    ctypes.CDLL(None).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER
except (AttributeError, OSError):
    pass
tick = os.sysconf("SC_CLK_TCK")
procs = {}  # pid -> [cpu s, first parent seen, command line]

def descendants():
    out, todo = [], [os.getpid()]
    while todo:
        p = todo.pop()
        try:
            for t in os.listdir(f"/proc/{p}/task"):
                with open(f"/proc/{p}/task/{t}/children") as fh:
                    kids = [int(c) for c in fh.read().split()]
                todo += kids
                out += kids
        except OSError:
            pass
    return out

def sample():
    for p in descendants():
        try:
            with open(f"/proc/{p}/stat") as fh:
                f = fh.read().rpartition(")")[2].split()
            if p not in procs:
                with open(f"/proc/{p}/cmdline", "rb") as fh:
                    procs[p] = [0.0, int(f[1]), fh.read().replace(b"\\0", b" ").decode(errors="replace")]
            procs[p][0] = (int(f[11]) + int(f[12])) / tick
        except (OSError, ValueError, IndexError):
            pass

stop = threading.Event()
def loop():
    while not stop.wait(0.05):
        sample()
load0 = os.getloadavg()[0]
t0 = time.perf_counter()
child = subprocess.Popen(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
sampler = threading.Thread(target=loop, daemon=True)
sampler.start()
out, err = child.communicate()
wall = time.perf_counter() - t0
own = resource.getrusage(resource.RUSAGE_CHILDREN)
while True:
    try:
        os.waitpid(-1, 0)
    except ChildProcessError:
        break
stop.set()
sampler.join()
r = resource.getrusage(resource.RUSAGE_CHILDREN)
procs[child.pid] = [own.ru_utime + own.ru_stime, os.getpid(), "tce run"]  # exact: reaped first
print(json.dumps(dict(wall=wall, cpu=r.ru_utime + r.ru_stime, rc=child.returncode, err=err[-2000:], root=child.pid,
                      procs=procs, load=[load0, os.getloadavg()[0]])))
"""


def critical_cpu(got: dict[str, Any]) -> float:
    """CPU seconds on the longest chain of a measured run (:func:`measured_run`): the ``tce run``
    process, the fork server's (serial: the parent waits for its imports) and the busiest
    worker forked from it, plus any other process it started. On an idle machine with a core
    per worker, the run's wall time would be about this; on a shared one, the ratio of two
    runs' critical CPU is the speed-up the work allows, which the wall time cannot show while
    other sessions hold the cores (the scheduler shares the CPU between sessions, not
    processes: Linux autogroups)."""
    procs = {int(k): v for k, v in got["procs"].items()}
    root = int(got["root"])
    server = [p for p, (_, parent, cmd) in procs.items() if parent == root and "forkserver" in cmd]
    workers = [v[0] for p, v in procs.items() if v[1] in server]
    others = [v[0] for p, v in procs.items() if p != root and p not in server and v[1] not in server]
    return procs[root][0] + sum(procs[p][0] for p in server) + max(workers, default=0.0) + sum(others)


def measured_run(study: Path, out: Path, args: Sequence[str]) -> dict[str, Any]:
    """``tce run STUDY --fresh ARGS`` in a fresh process: its wall time, the CPU time of it and
    of every process it started (``cpu``), the CPU of each process (``procs``), the CPU on the
    longest chain (``critical``, :func:`critical_cpu`), the load average before and after
    (``load``), whether the CPUs were free for figure drawers when it started (``cpu_free``,
    :func:`tce.plot.drawers.cpu_free`) and the solver time its results record (``solve_time``
    summed over scenarios: wall time inside the solve calls). The run's environment is
    :func:`run_env` (tce compiled)."""
    import xarray as xr

    from ..plot.drawers import cpu_free

    cmd = [sys.executable, "-m", "tce.cli", "-q", "run", str(study), "--out", str(out), "--fresh", *args]
    free = cpu_free()  # as tce run will find it: figures by the drawers or in the run's process
    done = subprocess.run([sys.executable, "-c", _MEASURED, *cmd], capture_output=True, text=True, check=True,
                          env=run_env())
    got = json.loads(done.stdout.strip().splitlines()[-1])
    if got["rc"] != 0:
        raise RuntimeError(f"tce run {study.name} failed: {got['err']}")
    got["critical"] = critical_cpu(got)
    got["cpu_free"] = free
    name = next(line.split("=", 1)[1].strip().strip('"') for line in study.read_text().splitlines()
                if line.strip().startswith("name"))
    with xr.open_dataset(out / name / "results.nc") as ds:
        got["solver"] = float(ds["solve_time"].sum())
        got["scenarios"] = int(ds.sizes["scenario"])
    return got


def solving_cpu(study: Path, every: int = 1) -> float:
    """CPU seconds of the load paths of every scenario of ``study`` in this process, as the
    runner solves them (a cold analysis per scenario) but without recording or writing: the
    solving a run cannot do without (the results' ``solve_time`` is wall time, which a shared
    machine stretches). ``every = k``: every k-th scenario, the sum times k (an estimate, for
    a large sweep)."""
    from ..analysis.loadpath import load_path
    from ..study.runner import _analysis, _cold
    from ..study.schema import load_study

    st = load_study(study)
    c0 = time.process_time()
    for sc in st.scenarios()[::every]:
        an = _cold(_analysis(sc, st.assembly(sc.structure)))
        load_path(an, settlements=sc.settlements, step=sc.loads["lambda_step"], atol=sc.loads["tolerance"],
                  lam_cap=sc.loads["lambda_cap"], loads=sc.loads_pattern)
    return (time.process_time() - c0) * every


#: the paper studies whose figures are held to 1.5x their own ``--no-plots`` run
FIGURE_STUDIES = ("fig7_8_inplane", "fig9_outofplane", "fig10_dome")
#: 50 settlement magnitudes instead of SWEEP_300's 5: 3,000 scenarios
MAGNITUDES_3000 = "[" + ", ".join(f"{0.5 + 0.05 * k:.2f}" for k in range(50)) + "]"


def _load(gs: Sequence[dict[str, Any]]) -> str:
    """The load average (1 min) over some measured runs: median and range."""
    loads = [x for g in gs for x in g["load"]]
    return f"load average {statistics.median(loads):.1f} ({min(loads):.1f}-{max(loads):.1f})"


def run_by_run(runs: Sequence[dict[str, Any]], base: Sequence[dict[str, Any]]) -> list[float]:
    """The wall time of each of ``runs`` over that of ``base`` in the same round (both from
    :func:`_interleaved`: round k of each variant is item k)."""
    return [g["wall"] / b["wall"] for g, b in zip(runs, base, strict=True)]


def _interleaved(study: Path, out: Path, variants: dict[str, list[str]], repeats: int) -> dict[str, list[dict[str, Any]]]:
    """``repeats`` measured runs (:func:`measured_run`) of each variant (``label -> tce run
    arguments``), interleaved, every other round in reverse order."""
    got: dict[str, list[dict[str, Any]]] = {k: [] for k in variants}
    for i in range(repeats):
        for label in (list(variants) if i % 2 == 0 else list(variants)[::-1]):
            got[label].append(measured_run(study, out, variants[label]))
    return got


def _sweeps(quick: bool) -> list[dict[str, Any]]:
    """Whole runs, each a fresh ``tce run --fresh`` (:func:`measured_run`), variants
    interleaved, medians of repeats, wall and CPU (of every process) with the load average:

    - the 300-scenario sweep of the paper's arch (10 frictions x 5 magnitudes x 6 settlement
      cases, no figures) with ``--jobs 1``, ``--jobs 2`` and the default; the CPU of the same
      load paths alone in this process (:func:`solving_cpu`) and the CPU on the longest chain
      of processes (:func:`critical_cpu`);
    - :data:`FIGURE_STUDIES` with ``--no-plots``, with figures (``--no-report``: drawn by the
      processes of :mod:`tce.plot.drawers`), with figures drawn in the run's process
      (``--no-report --jobs 1``) and as the default (figures and the calculation report with
      its PDF);
    - the share of CPU in solving of each paper study (the 3,000-scenario sweep's is section
      ``sweep3000``).

    ``--quick``: a 60-scenario sweep and Fig. 7-8, one repeat.
    """
    import tempfile

    rows: list[dict[str, Any]] = []
    repeats = 1 if quick else 3
    root = Path(__file__).resolve().parents[2] / "studies"
    with tempfile.TemporaryDirectory() as tmp:
        sweep = Path(tmp) / "sweep300.toml"
        text = SWEEP_300 if not quick else SWEEP_300.replace(
            "[0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2, 1.4, 1.7, 2.0]", "[0.5, 0.8]")
        sweep.write_text(text)
        variants = {"--jobs 1": ["--no-plots", "--jobs", "1"], "--jobs 2": ["--no-plots", "--jobs", "2"],
                    "default": ["--no-plots"]}
        got = _interleaved(sweep, Path(tmp) / "out", variants, repeats)
        base = statistics.median(g["wall"] for g in got["--jobs 1"])
        base_cpu = statistics.median(g["cpu"] for g in got["--jobs 1"])
        solving = solving_cpu(sweep)
        for label, gs in got.items():
            wall, cpu = statistics.median(g["wall"] for g in gs), statistics.median(g["cpu"] for g in gs)
            crit = statistics.median(g["critical"] for g in gs)
            solver = statistics.median(g["solver"] for g in gs)
            rows.append(_row("sweeps", f"sweep of {gs[0]['scenarios']} scenarios (arch, no figures)", label,
                             n_solves=len(gs), time_s=wall, time_min_s=min(g["wall"] for g in gs),
                             solver_time_s=solving, cpu_s=crit,
                             note=f"{base / wall:.2f}x faster than --jobs 1 (wall); CPU {cpu:.2f} s, "
                                  f"{cpu / solving:.1f}x the load paths' CPU ({solving:.2f} s), solving "
                                  f"{solving / cpu:.0%} of the CPU; longest chain {crit:.2f} CPU-s, "
                                  f"{base_cpu / crit:.2f}x faster than --jobs 1 by CPU; recorded solve_time "
                                  f"{solver:.2f} s (wall); {_load(gs)}"))
        for name in FIGURE_STUDIES[:1] if quick else FIGURE_STUDIES:
            study = root / f"{name}.toml"
            if not study.exists():
                continue
            kinds = {"--no-plots": ["--no-plots"], "figures (--no-report)": ["--no-report"],
                     "figures (--no-report), --jobs 1: drawn in the run's process": ["--no-report", "--jobs", "1"],
                     "figures and report (default)": []}
            # five rounds: a run of the arch takes about a second, and this machine's noise is 10-20%
            runs = _interleaved(study, Path(tmp) / "out", kinds, 1 if quick else 5)
            plain_cpu = statistics.median(g["cpu"] for g in runs["--no-plots"])
            plain_wall = statistics.median(g["wall"] for g in runs["--no-plots"])
            for label, gs in runs.items():
                cpu, wall = statistics.median(g["cpu"] for g in gs), statistics.median(g["wall"] for g in gs)
                paired = run_by_run(gs, runs["--no-plots"])
                rows.append(_row("sweeps", f"tce run {name}", label, n_solves=len(gs), time_s=wall,
                                 time_min_s=min(g["wall"] for g in gs), cpu_s=cpu,
                                 note=f"CPU {cpu:.2f} s, {cpu / plain_cpu:.2f}x --no-plots (CPU); wall "
                                      f"{wall / plain_wall:.2f}x --no-plots, {statistics.median(paired):.2f}x "
                                      f"({min(paired):.2f}-{max(paired):.2f}x) run by run in the same rounds; "
                                      f"drawers usable (CPUs free) in {sum(g['cpu_free'] for g in gs)} of "
                                      f"{len(gs)} runs; {_load(gs)}"))
        for name in () if quick else PAPER_STUDIES:
            if not (root / f"{name}.toml").exists():
                continue
            g = measured_run(root / f"{name}.toml", Path(tmp) / "out", ["--no-plots"])
            solving = solving_cpu(root / f"{name}.toml")
            rows.append(_row("sweeps", f"tce run {name}", "default (no figures): share of CPU in solving", n_solves=1,
                             time_s=g["wall"], solver_time_s=solving, cpu_s=g["cpu"],
                             note=f"CPU {g['cpu']:.2f} s, the load paths {solving:.2f} s: solving {solving / g['cpu']:.1%} "
                                  f"of the CPU; recorded solve_time {g['solver']:.3f} s (wall); {_load([g])}"))
    return rows


def _sweep3000(quick: bool) -> list[dict[str, Any]]:
    """The share of CPU in solving of a 3,000-scenario sweep of the paper's arch (10 frictions
    x 50 settlement magnitudes x 6 cases, no figures; one fresh ``tce run`` with the default
    jobs, :func:`measured_run`): the CPU of every process against the load paths of every
    tenth scenario timed alone in this process (:func:`solving_cpu`), times ten. ``--quick``:
    nothing (the run takes minutes)."""
    import tempfile

    rows: list[dict[str, Any]] = []
    if quick:
        return rows
    with tempfile.TemporaryDirectory() as tmp:
        big = Path(tmp) / "sweep3000.toml"
        # lambda_cap 1 (above every lambda_max of the sweep, 0.2-0.4: no path is capped) keeps the
        # study's bound on its solves (MAX_SOLVES) from refusing 3,000 uncapped paths
        big.write_text(SWEEP_300.replace('name = "sweep300"', 'name = "sweep3000"').replace(
            "[0.5, 1.0, 1.5, 2.0, 3.0]", MAGNITUDES_3000).replace("tolerance = 1e-6", "tolerance = 1e-6\nlambda_cap = 1.0"))
        g = measured_run(big, Path(tmp) / "out", ["--no-plots"])
        solving = solving_cpu(big, every=10)
        rows.append(_row("sweeps", f"sweep of {g['scenarios']} scenarios (arch, no figures)",
                         "default: share of CPU in solving", n_solves=1, time_s=g["wall"], solver_time_s=solving,
                         cpu_s=g["critical"],
                         note=f"CPU {g['cpu']:.1f} s, the load paths {solving:.1f} s (every 10th timed, x10): "
                              f"solving {solving / g['cpu']:.0%} of the CPU, {g['cpu'] / solving:.2f}x; longest "
                              f"chain {g['critical']:.1f} CPU-s; {_load([g])}"))
    return rows




# ---------------------------------------------------------------- scale: one large model, stage by stage
#: dome sizes (sectors = courses) of the scale section: 992 and 20,306 blocks (--quick: 992)
SCALE_SIZES, QUICK_SCALE_SIZES = (31, 142), (31,)


def _scale(quick: bool) -> list[dict[str, Any]]:
    """Memory and CPU of each stage of building and solving one large dome's lambda_max
    (:func:`tce.quality.scale.dome_stages`), each size in a fresh process, once (the 50k and
    100k rows of docs/scaling.md were run the same way, by hand, under an address-space limit)."""
    rows: list[dict[str, Any]] = []
    root = str(Path(__file__).resolve().parent.parent.parent)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([root, os.environ.get("PYTHONPATH", "")]))
    for n in QUICK_SCALE_SIZES if quick else SCALE_SIZES:
        done = subprocess.run([sys.executable, "-m", "tce.quality.scale", str(n)], capture_output=True, text=True,
                              env=env, timeout=7200)
        if done.returncode != 0:
            rows.append(_row("scale", f"dome {n} x {n}", "stages", note=f"failed: {done.stderr[-300:]}"))
            continue
        r = json.loads(done.stdout.strip().splitlines()[-1])
        solve = next(st for st in r["stages"] if st["stage"] == "Clarabel solved")
        build = sum(st["cpu_s"] for st in r["stages"][1:3])
        for st in r["stages"]:
            rows.append(_row("scale", f"dome {r['n_blocks']} blocks", st["stage"], solver="CLARABEL", model="spatial",
                             n_blocks=r["n_blocks"], time_s=st["cpu_s"], peak_mem_mb=1e3 * st["peak_gb"],
                             note=f"resident {st['rss_gb']:.2f} GB, peak {st['peak_gb']:.2f} GB; {r['n_contacts']} "
                                  f"contacts, {r['n_vars']} unknowns, {r['rows']} rows, nnz(A) {r['nnz_A']}; "
                                  f"{r['status']} in {r['iterations']} it; build {build:.1f} CPU-s, "
                                  f"solve {solve['cpu_s']:.1f} CPU-s"))
    return rows

# ---------------------------------------------------------------- past one machine: Dask
#: a sweep whose scenarios carry about half a CPU-second of solving each: a dome of 12 sectors x
#: 6 courses (84 blocks, 3D SOCP) under 6 frictions x 2 settlement cases
DASK_DOME_SWEEP = """
[study]
name = "dask_dome"
[structure]
type = "dome"
sectors = 12
courses = 6
[material]
friction = 0.8
[loads]
lambda_step = 0.05
tolerance = 1e-4
[sweep]
friction = [0.6, 0.7, 0.8, 0.9, 1.0, 1.2]
[scenarios.none]
[scenarios.one_outward]
s01 = [0.001, 0, 0, 0, 0, 0]
"""

#: the variants of the dask section: label -> ``tce run`` arguments (``--no-plots`` added)
DASK_VARIANTS = {
    "in-process (--jobs 1)": ["--jobs", "1"],
    "processes, 2 workers": ["--jobs", "2"],
    "dask LocalCluster, 1 worker": ["--backend", "dask", "--jobs", "1"],
    "dask LocalCluster, 2 workers": ["--backend", "dask", "--jobs", "2"],
}


def _dask(quick: bool) -> list[dict[str, Any]]:
    """Throughput against workers on the Dask route (``tce run --backend dask --jobs N``, a
    LocalCluster of N single-threaded worker processes) against the fork-server pool and the
    in-process run: a light sweep (the 60-scenario arch sweep of ``sweeps --quick``, about 10
    ms of solving a scenario) and a heavier one (:data:`DASK_DOME_SWEEP`, 12 dome scenarios);
    each run a fresh ``tce run --fresh --no-plots``, CPU of every process counted (cluster
    included), variants interleaved, medians (``--quick``: the heavy sweep only, one repeat)."""
    import importlib.util
    import tempfile

    if importlib.util.find_spec("distributed") is None:
        return [_row("dask", "dask not installed", "", note="pip install 'tce[dask]'")]
    return _dask_rows(quick)


def _dask_rows(quick: bool) -> list[dict[str, Any]]:
    import tempfile

    rows: list[dict[str, Any]] = []
    repeats = 1 if quick else 3
    light = SWEEP_300.replace("[0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2, 1.4, 1.7, 2.0]", "[0.5, 0.8]")
    sweeps = {"dome": DASK_DOME_SWEEP} if quick else {"arch": light, "dome": DASK_DOME_SWEEP}
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in sweeps.items():
            study = Path(tmp) / f"{name}.toml"
            study.write_text(text)
            got: dict[str, list[dict[str, float]]] = {k: [] for k in DASK_VARIANTS}
            for _ in range(repeats):
                for label, args in DASK_VARIANTS.items():
                    got[label].append(measured_run(study, Path(tmp) / "out", ["--no-plots", *args]))
            solving = solving_cpu(study)
            base = statistics.median(g["wall"] for g in got["in-process (--jobs 1)"])
            for label, gs in got.items():
                wall, cpu = statistics.median(g["wall"] for g in gs), statistics.median(g["cpu"] for g in gs)
                n = gs[0]["scenarios"]
                rows.append(_row("dask", f"{name} sweep of {n} scenarios (no figures)", label, n_solves=len(gs),
                                 time_s=wall, time_min_s=min(g["wall"] for g in gs), solver_time_s=solving,
                                 note=f"{n / wall:.2f} scenarios per wall s, {base / wall:.2f}x in-process; CPU "
                                      f"{cpu:.2f} s, {cpu - solving:.2f} s beyond the load paths' {solving:.2f} s"))
    return rows

# ---------------------------------------------------------------- model reduction
def _reduction(quick: bool) -> list[dict[str, Any]]:
    arch = semicircular_arch().validate()
    reps = 50 if quick else 200
    rows: list[dict[str, Any]] = []
    spatial, planar = build_model(arch, "spatial"), build_model(arch, "planar")
    W = arch.total_weight
    lam = 0.1

    def tce_row(case: str, method: str, model: Model, mat: Material, ref_h: float | None) -> float:
        s = TCESolver(model, mat)
        med, res, times = _timed(lambda i: s.solve(lam, 0.0, SETTLEMENT), reps)
        h = float(res[-1].support_wrenches[-1, 0])
        rows.append(
            _row("reduction", case, method, solver="CLARABEL", model=model.kind, n_blocks=len(arch.blocks),
                 n_solves=reps, time_s=med, time_min_s=min(times),
                 solver_time_s=statistics.median(r.solve_time for r in res),
                 error=np.nan if ref_h is None else abs(h - ref_h) / W, error_of="right thrust change / W",
                 residual=res[-1].eq_residual, note=f"right support Fx = {h:.5f} kN")
        )
        return h

    h = tce_row("in-plane scene, mu=0.8", "3D SOCP", spatial, Material(friction=FRICTION), None)
    tce_row("in-plane scene, mu=0.8", "planar LP", planar, Material(friction=FRICTION), h)
    tce_row("in-plane scene, mu=0.8", "3D Heyman (no cone, LP)", spatial, Material(), h)
    stiff = Material(friction=FRICTION, normal_stiffness=1e6, shear_stiffness=4e5)
    tce_row("in-plane scene, mu=0.8", "3D compliant (QP + cones)", spatial, stiff, h)
    h2 = tce_row("in-plane scene, mu=0.8, planar", "planar compliant (QP)", planar, stiff, None)
    tce_row("in-plane scene, mu=0.8, planar", "planar rigid (LP)", planar, Material(friction=FRICTION), h2)
    for alpha in (0.0, 90.0):
        ref = None
        for method, mat in (("lambda_max cone mu=0.8", Material(friction=FRICTION)), ("lambda_max Heyman", Material())):
            s = LimitSolver(spatial, mat)
            med, res, _ = _timed(lambda i: s.solve(alpha), 5 if quick else 30)  # noqa: B023
            lm = res[-1].lambda_max
            rows.append(
                _row("reduction", f"lambda_max alpha={alpha:g}", method, solver="CLARABEL", model="spatial",
                     n_blocks=len(arch.blocks), n_solves=len(res), time_s=med, solver_time_s=res[-1].solve_time,
                     error=np.nan if ref is None else abs(lm - ref), error_of="lambda_max change",
                     note=f"lambda_max={lm:.6f}")
            )
            ref = lm if ref is None else ref
    return rows


# ---------------------------------------------------------------- plotting
PLOT_STUDIES = ("fig3_4_settlements", "fig5_6_transversal", "fig7_8_inplane", "fig9_outofplane", "fig10_dome")
PLOT_JOBS = 2
_PLOT_RUN = """
import json, resource, shutil, sys, tempfile, time
from pathlib import Path
from tce.study.schema import load_study
from tce.plot import write_figures
from tce.study.runner import run_study
import xarray as xr
study, jobs, repeats = load_study(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
out = Path(tempfile.mkdtemp())
rows = []
for k in range(repeats):
    t, c = time.perf_counter(), time.process_time()
    report = run_study(study, out / str(k), jobs=jobs)
    solve, solve_cpu = time.perf_counter() - t, time.process_time() - c
    ds = xr.load_dataset(report.results)
    t, c = time.perf_counter(), time.process_time()
    files = write_figures(ds, out / str(k) / study.name, jobs=jobs)
    rows.append(dict(solve=solve, plot=time.perf_counter() - t, solve_cpu=solve_cpu, plot_cpu=time.process_time() - c,
                     files=len(files), n_solves=int(ds.n_solves.sum()), scenarios=int(ds.sizes["scenario"])))
from joblib.externals.loky import get_reusable_executor
get_reusable_executor().shutdown(wait=True)  # the workers' CPU time is the solving's (they only solved)
rows[0]["workers_cpu"] = sum(getattr(resource.getrusage(resource.RUSAGE_CHILDREN), f) for f in ("ru_utime", "ru_stime"))
shutil.rmtree(out, ignore_errors=True)
print(json.dumps(rows))
"""
SWEEP_300 = """
[study]
name = "sweep300"
[structure]
type = "semicircular_arch"
[material]
friction = 0.8
[loads]
lambda_step = 0.02
tolerance = 1e-6
[sweep]
friction = [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2, 1.4, 1.7, 2.0]
magnitude = [0.5, 1.0, 1.5, 2.0, 3.0]
[scenarios.none]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[scenarios.inward]
right = [-0.001, 0, 0, 0, 0, 0]
[scenarios.downward]
right = [0, 0, -0.001, 0, 0, 0]
[scenarios.transversal]
right = [0, 0.001, 0, 0, 0, 0]
[scenarios.rotation]
right = [0, 0, 0, 0.001, 0, 0]
"""


def _plot_run(study: Path, repeats: int, timeout: float) -> list[dict[str, Any]]:
    """Solve and plot ``study`` ``repeats`` times in one fresh process (see ``plotting``)."""
    env = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-c", _PLOT_RUN, str(study), str(PLOT_JOBS), str(repeats)],
                          capture_output=True, text=True, timeout=timeout, env=env, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def _plotting(quick: bool) -> list[dict[str, Any]]:
    """Plotting against solving and writing, per shipped paper study (and the 300-scenario sweep)."""
    import tempfile

    studies = Path(__file__).resolve().parents[2] / "studies"
    cases = [(name, studies / f"{name}.toml") for name in PLOT_STUDIES if (studies / f"{name}.toml").exists()]
    tmp = None
    if not quick:
        tmp = tempfile.TemporaryDirectory()
        sweep = Path(tmp.name) / "sweep300.toml"
        sweep.write_text(SWEEP_300)
        cases.append(("sweep300 (10 x 5 x 6 scenarios)", sweep))
    rows = []
    try:
        for name, path in cases:
            repeats = 1 if quick or name.startswith("sweep") else 3
            runs = _plot_run(path, repeats, timeout=7200)
            warm = runs[1:]
            first = runs[0]
            common = dict(n_solves=first["n_solves"])
            what = f"{first['scenarios']} scenarios, {first['files']} files"
            cpu_solve = first["solve_cpu"] + (first.get("workers_cpu", 0.0) if repeats == 1 else float("nan"))
            rows.append(_row("plotting", name, "solve + write (cold process, as tce run)", time_s=first["solve"],
                             note=f"{what}; CPU {cpu_solve:.2f} s (workers included)" if repeats == 1 else what,
                             **common))
            rows.append(_row("plotting", name, "figures + view (cold process, as tce run)", time_s=first["plot"],
                             note=f"{what}; CPU {first['plot_cpu']:.2f} s; plot / (solve + write) = "
                                  f"{first['plot'] / first['solve']:.2f} (wall)"
                                  + (f", {first['plot_cpu'] / cpu_solve:.2f} (CPU)" if repeats == 1 else ""),
                             **common))
            if warm:
                solve = statistics.median(r["solve"] for r in warm)
                plot = statistics.median(r["plot"] for r in warm)
                rows.append(_row("plotting", name, "solve + write (same process again: imports warm)", time_s=solve,
                                 note=what, **common))
                rows.append(_row("plotting", name, "figures + view (same process again: imports warm)", time_s=plot,
                                 note=f"{what}; plot / (solve + write) = {plot / solve:.2f} (wall)", **common))
    finally:
        if tmp is not None:
            tmp.cleanup()
    return rows


# ---------------------------------------------------------------- targets, outputs
def evaluate_targets(df: pd.DataFrame) -> list[tuple[str, str, bool]]:
    """The issue's targets as ``(target, measured figure, met)`` from a bench table."""
    out: list[tuple[str, str, bool]] = []
    ps = df[df.section == "per_solve"]

    def pick(model: str, method: str, solver: str = "CLARABEL") -> pd.Series | None:
        m = ps[(ps.model == model) & (ps.method.str.startswith(method)) & (ps.solver == solver)]
        return None if m.empty else m.iloc[0]

    d3, d2 = pick("spatial", "clarabel-direct (warm"), pick("planar", "clarabel-direct (warm")
    for variant in ("clarabel-direct (warm", "clarabel-direct, with refinement"):
        s3, s2 = pick("spatial", variant), pick("planar", variant)
        tag = "default" if variant.endswith("(warm") else "with refinement"
        if s3 is not None:
            out.append((f"3D SOCP arch solve <= 1.0 ms end to end ({tag})", f"{s3.time_s * 1e3:.3f} ms",
                        s3.time_s <= 1.0e-3))
        if s2 is not None:
            out.append((f"planar LP arch solve <= 0.3 ms ({tag})", f"{s2.time_s * 1e3:.3f} ms", s2.time_s <= 0.3e-3))
    for model, d in (("spatial", d3), ("planar", d2)):
        rb, pr = pick(model, "cvxpy built"), pick(model, "cvxpy param")
        if d is None or rb is None or pr is None:
            continue
        out.append((f"{model}: direct >= 10x faster than cvxpy built per solve (CLARABEL)",
                    f"{rb.time_s / d.time_s:.0f}x", rb.time_s / d.time_s >= 10))
        out.append((f"{model}: direct faster than parametrised cvxpy (CLARABEL)",
                    f"{pr.time_s / d.time_s:.1f}x", pr.time_s > d.time_s))
    hot = df[df.section == "hot_path"]
    for model in ("spatial", "planar"):
        h = hot[hot.model == model]
        mine, raw = h[h.method.str.startswith("tce")], h[h.method.str.startswith("clarabel")]
        if len(mine) and len(raw):
            r = float(mine.time_s.iloc[0] / raw.time_s.iloc[0])
            out.append((f"{model}: load-path solve <= 1.15x Clarabel's own update + solve (same run, interleaved)",
                        f"{r:.3f}x ({mine.time_s.iloc[0] * 1e3:.3f} / {raw.time_s.iloc[0] * 1e3:.3f} ms)", r <= 1.15))
    cost = df[df.section == "limit_cost"]
    for case, g in cost.groupby("case", sort=False):
        t = dict(zip(g.method, g.time_s))
        raw = t.get("clarabel set-up + solve (raw, same problem)")
        mine = t.get("tce direct lambda_max (LimitSolver.solve, no mechanism)")
        if raw and mine:
            out.append((f"{case}: direct lambda_max <= 1.3x one raw Clarabel set-up + solve (CPU, interleaved)",
                        f"{mine / raw:.3f}x ({mine * 1e3:.3f} / {raw * 1e3:.3f} ms)", mine <= 1.3 * raw))
        for tag, raw_tag in (("no canonical states", "no canonical states"),
                             ("with canonical states (the default)", "with the canonical QP of every admissible step"),
                             ("with canonical states (the default)",
                              "with the canonical QP of every admissible step, refined as tce's")):
            path = t.get(f"tce load path (direct bracket, no mechanism, {tag})")
            bis = t.get(f"hand-written bisection on raw clarabel ({raw_tag})")
            if path and bis:
                out.append((f"{case}: {g.model.iloc[0]} load path ({tag}) no slower than a hand-written bisection on raw "
                            f"Clarabel ({raw_tag}; CPU, interleaved)",
                            f"{path / bis:.3f}x ({path * 1e3:.2f} / {bis * 1e3:.2f} ms)", path <= bis))
    for case, g in df[df.section == "plotting"].groupby("case", sort=False):
        cold = {m.split(" (")[0]: t for m, t in zip(g.method, g.time_s) if "cold" in m}
        if len(cold) == 2:
            r = cold["figures + view"] / cold["solve + write"]
            out.append((f"{case}: plotting <= 0.3x solving + writing (as tce run --jobs {PLOT_JOBS})",
                        f"{r:.2f}x ({cold['figures + view']:.1f} s / {cold['solve + write']:.1f} s)", r <= 0.3))
    big = df[(df.section == "scaling") & (df.n_blocks >= 9000) & df.method.str.startswith("build")]
    for _, r in big.iterrows():
        out.append((f"{r.case}: one lambda_max solve < 60 s and < 4 GiB",
                    f"{r.time_s:.1f} s, {r.peak_mem_mb / 1024:.2f} GiB",
                    bool(r.time_s < 60 and r.peak_mem_mb < 4096)))
        out.append((f"{r.case}: building it (assembly, checks, model) <= 0.2x one lambda_max solve",
                    f"{r.build_s / r.time_s:.3f}x ({r.build_s:.2f} / {r.time_s:.1f} s)", bool(r.build_s <= 0.2 * r.time_s)))
    lp = df[df.section == "load_path"]
    for _, r in lp[lp.method.str.startswith("direct bracket") & ~lp.method.str.contains("refinement")].iterrows():
        tol = r.method.split("atol=")[1]
        bis = lp[lp.method == f"bisection atol={tol}"]
        if len(bis):
            b = bis.iloc[0]
            out.append((f"load path to {tol}: direct bracket takes fewer solves than bisection, same lambda_max within atol",
                        f"{r.n_solves:.0f} vs {b.n_solves:.0f} solves, time {r.time_s / b.time_s:.2f}x",
                        bool(r.n_solves < b.n_solves and abs(r.error - b.error) <= float(tol))))
    sw = df[df.section == "sweeps"]
    for case in sw.case.unique():
        g = sw[sw.case == case].set_index("method")
        if "figures (--no-report)" in g.index:
            plain, figs = g.loc["--no-plots"], g.loc["figures (--no-report)"]
            out.append((f"{case}: with figures at most 1.5x its own --no-plots run (CPU, every process)",
                        f"{figs.cpu_s / plain.cpu_s:.2f}x ({figs.cpu_s:.2f} / {plain.cpu_s:.2f} CPU-s; wall "
                        f"{figs.time_s / plain.time_s:.2f}x)", bool(figs.cpu_s <= 1.5 * plain.cpu_s)))
            # the drawers (tce.plot.drawers) overlap the figures' imports with the solve and split the
            # drawing: a gain in wall time only, which a machine busy with other sessions hides
            load = figs.note.rpartition("; ")[2]
            paired = next((p.partition(", ")[2] for p in figs.note.split("; ") if "run by run" in p), "")
            out.append((f"{case}: with figures at most 1.5x its own --no-plots run (wall)",
                        f"{figs.time_s / plain.time_s:.2f}x ({figs.time_s:.2f} / {plain.time_s:.2f} s; {load}"
                        f"{'; ' + paired if paired else ''})",
                        bool(figs.time_s <= 1.5 * plain.time_s)))
            here = next((g.loc[k] for k in g.index if k.startswith("figures (--no-report), --jobs 1")), None)
            if here is not None:
                out.append((f"{case}: figures by the drawers no slower than drawn in the run's process (--jobs 1; wall)",
                            f"{figs.time_s / here.time_s:.2f}x ({figs.time_s:.2f} / {here.time_s:.2f} s; CPU "
                            f"{figs.cpu_s / here.cpu_s:.2f}x)", bool(figs.time_s <= 1.05 * here.time_s)))
        if "--jobs 1" not in g.index:
            continue
        j1, j2, dflt = (g.time_s.get(k) for k in ("--jobs 1", "--jobs 2", "default"))
        load = g.note["--jobs 2"].rpartition("; ")[2]
        out.append((f"{case}: --jobs 2 at least 1.6x faster than --jobs 1 (wall)", f"{j1 / j2:.2f}x ({load})",
                    bool(j1 >= 1.6 * j2)))
        c1, c2 = g.cpu_s["--jobs 1"], g.cpu_s["--jobs 2"]
        out.append((f"{case}: --jobs 2 at least 1.6x faster than --jobs 1 (CPU on the longest chain of processes)",
                    f"{c1 / c2:.2f}x ({c1:.1f} / {c2:.1f} CPU-s)", bool(c1 >= 1.6 * c2)))
        out.append((f"{case}: the default no slower than --jobs 1 (wall)", f"{dflt / j1:.2f}x", bool(dflt <= 1.05 * j1)))
        cd = g.cpu_s["default"]
        out.append((f"{case}: the default no slower than --jobs 1 (CPU on the longest chain)", f"{cd / c1:.2f}x",
                    bool(cd <= 1.05 * c1)))
        cpu = float(g.note["--jobs 1"].split("CPU ")[1].split(" s")[0])
        solver = float(g.solver_time_s["--jobs 1"])
        out.append((f"{case}: --jobs 1 at most 3x its own solving (CPU of the run / CPU of its load paths)",
                    f"{cpu / solver:.1f}x ({cpu:.1f} / {solver:.2f} s)", bool(cpu <= 3 * solver)))
    runs = df[df.section == "runs"]
    for case in runs.case.unique():
        g = runs[runs.case == case].set_index("method").time_s
        if "--jobs 1 (no figures)" in g:
            out.append((f"{case}: default jobs no slower than --jobs 1 (no figures)",
                        f"{g['default (no figures)'] / g['--jobs 1 (no figures)']:.2f}x",
                        bool(g["default (no figures)"] <= 1.05 * g["--jobs 1 (no figures)"])))
    return out


def _fmt(v: Any) -> str:
    if isinstance(v, float | np.floating):
        if not np.isfinite(v):
            return "" if np.isnan(v) else str(v)
        return f"{v:.3g}"
    return str(v)


def to_markdown(df: pd.DataFrame, machine: str = "") -> str:
    """The bench table as Markdown (times in ms), followed by the targets."""
    cols = ["section", "case", "method", "solver", "model", "n_solves", "time_ms", "build_ms", "solver_ms", "ratio",
            "error", "error_of", "residual", "peak_mem_mb", "cpu_s", "note"]
    t = df.assign(time_ms=df.time_s * 1e3, build_ms=df.build_s * 1e3, solver_ms=df.solver_time_s * 1e3)
    lines = [f"Machine: {machine}", ""] if machine else []
    lines += ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for _, r in t.iterrows():
        lines.append("| " + " | ".join(_fmt(r[c]) for c in cols) + " |")
    lines += ["", "| target | measured | met |", "|---|---|---|"]
    lines += [f"| {a} | {b} | {'yes' if ok else 'no'} |" for a, b, ok in evaluate_targets(df)]
    return "\n".join(lines) + "\n"


def _plot(df: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5))
    d = df[np.isfinite(df.error) & np.isfinite(df.time_s)]
    family = np.select(
        [d.method.str.startswith("cvxpy built"), d.method.str.startswith("cvxpy param"), d.method.str.startswith("pyramid")],
        ["cvxpy built per solve", "cvxpy parametrised", "pyramid LP"], "direct",
    )
    markers = {"direct": "o", "cvxpy built per solve": "x", "cvxpy parametrised": "^", "pyramid LP": "s"}
    for (section, fam, solver), g in d.assign(family=family).groupby(["section", "family", "solver"]):
        ax.scatter(g.time_s * 1e3, np.maximum(g.error, 1e-16), marker=markers[fam], s=24,
                   label=f"{section}: {fam} ({solver})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median time per call (ms)")
    ax.set_ylabel("error (see error_of; floored at 1e-16)")
    ax.set_title("tce bench: speed against error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def _machine() -> str:
    import platform

    import clarabel
    import cvxpy

    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as fh:
            cpu = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return (f"{cpu}, {os.cpu_count()} cores; Python {platform.python_version()}, numpy {np.__version__}, "
            f"clarabel {clarabel.__version__}, cvxpy {cvxpy.__version__}")


SECTIONS: dict[str, Callable[[bool], list[dict[str, Any]]]] = {
    "per_solve": _per_solve,
    "hot_path": _hot_path,
    "limit": _limit_rows,
    "limit_cost": _limit_cost,
    "load_path": _load_path,
    "canonical": _canonical,
    "discretisation": _discretisation,
    "scaling": _scaling,
    "runs": _runs,
    "sweeps": _sweeps,
    "sweep3000": _sweep3000,
    "dask": _dask,
    "scale": _scale,
    "reduction": _reduction,
    "plotting": _plotting,
}


def run_bench(out_dir: Path = Path("results/bench"), quick: bool = False,
              sections: Sequence[str] | None = None) -> pd.DataFrame:
    """Run the bench and write ``bench.csv``, ``bench.md`` and ``speed_error.png`` in ``out_dir``.

    Parameters
    ----------
    out_dir : Path
        Output folder (created).
    quick : bool
        A reduced run (fewer repeats and sizes) that takes well under a minute.
    sections : sequence of str, optional
        Subset of :data:`SECTIONS` (default: all).

    Returns
    -------
    pandas.DataFrame
        One row per measurement, columns :data:`COLUMNS`.
    """
    names = list(sections or SECTIONS)
    unknown = set(names) - set(SECTIONS)
    if unknown:
        raise ValueError(f"unknown bench sections {sorted(unknown)}; choose from {list(SECTIONS)}")
    rows: list[dict[str, Any]] = []
    for name in track(names, "bench", unit="section"):
        rows += SECTIONS[name](quick)
    df = pd.DataFrame(rows, columns=COLUMNS)
    base = df[(df.section == "per_solve") & (df.model == "spatial") & df.method.str.startswith("clarabel-direct (warm")]
    if not base.empty:
        df["ratio"] = df.time_s / float(base.time_s.iloc[0])
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    df.to_csv(out_dir / "bench.csv", index=False)
    (out_dir / "bench.md").write_text(to_markdown(df, _machine()))
    _plot(df, out_dir / "speed_error.png")
    return df


def add_bench_arguments(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Options of ``tce bench``: ``--out``, ``--quick``, ``--section`` (repeatable)."""
    parser.add_argument("--out", type=Path, default=Path("results/bench"), help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced run (< 60 s)")
    parser.add_argument("--section", action="append", choices=list(SECTIONS), help="run only these sections")
    return parser


def bench_command(args: argparse.Namespace) -> int:
    """Entry point of ``tce bench``: run, print the Markdown table and where files went."""
    out = Path(getattr(args, "out", None) or "results/bench")
    df = run_bench(out, quick=bool(getattr(args, "quick", False)), sections=getattr(args, "section", None))
    print((out / "bench.md").read_text())
    print(f"wrote {out / 'bench.csv'}, {out / 'bench.md'}, {out / 'speed_error.png'} ({len(df)} rows)")
    return 0
