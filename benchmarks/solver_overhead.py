"""tce's solves against Clarabel driven by hand on the same data (development benchmark).

``hot_path``: ``tce bench --section hot_path`` (:mod:`tce.quality.bench`): the load path's
inner solve, its status read and its canonical state read, against Clarabel's own
``update(b) + solve()`` on identical data, interleaved call by call.
``limit_cost``: the direct lambda_max against one raw Clarabel set-up + solve of the same
problem, and the load path against a bisection written by hand on a warm raw Clarabel solver:
to lambda_max (the states not read), and with the canonical state of every step read (as a
study stores them) against the raw bisection solving the canonical QP of every admissible
step; CPU time, interleaved, medians.

It reaches into ``tce.core``'s internals (the problem builders, the warm solver): update it when
they change. Usage: ``python benchmarks/solver_overhead.py [--quick]``.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pandas as pd

from tce.core.limit import LimitSolver
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.solve import SolverOptions
from tce.quality.bench import COLUMNS, FRICTION, SECTIONS, SETTLEMENT, report, row
from tce.structures.arch import semicircular_arch


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

    from tce.core.canonical import FACE_SLACK, canonical_problem
    from tce.core.clarabel_solver import _cones

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


def limit_cost(quick: bool) -> list[dict[str, Any]]:
    """The direct lambda_max against one raw Clarabel set-up + solve of the same problem, and
    the planar load path against a hand-written bisection on raw Clarabel, interleaved call
    by call (CPU time, medians; ratios in ``note``)."""
    import clarabel

    from tce.analysis.loadpath import load_path
    from tce.core.analysis import Analysis
    from tce.core.clarabel_solver import _cones
    from tce.core.loads import scene_vectors
    from tce.core.problem import limit_problem, tce_b, tce_problem

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
            rows.append(row("limit_cost", f"arch 16 blocks lambda_max, {label}", name, model=kind,
                             n_blocks=len(arch.blocks), n_solves=reps, time_s=med,
                             note=f"{med / raw:.3f}x raw (CPU, interleaved)"))
    # the load path (direct bracket, no mechanism) against the hand-written bisection: to lambda_max
    # (the states not read: the same work as the raw bisection, the target), and with the canonical
    # state of every step read (as a study stores them) against the raw bisection solving the canonical
    # QP of every admissible step with the raw solver's settings (no iterative refinement) and with
    # tce's canonical settings (refined: the same solves as tce's; :func:`_raw_canonical`)
    U = np.zeros(6 * len(arch.support_names))
    i = 6 * arch.support_names.index("right")
    scenes = (("planar", "arch in plane, 1 mm spreading, step 0.02, atol 1e-6", SETTLEMENT, 0, 10 if quick else 60),
              ("spatial", "arch, 1 mm transversal motion (3D SOCP), step 0.02, atol 1e-6",
               {"right": [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]}, 1, 2 if quick else 10))
    atol, step = 1e-6, 0.02
    opts = SolverOptions()
    for kind, case, sett, component, repeats in scenes:
        model = build_model(arch, kind)
        U[:] = 0.0
        U[i + component] = sett["right"][component]
        f = LimitSolver(model, mat).formulation
        _, b_fixed, b_live = scene_vectors(model, 0.0)
        tp = tce_problem(f, tce_b(f, b_fixed), U)
        b0, b1 = tce_b(f, b_fixed), tce_b(f, b_fixed + b_live) - tce_b(f, b_fixed)
        settings = opts.settings(refine=False, kkt=f.kkt)
        raws = {"raw": None, "raw, canonical QP": settings, "raw, refined canonical QP": opts.settings(kkt=f.kkt)}
        times: dict[str, list[float]] = {k: [] for k in ("tce", "tce, states read", *raws)}
        got: dict[str, Any] = {}
        loads = [os.getloadavg()[0]]
        for r in range(repeats):
            names = list(times)
            for name in (names if r % 2 else names[::-1]):
                an = Analysis(arch, mat, model=kind, options=opts)
                # both start from the built, scaled operators: the raw one from tp, whose A is its
                # formulation's constraints (built on first use: 0.3-0.6 ms on the planar arch)
                an.formulation(kind).constraints
                t0 = clock()
                if name.startswith("tce"):
                    got[name] = load_path(an, 0.0, sett, step=step, atol=atol, mechanism=False)
                    if name == "tce, states read":
                        for st in got[name].steps:
                            st.forces  # noqa: B018 (selects the canonical state)
                else:
                    raw = clarabel.DefaultSolver(tp.P, tp.q, tp.A, b0, _cones(tp), settings)
                    after = None if raws[name] is None else _raw_canonical(f, b0, b1, tp.q, raws[name])
                    got[name] = _raw_bisection(raw, b0, b1, step, atol, after)
                times[name].append(clock() - t0)
            loads.append(os.getloadavg()[0])
        lp = got["tce"]
        against = {"tce": ("raw",), "tce, states read": ("raw, canonical QP", "raw, refined canonical QP")}
        what = {"tce": "to lambda_max, states not read",
                "tce, states read": "the canonical state of every step read, as a study stores them"}
        for name, base in against.items():
            mt = statistics.median(times[name])
            ratios = "; ".join(f"{mt / statistics.median(times[k]):.3f}x the {k} bisection" for k in base)
            rows.append(row("limit_cost", case, f"tce load path (direct bracket, no mechanism, {what[name]})",
                             model=kind, n_blocks=len(arch.blocks), n_solves=lp.n_solves, time_s=mt,
                             note=f"{ratios} (CPU, interleaved, {repeats} runs, load average "
                                  f"{min(loads):.1f}-{max(loads):.1f}); lambda_max {lp.lambda_max:.7f}, "
                                  f"{lp.n_solves} TCE solves + 1 direct"))
        for k, qp in raws.items():
            lam_raw, n_raw = got[k]
            raw_what = {"raw": "no canonical states", "raw, canonical QP": "with the canonical QP of every admissible step",
                        "raw, refined canonical QP": "with the canonical QP of every admissible step, refined as tce's"}[k]
            rows.append(row("limit_cost", case, f"hand-written bisection on raw clarabel ({raw_what})",
                             model=kind, n_blocks=len(arch.blocks), n_solves=n_raw,
                             time_s=statistics.median(times[k]), note=f"lambda_max {lam_raw:.7f}, {n_raw} solves"))
    return rows


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    quick = parser.parse_args().quick
    print(report(pd.DataFrame(SECTIONS["hot_path"](quick) + limit_cost(quick), columns=COLUMNS)), end="")
