"""``tce bench``: the time of the solves a user runs against their error, on this machine.

The sections :func:`run_bench` measures, in one table (:data:`COLUMNS`) printed by
:func:`report`:

``solve``
    One TCE solve of the paper's arch (16 blocks, the right support spreading 1 mm, ``lam``
    cycling over :data:`LAMS`) for each model (3D SOCP, planar LP) and contact law
    (:data:`LAWS`): :class:`tce.core.solve.TCESolver` at its default and a loose tolerance,
    and :class:`tce.core.cvx.CvxTCE` with each installed solver. ``error``: the largest
    in-plane support reaction ``(Fx, Fz, My)`` against tolerance 1e-12, over the total weight
    (the out-of-plane components carry a free self-stress in 3D).
``hot_path``
    A load path's solve of the same arch (:meth:`tce.core.analysis.Analysis.path`, friction
    0.8) against Clarabel's own ``update(b) + solve()`` of the same solver object, interleaved
    call by call, CPU time: the status read (what the path's decisions read) and the canonical
    state read (what a stored step costs, ``docs/conventions.md``); with the right support
    spreading 1 mm (``error`` as in ``solve``) and without a support motion (every admissible
    state optimal, the raw solve an LP with zero objective; ``error``: the vertical reactions'
    sum against the weight, over the weight, the thrust not being unique).
``limit``
    :class:`tce.core.limit.LimitSolver` on the same arch, each model and law, at ``alpha`` 0
    and 90, against tolerance 1e-12; and the friction pyramids of ``k`` sides
    (:func:`tce.core.pyramid.pyramid_lambda_max`) that bracket the cone's lambda_max where
    sliding governs (friction 0.5, ``alpha = 45``).
``load_path``
    :func:`tce.analysis.loadpath.load_path` (step 0.02) to each bisection tolerance, with the
    direct bracket and with plain bisection: solves, time (to lambda_max: the steps' states
    are not read), error of lambda_max against the direct limit at tolerance 1e-12.
``scaling``
    Arches and domes of about 100, 1,000 and 10,000 blocks, each in a fresh process: build
    and solve times, peak resident memory, fitted growth of the solve time.
``reliability``
    Samples of the paper's arch that keep its geometry (:func:`reliability_case`: a 1 kN point
    load at ``x = -0.25`` m, friction lognormal, unit weight normal). The CPU time per sample
    of :class:`tce.analysis.reliability.WarmLimit` against one direct-limit solve of the same
    problem (:func:`tce.core.problem.limit_problem`, built beforehand) on raw Clarabel, a new
    ``clarabel.DefaultSolver`` set up and solved per sample, in interleaved rounds, with the
    samples as one batch of :class:`tce.analysis.batched.BatchedLimit` beside them where the
    extra ``batched`` is installed (``error``: the largest difference of lambda_max).
    :data:`RELIABILITY_SAMPLES` samples in one call (``error``: the half-width of the 95 %
    Clopper-Pearson interval of ``P(capacity < RELIABILITY_THRESHOLD)``). Samples in chunks of
    :data:`RELIABILITY_CHUNK`, each a cold ``WarmLimit`` (:func:`reliability_chunk`), in
    process, in 1 and 2 worker processes (``concurrent.futures``, spawned) and on a Dask
    ``LocalCluster`` of 2 workers (a note without ``dask[distributed]``): ``time_s`` is the
    second pass on the started workers, ``build_s`` what the first pass cost more (their
    start), ``error`` the largest difference from the in-process capacities.

Times are medians of repeated calls after one warm-up (wall clock, ``hot_path`` CPU time; s
in the table, ms in the report); a ``solve`` row's time includes reading the state it is judged
by. The report's first line names the day, the commit and the load it was measured at.
"""

from __future__ import annotations

import gc
import importlib.util
import itertools
import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import pandas as pd

from ..analysis.reliability import JointDistribution, RandomVariable, WarmLimit, evaluate, failure_probability
from ..core.limit import LimitSolver
from ..core.material import Material
from ..core.model import build_model
from ..core.pyramid import pyramid_lambda_max
from ..core.solve import SolverOptions, TCESolver
from ..structures.arch import semicircular_arch
from ..study.progress import track

__all__ = ["COLUMNS", "SECTIONS", "growth_exponent", "median_time", "reliability_case", "reliability_chunk",
           "reliability_joint", "report", "row", "run_bench", "scaling_case"]

FRICTION = 0.8
#: load multipliers the ``solve`` section cycles over
LAMS = (0.0, 0.05, 0.1, 0.15, 0.2)
#: the right support spreading 1 mm (m)
SETTLEMENT = {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}
IN_PLANE = [0, 2, 4]  # Fx, Fz, My of a support wrench: unique; Fy, Mx, Mz carry a free self-stress in 3D
REFERENCE = SolverOptions(tol=1e-12, residual_tol=1e-9)
MODELS = {"spatial": "3D SOCP", "planar": "planar LP"}
#: the contact laws of the ``solve`` and ``limit`` sections (stiffnesses in kN/m^3)
LAWS = {
    "friction 0.8": Material(friction=FRICTION),
    "Heyman (no sliding)": Material(),
    "compliant, friction 0.8": Material(friction=FRICTION, normal_stiffness=1e6, shear_stiffness=4e5),
}
#: sizes of the ``scaling`` section (arch: voussoirs; dome: sectors = courses)
SCALING_SIZES = {"arch": (98, 998, 9998), "dome": (10, 31, 100)}
QUICK_SCALING_SIZES = {"arch": (98, 298), "dome": (6, 10)}
COLUMNS = ["section", "case", "method", "model", "n_blocks", "n_solves", "time_s", "build_s", "error", "error_of",
           "peak_mem_mb", "note"]


def median_time(fn: Callable[[int], Any], repeats: int) -> tuple[float, list[Any]]:
    """Median wall time (s) of ``fn(i)`` over ``repeats`` calls after one warm-up call, and the answers."""
    fn(0)
    gc.collect()
    out, times = [], []
    for i in range(repeats):
        t0 = time.perf_counter()
        out.append(fn(i))
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def row(section: str, case: str, method: str, **kw: Any) -> dict[str, Any]:
    """One row of the bench table: :data:`COLUMNS`, NaN or empty where ``kw`` gives no value."""
    row: dict[str, Any] = dict.fromkeys(COLUMNS, np.nan)
    row.update(section=section, case=case, method=method, model="", error_of="", note="")
    row.update(kw)
    return row


def growth_exponent(n: Sequence[float], t: Sequence[float]) -> float:
    """Least-squares slope of ``log t`` against ``log n`` (NaN with fewer than 2 positive points)."""
    n_, t_ = np.asarray(n, dtype=float), np.asarray(t, dtype=float)
    ok = (n_ > 0) & (t_ > 0) & np.isfinite(t_)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(n_[ok]), np.log(t_[ok]), 1)[0])


# ---------------------------------------------------------------- one TCE solve
def _with_state(r: Any) -> Any:
    """``r`` with its state read (a TCE result selects its canonical state on first read)."""
    r.state  # noqa: B018
    return r


def _solve(quick: bool) -> list[dict[str, Any]]:
    """One TCE solve, each model and contact law, direct and through cvxpy (module doc)."""
    import cvxpy as cp

    from ..core.cvx import CvxTCE

    arch = semicircular_arch().validate()
    W = arch.total_weight
    reps, cvx_reps = (30, 5) if quick else (200, 50)
    solvers = ["CLARABEL"] if quick else [s for s in ("CLARABEL", "ECOS", "SCS", "HIGHS") if s in cp.installed_solvers()]
    rows: list[dict[str, Any]] = []
    for kind, label in MODELS.items():
        model = build_model(arch, kind)
        for law, mat in LAWS.items():
            ref_solver = TCESolver(model, mat, REFERENCE)
            ref = [ref_solver.solve(lam, 0.0, SETTLEMENT) for lam in LAMS]

            def add(method: str, fn: Callable[[int], Any], n: int) -> None:
                med, res = median_time(fn, n)
                ok = all(r.status == "optimal" for r in res)
                err = max(float(np.abs(r.support_wrenches - ref[i % len(LAMS)].support_wrenches)[:, IN_PLANE].max())
                          for i, r in enumerate(res)) / W if ok else np.inf
                thrust = ref[LAMS.index(0.1)].support_wrenches[arch.support_names.index("right"), 0]
                rows.append(row("solve", f"arch, {label}, {law}", method, model=kind, n_blocks=len(arch.blocks),
                                 n_solves=n, time_s=med, error=err, error_of="in-plane reactions / W",
                                 note=f"right support Fx at lam 0.1: {thrust:.5f} kN" if ok else "not all optimal"))

            for method, options in (("clarabel-direct", None),
                                    ("clarabel-direct, tol 1e-8", SolverOptions(tol=1e-8, residual_tol=1e-7))):
                direct = TCESolver(model, mat, options)
                add(method, lambda i, d=direct: _with_state(d.solve(LAMS[i % len(LAMS)], 0.0, SETTLEMENT)), reps)
            if law != "friction 0.8":
                continue
            for name in [s for s in solvers if s != "HIGHS" or kind == "planar"]:
                param = CvxTCE(model, mat)
                add(f"cvxpy parametrised, {name}",
                    lambda i, p=param, s=name: p.solve(LAMS[i % len(LAMS)], 0.0, SETTLEMENT, solver=s), cvx_reps)
    return rows


# ---------------------------------------------------------------- against raw Clarabel
#: the ``hot_path`` section's support motions: the right support spreading 1 mm (a thin optimal
#: face), and none (every admissible state optimal: the raw solve is an LP with zero objective)
HOT_PATH_SCENES = {"1 mm spreading": SETTLEMENT, "no support motion": None}


def _hot_path(quick: bool) -> list[dict[str, Any]]:
    """A load path's solve against Clarabel's own ``update(b) + solve()`` on the same data (module doc)."""
    from ..core.analysis import Analysis
    from ..core.problem import tce_b

    arch = semicircular_arch().validate()
    W = arch.total_weight
    reps = 150 if quick else 1000
    clock = time.process_time
    rows: list[dict[str, Any]] = []
    for (kind, label), (scene, motion) in itertools.product(MODELS.items(), HOT_PATH_SCENES.items()):
        an = Analysis(arch, LAWS["friction 0.8"], model=kind)
        solve = an.path(0.0, motion)
        solve(LAMS[0]).forces  # noqa: B018 (sets up the warm solvers)
        solver = an.solver(kind)
        f = solver.formulation
        raw = solver._warm._solver  # the very Clarabel object tce's solve drives
        data = [tce_b(f, solver.rhs(lam, 0.0)) for lam in LAMS]
        ref = [TCESolver(solver.model, solver.material, REFERENCE).solve(lam, 0.0, motion) for lam in LAMS if motion]
        times: dict[str, list[float]] = {"status": [], "state": [], "raw": []}
        err = dict.fromkeys(times, 0.0)
        for i in range(reps):
            j = i % len(LAMS)
            t0 = clock()
            r = solve(LAMS[j])
            ok = r.status == "optimal"
            t1 = clock()
            s = solve(LAMS[j])
            s.forces  # noqa: B018 (selects the canonical state)
            t2 = clock()
            raw.update(b=data[j])
            x = np.asarray(raw.solve().x)
            t3 = clock()
            for name, t in (("status", t1 - t0), ("state", t2 - t1), ("raw", t3 - t2)):
                times[name].append(t)
            wrench = {"status": r.optimum.support_wrenches if ok else np.full_like(s.support_wrenches, np.inf),
                      "state": s.support_wrenches,
                      "raw": (solver.model.B_sup @ f.forces(x)).reshape(-1, 6)}
            for name, w in wrench.items():
                # without a motion the thrust is not unique: the solver's point is judged by the weight alone
                off = abs(w[:, 2].sum() - W) if motion is None else np.abs(w - ref[j].support_wrenches)[:, IN_PLANE].max()
                err[name] = max(err[name], float(off) / W)
        med = {k: statistics.median(v) for k, v in times.items()}
        methods = {"status": "tce load-path solve, status read (its decisions)",
                   "state": "tce load-path solve, canonical state read (a stored step)",
                   "raw": "clarabel update(b) + solve (raw, same solver object)"}
        for name, method in methods.items():
            rows.append(row("hot_path", f"arch, {label}, friction 0.8, {scene}", method, model=kind,
                            n_blocks=len(arch.blocks), n_solves=reps, time_s=med[name], error=err[name],
                            error_of="vertical reactions - W, / W" if motion is None else "in-plane reactions / W",
                            note=f"{med[name] / med['raw']:.2f}x raw (CPU time, interleaved)"))
    return rows


# ---------------------------------------------------------------- lambda_max
def _limit(quick: bool) -> list[dict[str, Any]]:
    """Direct lambda_max of each model and law, and the friction pyramids' bracket (module doc)."""
    arch = semicircular_arch().validate()
    reps = 5 if quick else 30
    rows: list[dict[str, Any]] = []
    for kind, label in MODELS.items():
        model = build_model(arch, kind)
        for law in ("friction 0.8", "Heyman (no sliding)"):
            for alpha in (0.0, 90.0) if kind == "spatial" else (0.0,):
                ref = LimitSolver(model, LAWS[law], tol=1e-12).solve(alpha).lambda_max
                solver = LimitSolver(model, LAWS[law])
                med, res = median_time(lambda i, s=solver, a=alpha: s.solve(a), reps)
                rows.append(row("limit", f"arch, {label}, {law}, alpha {alpha:g}", "direct lambda_max", model=kind,
                                 n_blocks=len(arch.blocks), n_solves=reps, time_s=med,
                                 error=abs(res[-1].lambda_max - ref), error_of="lambda_max",
                                 note=f"lambda_max {ref:.6f}"))
    model, mu, alpha = build_model(arch, "spatial"), 0.5, 45.0
    case = f"arch, 3D SOCP, friction {mu}, alpha {alpha:g}"
    ref = LimitSolver(model, Material(friction=mu), tol=1e-12).solve(alpha).lambda_max
    solver = LimitSolver(model, Material(friction=mu))
    med, res = median_time(lambda i: solver.solve(alpha), reps)
    rows.append(row("limit", case, "direct lambda_max (cone)", model="spatial", n_blocks=len(arch.blocks),
                     n_solves=reps, time_s=med, error=abs(res[-1].lambda_max - ref), error_of="lambda_max",
                     note=f"lambda_max {ref:.6f}"))
    for k in (4, 16) if quick else (4, 8, 16, 32, 64):
        got = {}
        for side in ("inscribed", "circumscribed"):
            med, res = median_time(lambda i, s=side: pyramid_lambda_max(model, mu, alpha, k, s), reps)
            got[side] = (med, res[-1].lambda_max)
        width = got["circumscribed"][1] - got["inscribed"][1]
        for side, (med, lam) in got.items():
            rows.append(row("limit", case, f"pyramid {side}, {k} sides (LP)", model="spatial",
                             n_blocks=len(arch.blocks), n_solves=reps, time_s=med, error=abs(lam - ref),
                             error_of="lambda_max", note=f"bracket width {width:.3g}"))
    return rows


# ---------------------------------------------------------------- load path
def _load_path(quick: bool) -> list[dict[str, Any]]:
    """Load paths to each tolerance, direct bracket against plain bisection, interleaved (module doc)."""
    from ..analysis.loadpath import load_path
    from ..core.analysis import Analysis

    arch = semicircular_arch().validate()
    mat = LAWS["friction 0.8"]
    ref = LimitSolver(build_model(arch, "planar"), mat, tol=1e-12).solve(0.0).lambda_max
    rows: list[dict[str, Any]] = []
    for atol in (1e-2, 1e-4, 1e-6, 1e-8) if quick else (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8):
        times: dict[str, list[float]] = {"direct": [], "bisection": []}
        res: dict[str, Any] = {}
        for _ in range(1 if quick else 3):
            for bracket in times:
                an = Analysis(arch, mat)
                t0 = time.perf_counter()
                res[bracket] = load_path(an, 0.0, SETTLEMENT, step=0.02, atol=atol, bracket=bracket)
                times[bracket].append(time.perf_counter() - t0)
        for bracket, r in res.items():
            rows.append(row("load_path", "arch in plane, 1 mm spreading, step 0.02",
                             f"{'direct bracket' if bracket == 'direct' else 'bisection'}, atol {atol:g}",
                             model=r.steps[-1].model, n_blocks=len(arch.blocks), n_solves=r.n_solves,
                             time_s=statistics.median(times[bracket]), error=abs(r.lambda_max - ref),
                             error_of="lambda_max vs direct limit", note=f"{r.outcome}; gap {r.gap:.2g}"))
    return rows


# ---------------------------------------------------------------- scaling
def scaling_case(structure: str, size: int, friction: float = FRICTION) -> dict[str, Any]:
    """Build one structure and time one direct lambda_max (call it in a fresh process).

    Parameters
    ----------
    structure : {"arch", "dome"}
        A semicircular arch of ``size`` voussoirs (``alpha = 90``) or a hemispherical dome of
        ``size`` sectors and courses (``alpha = 0``).
    size : int
    friction : float

    Returns
    -------
    dict
        ``n_blocks``, ``n_vars``, ``status``, ``lambda_max``, the wall times (s) ``t_build``
        (generation, checks, model) and ``t_solve``, and ``peak_mem_mb``, the process's peak
        resident memory (MB).
    """
    import resource

    from ..structures.dome import hemispherical_dome

    t0 = time.perf_counter()
    a = semicircular_arch(voussoirs=size) if structure == "arch" else hemispherical_dome(sectors=size, courses=size)
    model = build_model(a.validate(), "spatial")
    t1 = time.perf_counter()
    res = LimitSolver(model, Material(friction=friction)).solve(90.0 if structure == "arch" else 0.0)
    t2 = time.perf_counter()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux
    return dict(n_blocks=len(a.blocks), n_vars=model.n_vars, status=res.status, lambda_max=res.lambda_max,
                t_build=t1 - t0, t_solve=t2 - t1, peak_mem_mb=peak)


def _fresh_case(structure: str, size: int, timeout: float) -> dict[str, Any] | None:
    """:func:`scaling_case` in a fresh Python process (None if it fails or times out)."""
    code = f"import json, tce.quality.bench as b; print(json.dumps(b.scaling_case({structure!r}, {size})))"
    try:
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout,
                             check=True, env=dict(os.environ))
    except (subprocess.TimeoutExpired, subprocess.CalledProcessError):
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


def _scaling(quick: bool) -> list[dict[str, Any]]:
    """Build and one lambda_max against size, each in a fresh process, sizes interleaved (module doc)."""
    rows: list[dict[str, Any]] = []
    repeats = 1 if quick else 3
    for structure, sizes in (QUICK_SCALING_SIZES if quick else SCALING_SIZES).items():
        runs: dict[int, list[dict[str, Any]]] = {n: [] for n in sizes}
        for _ in range(repeats):
            for n in sizes:
                got = _fresh_case(structure, n, timeout=120 if quick else 1800)
                if got is not None:
                    runs[n].append(got)
        first = len(rows)
        for n, got in runs.items():
            if not got:
                rows.append(row("scaling", f"{structure} of size {n}", "build + lambda_max", note="failed or timed out"))
                continue
            med = {k: statistics.median(g[k] for g in got) for k in ("t_build", "t_solve", "peak_mem_mb")}
            rows.append(row("scaling", f"{structure}, 3D SOCP", "build + lambda_max", model="spatial",
                             n_blocks=got[0]["n_blocks"], n_solves=len(got), time_s=med["t_solve"],
                             build_s=med["t_build"], peak_mem_mb=med["peak_mem_mb"],
                             note=f"{got[0]['status']}, {got[0]['n_vars']} unknowns"))
        done = [r for r in rows[first:] if np.isfinite(r["time_s"])]
        e = growth_exponent([r["n_blocks"] for r in done], [r["time_s"] for r in done])
        for r in rows[first:]:
            r["note"] += f"; solve ~ n^{e:.2f}"
    return rows


# ---------------------------------------------------------------- reliability
#: the ``reliability`` section's failure threshold: a collapse load of the 1 kN point load below 0.8 kN
RELIABILITY_THRESHOLD = 0.8
#: samples of the one-call row (``--quick``: a fifth); each throughput run takes half (``--quick``: a tenth)
RELIABILITY_SAMPLES = 10_000
#: samples per job of the throughput rows (the study layout's default ``chunk``)
RELIABILITY_CHUNK = 250
UNIT_WEIGHT = 20.0  # kN/m^3, the paper's arch


def reliability_joint() -> JointDistribution:
    """The section's inputs: friction lognormal (mean 0.6, c.o.v. 0.15) and unit weight normal
    (mean 20 kN/m^3, std 1 kN/m^3), independent."""
    return JointDistribution([RandomVariable("friction", "lognormal", 0.6, cov=0.15),
                              RandomVariable("unit_weight", "normal", UNIT_WEIGHT, std=1.0)])


def reliability_case(kind: str = "planar") -> WarmLimit:
    """A :class:`tce.analysis.reliability.WarmLimit` of the paper's arch (14 voussoirs, friction
    0.6) under a live point load of 1 kN downwards on the extrados at ``x = -0.25`` m
    (``studies/arch_point_load.toml``'s critical position of its grid): lambda_max is the
    collapse load in kN. Sample keys ``mu`` (friction) and ``g`` (unit weight over 20 kN/m^3,
    the fixed load factor); :func:`_warm_samples` makes them from physical values."""
    from ..core.analysis import Analysis
    from ..core.loads import LoadPattern, PointLoad

    loads = LoadPattern(lateral=False, point=[PointLoad(force=[0.0, 0.0, -1.0], on_top=(-0.25, 0.0))])
    analysis = Analysis(semicircular_arch(), Material(friction=0.6), model=kind)
    return WarmLimit(analysis, {"mu": "friction", "g": "fixed_factor"}, loads=loads)


def _warm_samples(x: np.ndarray) -> list[dict[str, float]]:
    """``(n, 2)`` physical values (friction, unit weight in kN/m^3) as :func:`reliability_case` samples."""
    return [{"mu": float(mu), "g": float(gamma) / UNIT_WEIGHT} for mu, gamma in np.atleast_2d(x)]


def reliability_chunk(kind: str, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Statuses and capacities (kN; :func:`tce.analysis.reliability.outcome_value`) of the
    samples ``x`` ``(n, 2)`` by a cold :func:`reliability_case`: one job of the throughput rows."""
    return evaluate(reliability_case(kind), _warm_samples(x))


def _raw_limit(problem: Any, settings: Any) -> float:
    """lambda_max of a limit problem by a new Clarabel solver set up and solved (NaN unless solved)."""
    import clarabel

    from ..core.clarabel_solver import _cones

    sol = clarabel.DefaultSolver(problem.P, problem.q, problem.A, problem.b, _cones(problem), settings).solve()
    return float(sol.x[-1]) if str(sol.status) == "Solved" else float("nan")


def _reliability_cost(quick: bool) -> list[dict[str, Any]]:
    """WarmLimit per sample against raw Clarabel per sample (and the samples as one Moreau batch
    where the extra ``batched`` is installed), CPU time, interleaved rounds."""
    from ..core.problem import Formulation, limit_problem

    n, rounds = (60, 3) if quick else (200, 8)
    x = reliability_joint().sample(n, "lhs", seed=1)[1]
    have_moreau = importlib.util.find_spec("moreau") is not None
    methods = {"raw": "raw clarabel: a new solver set up and solved per sample",
               "warm": "WarmLimit sample (update, solve, checks)",
               "batched": "BatchedLimit: the samples as one Moreau batch (CPU), checks"}
    rows: list[dict[str, Any]] = []
    for kind, label in MODELS.items():
        warm = reliability_case(kind)
        samples = _warm_samples(x)
        problems = [limit_problem(Formulation(warm.model, Material(friction=s["mu"])), warm.b_fixed * s["g"],
                                  warm.b_live) for s in samples]
        runs = {"raw": lambda: [_raw_limit(p, warm.settings) for p in problems],
                "warm": lambda: [warm(s)[1] for s in samples]}
        if have_moreau:
            from ..analysis.batched import BatchedLimit

            batched = BatchedLimit(warm, batch_size=n)
            runs["batched"] = lambda: list(batched(samples)[1])
        times: dict[str, list[float]] = {k: [] for k in runs}
        out: dict[str, list[float]] = {}
        for r in range(rounds):
            for name in runs if r % 2 == 0 else reversed(runs):
                t0 = time.process_time()
                out[name] = runs[name]()
                times[name].append((time.process_time() - t0) / n)
        raw = np.array(out["raw"])
        med = {k: statistics.median(v) for k, v in times.items()}
        case = f"arch, {label}, 1 kN point load, friction and unit weight"
        common = dict(model=kind, n_blocks=len(warm.model.assembly.blocks), error_of="lambda_max vs raw")
        for name, method in methods.items():
            if name not in runs:
                rows.append(row("reliability", case, method, note="skipped: moreau is not installed "
                                "(pip install tce[batched])", **common))
                continue
            got = np.array(out[name])
            same = np.array_equal(np.isfinite(raw), np.isfinite(got))
            err = float(np.abs(raw - got)[np.isfinite(raw)].max(initial=0.0)) if same else np.inf
            note = ("CPU time; limit problems built beforehand" if name == "raw" else
                    f"{med[name] / med['raw']:.2f}x raw (CPU time, interleaved; issue 39: at most 1.5x)")
            rows.append(row("reliability", case, method, n_solves=n * rounds, time_s=med[name], error=err, note=note,
                            **common))
    return rows


def _reliability_one_call(quick: bool) -> dict[str, Any]:
    """:data:`RELIABILITY_SAMPLES` samples of the planar arch through one WarmLimit, wall time."""
    n = RELIABILITY_SAMPLES // 5 if quick else RELIABILITY_SAMPLES
    x = reliability_joint().sample(n, "lhs", seed=2)[1]
    t0 = time.perf_counter()
    warm = reliability_case("planar")
    t1, c1 = time.perf_counter(), time.process_time()
    statuses, values = evaluate(warm, _warm_samples(x))
    t2, c2 = time.perf_counter(), time.process_time()
    est = failure_probability(values, RELIABILITY_THRESHOLD, statuses)
    lo, hi = est.clopper_pearson
    counts = ", ".join(f"{k} {v}" for k, v in est.statuses.items())
    return row("reliability", f"arch, planar LP, {n:,} LHS samples in one call", "WarmLimit, evaluate()",
               model="planar", n_blocks=len(warm.model.assembly.blocks), n_solves=n, time_s=t2 - t1,
               build_s=t1 - t0, error=(hi - lo) / 2, error_of="pf: 95% Clopper-Pearson half-width",
               note=f"{n / (t2 - t1):.0f} samples/s (wall; {c2 - c1:.2f} CPU-s); "
                    f"P(capacity < {RELIABILITY_THRESHOLD} kN) = {est.pf:.4f} [{lo:.4f}, {hi:.4f}]; {counts}")


class _InProcess:
    """The throughput rows' reference runner: the chunks one after the other in this process."""

    def map(self, fn: Callable[..., Any], *args: Any) -> list[Any]:
        return list(map(fn, *args))

    def close(self) -> None:
        pass


class _Pool:
    """``n`` spawned worker processes of ``concurrent.futures``."""

    def __init__(self, n: int) -> None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        self.pool = ProcessPoolExecutor(n, mp_context=multiprocessing.get_context("spawn"))

    def map(self, fn: Callable[..., Any], *args: Any) -> list[Any]:
        return list(self.pool.map(fn, *args))

    def close(self) -> None:
        self.pool.shutdown()


class _Dask:
    """A Dask ``LocalCluster`` of ``n`` single-threaded worker processes and its client."""

    def __init__(self, n: int) -> None:
        import logging

        from dask.distributed import Client, LocalCluster

        self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                    silence_logs=logging.ERROR)
        self.client = Client(self.cluster)

    def map(self, fn: Callable[..., Any], *args: Any) -> list[Any]:
        return self.client.gather(self.client.map(fn, *args, pure=False))

    def close(self) -> None:
        self.client.close()
        self.cluster.close()


def _reliability_workers(quick: bool) -> list[dict[str, Any]]:
    """Throughput of the chunked samples in process, in 1 and 2 processes and on Dask (module doc)."""
    n = RELIABILITY_SAMPLES // (10 if quick else 2)
    x = reliability_joint().sample(n, "lhs", seed=3)[1]
    chunks = [x[i:i + RELIABILITY_CHUNK] for i in range(0, n, RELIABILITY_CHUNK)]
    runners: dict[str, Callable[[], Any]] = {
        "in process, chunks in turn": _InProcess,
        "process pool, 1 worker": lambda: _Pool(1),
        "process pool, 2 workers": lambda: _Pool(2),
    }
    have_dask = importlib.util.find_spec("distributed") is not None
    if have_dask:
        runners["Dask LocalCluster, 2 workers"] = lambda: _Dask(2)
    case = f"arch, planar LP, {n:,} samples in {len(chunks)} chunks"
    n_blocks = len(semicircular_arch().blocks)
    times: dict[str, list[tuple[float, float]]] = {k: [] for k in runners}
    answers: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for _ in range(1 if quick else 2):
        for name, make in runners.items():
            passes = []
            t0 = time.perf_counter()
            runner = make()
            try:
                for _ in range(2):
                    got = runner.map(reliability_chunk, ["planar"] * len(chunks), chunks)
                    passes.append(time.perf_counter() - t0)
                    t0 = time.perf_counter()
            finally:
                runner.close()
            answers[name] = (np.concatenate([s for s, _ in got]), np.concatenate([v for _, v in got]))
            times[name].append((passes[1], passes[0] - passes[1]))
    ref_status, ref = answers["in process, chunks in turn"]
    rows: list[dict[str, Any]] = []
    for name, measured in times.items():
        status, values = answers[name]
        finite = np.isfinite(ref)
        same = np.array_equal(status, ref_status) and np.array_equal(values[~finite], ref[~finite], equal_nan=True)
        err = float(np.abs(values[finite] - ref[finite]).max(initial=0.0)) if same else np.inf
        t, start = statistics.median(m[0] for m in measured), statistics.median(m[1] for m in measured)
        rows.append(row("reliability", case, name, model="planar", n_blocks=n_blocks, n_solves=n, time_s=t,
                        build_s=start if name != "in process, chunks in turn" else np.nan, error=err,
                        error_of="capacity vs in process",
                        note=f"{n / t:.0f} samples/s (wall, started workers)"))
    if not have_dask:
        rows.append(row("reliability", case, "Dask LocalCluster, 2 workers", model="planar", n_blocks=n_blocks,
                        note="skipped: dask[distributed] is not installed (pip install tce[dask])"))
    return rows


def _reliability(quick: bool) -> list[dict[str, Any]]:
    """Cost per sample against raw Clarabel, samples in one call, throughput against workers (module doc)."""
    return _reliability_cost(quick) + [_reliability_one_call(quick)] + _reliability_workers(quick)


SECTIONS: dict[str, Callable[[bool], list[dict[str, Any]]]] = {
    "solve": _solve,
    "hot_path": _hot_path,
    "limit": _limit,
    "load_path": _load_path,
    "scaling": _scaling,
    "reliability": _reliability,
}


def run_bench(quick: bool = False, sections: Sequence[str] | None = None) -> pd.DataFrame:
    """Measure the bench's sections on this machine.

    Parameters
    ----------
    quick : bool
        Fewer repeats and the smallest sizes.
    sections : sequence of str, optional
        Names of :data:`SECTIONS` (default: all).

    Returns
    -------
    pandas.DataFrame
        One row per measurement, columns :data:`COLUMNS`: times in s, memory in MB.
    """
    names = list(sections or SECTIONS)
    unknown = set(names) - set(SECTIONS)
    if unknown:
        raise ValueError(f"unknown bench sections {sorted(unknown)}; choose from {list(SECTIONS)}")
    rows: list[dict[str, Any]] = []
    for name in track(names, "bench", unit="section"):
        rows += SECTIONS[name](quick)
    return pd.DataFrame(rows, columns=COLUMNS)


def _fmt(v: Any) -> str:
    if isinstance(v, float | np.floating):
        return "" if np.isnan(v) else f"{v:.3g}"
    return str(v)


def _commit() -> str:
    """The commit of the tce source tree measured (``git describe``), or tce's version outside a git checkout."""
    from .. import __version__

    try:
        out = subprocess.run(["git", "describe", "--always", "--dirty"], capture_output=True, text=True, timeout=10,
                             cwd=os.path.dirname(__file__), check=True)
    except (OSError, subprocess.SubprocessError):
        return f"tce {__version__}"
    return f"commit {out.stdout.strip()}"


def report(df: pd.DataFrame) -> str:
    """The bench table as text: one table a section, times in ms, empty columns left out."""
    import platform

    import clarabel

    t = df.assign(time_ms=df.time_s * 1e3, build_ms=df.build_s * 1e3).drop(columns=["time_s", "build_s", "section"])
    cols = ["case", "method", "n_blocks", "n_solves", "build_ms", "time_ms", "error", "error_of", "peak_mem_mb", "note"]
    lines = [f"measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} at {_commit()}, load average "
             f"{os.getloadavg()[0]:.1f}; machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
             f"Python {platform.python_version()}, Clarabel {clarabel.__version__}; medians"]
    for section, g in df.groupby("section", sort=False):
        part = t.loc[g.index, cols].replace("", np.nan).dropna(axis=1, how="all")
        lines += ["", f"[{section}]", part.apply(lambda c: c.map(_fmt)).to_string(index=False)]
    return "\n".join(lines) + "\n"
