"""Non-associative friction: the load factor of joints that slide without opening.

The limit theorems behind :mod:`tce.core.limit` assume an associated flow rule: a Coulomb
joint that slides also opens (dilatancy ``dn = mu ||dt||``). Real dry joints slide without
opening, and where sliding takes part in the collapse the associative ``lambda_max`` is an
upper estimate (Drucker, 1954; Livesley, 1978, part II). This module estimates the collapse
load of non-dilatant Coulomb joints by the iterative scheme of Gilbert, Casapulla and Ahmed
(2006) [1]_, written for the cone programs of :mod:`tce.core.problem` as Portioli et al. did
for 3D blocks [2]_:

1. iteration 0 is the associative limit analysis: ``lambda_assoc`` and its normal forces
   ``fn_0``;
2. iteration ``k`` fixes the friction capacity of every contact from the normal forces of
   the previous ones, ``||ft|| <= mu max(fn_{k-1}, 0) + c A`` (``fn_{k-1}`` under-relaxed,
   :class:`NonAssocSolver`; a pseudo-cohesion, friction angle zero), leaves the normal
   forces free within ``-t A <= fn <= fc A``, and solves the limit problem again
   (:func:`tce.core.conic.cone_rows` with ``shear_capacity``). This law's flow rule has no
   dilatancy: a sliding contact that carries load does not open. The iterate is the
   optimal state nearest to the normal forces in use, with the least tangential forces
   (:func:`tce.core.problem.nearest_state_problem`: strictly convex, so one state, the same
   in every frame), taken ``1e-8`` below ``lambda_k`` (relative; of ``max(lambda_k, 1)``
   where the relative step is too thin for the solver, :data:`NEAREST_BACKOFF`); iteration 0
   takes the associative optimal state of least norm alike. (The solver's own choice among
   optimal states depends on the frame and on the order of the contacts, and so would the
   fixed point; it is taken only where every nearest-state solve fails.)
3. the scheme stops at a fixed point, a state ``F`` that is a non-associative collapse
   state to ``tol`` (times the total weight ``W`` for forces): ``lambda`` settled (the
   last three iterates within ``tol`` of each other, relative, absolute below 1: two
   changes in a row, because one small change may be followed by a larger one, as after an
   extrapolation, 5.; and where the two changes have one sign and the second is smaller, a
   creep of ratio ``rho`` between them, what is left of it if it goes on geometrically,
   ``|d_k| rho / (1 - rho)`` (the error estimate of Aitken's delta-squared process [3]_),
   also within ``tol``: a slow creep of small changes is not a fixed point; a creep that
   does not shrink is not settled unless its changes are below ``1e-3 tol``, the solver's
   noise); ``F`` an optimal state of the last sub-problem (equilibrium at
   ``lambda_k``, its capacities met), admissible for the Coulomb law itself (violation
   ``<= tol W``); and, at every contact that slides in the last mechanism (tangential speed
   above :data:`DILATANCY_TOL` of the largest vertex speed), ``|fn - fn_used| <= tol W``
   (the capacity used, ``mu fn_used``, is the one of the state's own normal force) and
   ``mu fn + c A - ||ft|| <= tol W`` (it slides at its Coulomb capacity). Contacts that do
   not slide may carry any admissible normal force. The mechanism (the dual of the last
   sub-problem) then slides without opening; this is checked at loaded sliding contacts
   (``dilatancy``).
4. where a sub-problem's optimal states are not unique the plain scheme may circle without
   settling. Once ``lambda`` has settled (3.), each iteration also solves
   :func:`tce.core.problem.least_violation_problem`: among the optimal states of the
   sub-problem, the one of least Coulomb violation and least ``|fn - fn_used|`` at the
   sliding contacts (of those, the one nearest to the normal forces in use:
   :func:`tce.core.problem.nearest_least_violation_problem`), and tests that state as in
   3. A polished state that fails the test is not carried on (its normal forces away from
   the sliding contacts are arbitrary on the optimal face, and as capacities they can
   start a cycle); the plain step goes on instead.
5. near a fixed point the plain iterates approach it linearly, slowly where one mode of
   ratio close to 1 carries ``lambda``. Where the last seven plain steps show such an
   approach, the normal forces that fix the next capacities are extrapolated to its limit
   (:func:`slow_mode_limit`, reduced-rank extrapolation). The safeguard: if the state of
   the extrapolated capacities is not nearer to a fixed point (the larger of its law
   violation and its consistency error at the sliding contacts, 3., did not decrease), the
   scheme goes on from the plain step the extrapolation replaced and extrapolates no more.
   The extrapolation only chooses the next capacities; a state is accepted by the test of
   3. alone.

Which fixed point: the one the iterates reach from the associative optimal state of least
norm, every iterate the unique nearest state of its sub-problem (2.), so that the sequence and
its limit are the same in every frame and every order of the blocks and contacts, to the
solver's tolerances (``tests/analysis/test_nonassoc.py``: a block-file wall in shuffled
orders).

The fixed point is a collapse state of the non-associative problem, so ``lambda_nonassoc``
is at most ``lambda_assoc`` (its state is statically admissible); it is the scheme's
estimate, not a proven lower bound: a non-associative problem may have several collapse
states and the lowest is a nonconvex problem (Ferris and Tin-Loi, 2001). Two blocks side by
side rocking together collapse, without dilatancy, at any load of an interval whose lowest
end is each block rocking alone (``tests/validation/test_materials_closed_forms.py``); the
scheme returns one load in it (with the nearest-state iterates, its lowest end to 1e-6).
The scheme may also fail to settle (Gilbert et al. report cycling on some problems); the
result then says ``not_converged`` and carries the iterates, never a number dressed as
converged.

References
----------
.. [1] M. Gilbert, C. Casapulla and H. M. Ahmed, "Limit analysis of masonry block structures
   with non-associative frictional joints using linear programming", *Computers &
   Structures* 84 (2006) 873-887, doi:10.1016/j.compstruc.2006.02.005.
.. [2] F. Portioli, C. Casapulla, M. Gilbert and L. Cascini, "Limit analysis of 3D masonry
   block structures with non-associative frictional joints using cone programming",
   *Computers & Structures* 143 (2014) 108-121.
.. [3] A. C. Aitken, "On Bernoulli's numerical solution of algebraic equations",
   *Proceedings of the Royal Society of Edinburgh* 46 (1926) 289-305.
"""

from __future__ import annotations

import logging
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..core.analysis import Analysis
from ..core.clarabel_solver import solve_once
from ..core.conic import ConeRows, cone_rows, cone_violation
from ..core.limit import LimitResult, LimitSolver, Mechanism
from ..core.loads import LoadPattern, as_pattern, scene_vectors
from ..core.passive import refuse_passive
from ..core.material import Material
from ..core.model import Model
from ..core.problem import least_violation_problem, nearest_least_violation_problem, nearest_state_problem
from ..core.result import Result

__all__ = ["NonAssocResult", "NonAssocSolver", "nonassociative_limit", "slow_mode_limit"]

log = logging.getLogger(__name__)

#: largest normal opening (relative to the largest vertex speed of the mechanism) a loaded
#: sliding contact may show in a non-dilatant mechanism
DILATANCY_TOL = 1e-4

#: steps below a sub-problem's lambda_max at which its nearest state is sought, in turn until
#: one solves cleanly (:meth:`NonAssocSolver._nearest`): each relative to ``lambda_max``, then
#: to ``max(|lambda_max|, 1)`` (the scheme's own scale of ``lambda``, as of ``tol``)
NEAREST_BACKOFF = (1e-8, 1e-7, 1e-6)

#: the extrapolation of a slow linear approach (:func:`slow_mode_limit`): plain steps in
#: the window after the first; least cosine between successive steps; largest spread of
#: their ratios; least ratio of the last change of lambda in the window to the first
ACCELERATION_DEPTH = 6
ACCELERATION_COS = 0.999
ACCELERATION_SPREAD = 0.005
ACCELERATION_LAMBDA_DECAY = 0.7


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class NonAssocResult(Result):
    """The associative/non-associative bracket of one load direction (``ok`` when ``converged``).

    Attributes
    ----------
    status : str
        ``converged`` (a fixed point whose state is admissible and whose mechanism has no
        dilatancy), ``not_converged`` (no fixed point within ``max_iter``: the iterates are in
        ``history``, ``lambda_nonassoc`` is NaN), ``dilatant`` (a fixed point whose mechanism
        still opens at a loaded sliding contact beyond :data:`DILATANCY_TOL`), or the status of
        a limit solve that failed (``infeasible``, ``unbounded``, ``numerical``).
    alpha : float
        Direction of the lateral loads (degrees; NaN for other live loads).
    model : str
        ``"planar"`` or ``"spatial"``.
    lambda_assoc : float
        Associative lambda_max (iteration 0): the upper end of the bracket.
    lambda_nonassoc : float
        The scheme's estimate for non-dilatant joints (NaN unless ``converged``).
    iterations : int
        Non-associative solves made (iteration 0 not counted).
    converged : bool
        ``lambda`` settled and the final state meets the Coulomb law.
    history : tuple of float
        ``lambda_k`` of every iteration, the associative one first.
    admissibility : float
        Largest violation of the material's law by the final state, over ``W``.
    consistency : float
        Largest ``|fn - fn_used|`` or ``mu fn + c A - ||ft||`` at the contacts that slide in
        the final mechanism (module docstring, 3.), over ``W``.
    dilatancy : float
        Largest normal opening of a loaded sliding contact in the final mechanism, relative
        to its largest vertex speed (0 for a mechanism without dilatancy).
    forces : (nc, dim) ndarray
        Final contact forces (kN); NaN unless ``converged``.
    mechanism : Mechanism or None
        Collapse mechanism of the final iteration.
    """

    HEADLINE = ("lambda_assoc", "lambda_nonassoc", "iterations", "model", "alpha")

    OK = ("converged",)

    alpha: float
    model: str
    lambda_assoc: float
    lambda_nonassoc: float = float("nan")
    iterations: int = 0
    converged: bool = False
    history: tuple[float, ...] = ()
    admissibility: float = float("nan")
    consistency: float = float("nan")
    dilatancy: float = float("nan")
    forces: NDArray[np.float64] = field(repr=False)
    mechanism: Mechanism | None = field(default=None, repr=False)

    def _arrays(self) -> tuple[dict[str, tuple], dict[str, Any]]:
        """``history``: lambda of every iteration (dim ``iteration``, the associative one first)."""
        return {"history": (("iteration",), np.asarray(self.history, dtype=float))}, {}


def contact_velocities(model: Model, velocities: NDArray[np.float64]) -> NDArray[np.float64]:
    """Relative velocity of every contact, ``(nc, dim)`` in its frame (normal first; B
    with respect to A, positive normal = opening), from block velocities ``(n_blocks, 6)``
    about each centroid (:attr:`tce.core.limit.Mechanism.velocities`)."""
    a = model.assembly
    ia = np.array([i.a for i in a.interfaces])[model.contact_interface]
    ib = np.array([i.b for i in a.interfaces])[model.contact_interface]
    p = model.contact_points
    c = a.centroids

    def point_velocity(block: NDArray[np.int64]) -> NDArray[np.float64]:
        return velocities[block, :3] + np.cross(velocities[block, 3:], p - c[block])

    rel = point_velocity(ib) - point_velocity(ia)
    normals = np.array([a.interfaces[k].normal for k in model.contact_interface]).reshape(-1, 3)
    dirs = np.concatenate([normals[:, None, :], model.tangents], axis=1)  # (nc, dim, 3)
    return np.einsum("kdj,kj->kd", dirs, rel)


def slow_mode_limit(
    fn: NDArray[np.float64], steps: NDArray[np.float64], lambdas: NDArray[np.float64], relaxation: float
) -> NDArray[np.float64] | None:
    """The limit of a slow linear approach of the relaxed scheme, extrapolated from its last
    plain steps; None where the steps do not show one.

    The scheme's iterates are ``fn_{j+1} = fn_j + w d_j`` with ``d_j = T(fn_j) - fn_j``
    (``T``: the normal forces of the nearest optimal state of the sub-problem whose
    capacities ``fn_j`` fixes). The extrapolation is the reduced-rank extrapolation (RRE;
    Smith, Ford and Sidi 1987, in Anderson's (1965) form, Walker and Ni 2011): the affine
    combination ``sum g_j (fn_j + w d_j)``, ``sum g_j = 1``, whose combined step
    ``||sum g_j d_j||`` is least. It removes from a linear approach as many modes as the
    window has steps minus one.

    It is returned only where the approach is a slow linear one, seen as:

    - ``lambda`` creeping: its changes over the window of one sign, the last between
      :data:`ACCELERATION_LAMBDA_DECAY` and 1 times the first (where ``lambda`` settles while
      only normal forces creep, the polish step of :class:`NonAssocSolver` ends the approach);
    - the steps ``d_j`` of one direction (successive cosines at least
      :data:`ACCELERATION_COS`) and contracting by a steady ratio below 1 (spread of the
      successive ratios ``d_j . d_{j+1} / |d_j|^2`` at most :data:`ACCELERATION_SPREAD`).

    Every quantity is a norm or scalar product of normal forces, or ``lambda``: the same in
    every frame and every order of the contacts.

    Parameters
    ----------
    fn, steps : (m + 1, nc) ndarray
        The iterates ``fn_j`` and their steps ``d_j`` (kN), oldest first.
    lambdas : (m + 1,) ndarray
        ``lambda_j`` of the sub-problems of ``fn_j``.
    relaxation : float
        ``w``.

    Returns
    -------
    (nc,) ndarray or None
        The extrapolated normal forces (kN), to fix the next capacities.

    References
    ----------
    D. G. Anderson, "Iterative procedures for nonlinear integral equations", *J. ACM* 12
    (1965) 547-560; D. A. Smith, W. F. Ford and A. Sidi, "Extrapolation methods for vector
    sequences", *SIAM Review* 29 (1987) 199-233; H. F. Walker and P. Ni, "Anderson
    acceleration for fixed-point iterations", *SIAM J. Numer. Anal.* 49 (2011) 1715-1735.
    """
    dlam = np.diff(lambdas)
    if not (np.all(dlam > 0) or np.all(dlam < 0)) or not ACCELERATION_LAMBDA_DECAY <= dlam[-1] / dlam[0] <= 1.0:
        return None
    norms = np.linalg.norm(steps, axis=1)
    if np.any(norms == 0.0):
        return None
    dots = np.einsum("ij,ij->i", steps[:-1], steps[1:])
    ratios = dots / norms[:-1] ** 2
    if (dots / (norms[:-1] * norms[1:])).min() < ACCELERATION_COS or ratios.max() >= 1.0:
        return None
    if np.ptp(ratios) > ACCELERATION_SPREAD:
        return None
    nxt = fn + relaxation * steps
    # g = (1 - c_0, c_0 - c_1, ..., c_{m-1}): sum g_j d_j = d_0 + sum_i c_i (d_{i+1} - d_i)
    c, *_ = np.linalg.lstsq(np.diff(steps, axis=0).T, -steps[0], rcond=None)
    return nxt[0] + c @ np.diff(nxt, axis=0)


class NonAssocSolver:
    """The iterative non-associative limit of one model and material (module docstring).

    Parameters
    ----------
    model : Model
    material : Material
        Its friction, cohesion and strengths; its ``flow`` is not consulted (this solver
        is the non-associative computation).
    max_iter : int
        Largest number of non-associative solves.
    tol : float
        Tolerance of the fixed-point test (module docstring, 3.): on ``lambda`` (relative,
        absolute below 1) and on forces (over ``W``).
    relaxation : float
        Under-relaxation ``w`` in (0, 1] of the normal forces that fix the capacities:
        ``fn <- fn + w (fn_k - fn)``; ``w < 1`` damps the cycling of problems whose
        sub-problems have many optimal force states (a whole course sliding).
    """

    def __init__(
        self, model: Model, material: Material, max_iter: int = 100, tol: float = 1e-6, relaxation: float = 0.5
    ) -> None:
        if not (isinstance(max_iter, int) and max_iter >= 1):
            raise ValueError(f"max_iter must be a whole number >= 1, got {max_iter!r}")
        if not (np.isfinite(tol) and tol > 0):
            raise ValueError(f"tol must be a finite number > 0, got {tol!r}")
        if not (np.isfinite(relaxation) and 0 < relaxation <= 1):
            raise ValueError(f"relaxation must be in (0, 1], got {relaxation!r}")
        self.model = model
        self.material = material
        self.max_iter = max_iter
        self.tol = tol
        self.relaxation = relaxation
        self.associative = LimitSolver(model, material)
        # the law of the fixed-capacity problems has no friction angle: its flow check in
        # LimitSolver is the one of mu = 0 (dn >= 0), with the same crushing
        self._fixed = Material(
            friction=0.0, tensile_strength=material.tensile_strength,
            compressive_strength=material.compressive_strength,
        )

    def solve(
        self, alpha: float | None = None, start: LimitResult | None = None, loads: LoadPattern | None = None
    ) -> NonAssocResult:
        """The bracket for lateral loads in direction ``alpha`` (degrees), or for the live
        loads of the pattern ``loads``; ``start`` is the associative answer when the caller
        has it (:meth:`tce.core.analysis.Analysis.limit`)."""
        pattern, b_fixed, b_live = scene_vectors(self.model, alpha, loads)
        refuse_passive(pattern, "the non-associative estimate")
        return self.solve_loads(b_fixed, b_live, pattern.direction, start)

    def solve_loads(
        self,
        b_fixed: NDArray[np.float64],
        b_live: NDArray[np.float64],
        alpha: float = float("nan"),
        start: LimitResult | None = None,
    ) -> NonAssocResult:
        """The bracket for live loads ``b_live`` with ``b_fixed`` always applied (``A_eq``'s row
        layout, kN and kN m)."""
        t0 = time.perf_counter()
        model, mat = self.model, self.material
        W = model.assembly.total_weight
        assoc = start if start is not None else self.associative.solve_loads(b_fixed, b_live, alpha)
        solve_time = assoc.solve_time
        empty = np.full((model.n_contacts, model.dim), np.nan)
        common = dict(alpha=float(alpha), model=model.kind, lambda_assoc=assoc.lambda_max)

        def done(**kw: object) -> NonAssocResult:
            return NonAssocResult(solve_time=solve_time, wall_time=time.perf_counter() - t0, **common, **kw)

        if assoc.status != "optimal":
            return done(status=assoc.status, forces=empty, history=(assoc.lambda_max,),
                        message=f"associative limit {assoc.status}: no bracket ({assoc.message})")
        mu = mat.friction
        if mu is None or mu == 0.0:
            # no friction capacity depends on the normal force: the associative state and
            # mechanism already have no dilatancy (Heyman: no sliding; mu = 0: dn >= 0 only)
            why = "unlimited friction: nothing slides" if mu is None else "friction 0: no capacity depends on fn"
            return done(status="converged", lambda_nonassoc=assoc.lambda_max, converged=True,
                        history=(assoc.lambda_max,), admissibility=0.0, dilatancy=0.0,
                        forces=assoc.forces, mechanism=assoc.mechanism, message=f"equal to the associative limit ({why})")
        history = [assoc.lambda_max]
        first = self._nearest(self.associative, b_fixed, b_live, assoc.lambda_max, np.zeros(model.n_contacts))
        fn = (first if first is not None else assoc.forces)[:, 0]
        last: LimitResult | None = None
        viol = cons = float("nan")
        polishing = False
        coulomb = cone_rows(model, mu, **mat.strengths)
        # the plain steps in a row (fn, T(fn) - fn, lambda), and the plain step and error an
        # extrapolation replaced, until the next iteration has tested it
        plain: deque[tuple[NDArray[np.float64], NDArray[np.float64], float]] = deque(maxlen=ACCELERATION_DEPTH + 1)
        pending: tuple[NDArray[np.float64], float] | None = None
        extrapolating = True
        for k in range(1, self.max_iter + 1):
            rows = cone_rows(model, 0.0, cohesion=mat.cohesion, tensile_strength=mat.tensile_strength,
                             compressive_strength=mat.compressive_strength, shear_capacity=mu * np.maximum(fn, 0.0))
            sub = LimitSolver(model, self._fixed, self.associative.tol, rows=rows)
            last = sub.solve_loads(b_fixed, b_live, alpha)
            solve_time += last.solve_time
            if last.status != "optimal":
                return done(status=last.status, forces=empty, iterations=k, history=tuple(history),
                            message=f"iteration {k}: limit solve {last.status} ({last.message})")
            history.append(last.lambda_max)
            sliding = self._sliding(last)
            nearest = self._nearest(sub, b_fixed, b_live, last.lambda_max, fn)
            state = nearest if nearest is not None else last.forces
            viol, cons = self._fixed_point_errors(state, fn, sliding)
            log.debug("non-associative iteration %d: lambda %.12g, law violation %.3g W, sliding contacts off "
                      "their capacity by %.3g W", k, history[-1], viol, cons)
            settled = self._settled(history)
            found = settled and viol <= self.tol and cons <= self.tol
            polishing = polishing or settled
            polished = None
            if not found and polishing:
                polished = self._polish(sub, b_fixed + last.lambda_max * b_live, coulomb, fn, sliding)
            if polished is not None:
                p_viol, p_cons = self._fixed_point_errors(polished, fn, sliding)
                log.debug("iteration %d polished: law violation %.3g W, sliding contacts off by %.3g W",
                          k, p_viol, p_cons)
                if settled and p_viol <= self.tol and p_cons <= self.tol:
                    found, state, viol, cons = True, polished, p_viol, p_cons
            if found:
                dil = self._dilatancy(last, state)
                status = "converged" if dil <= DILATANCY_TOL else "dilatant"
                return done(
                    status=status, lambda_nonassoc=last.lambda_max if status == "converged" else float("nan"),
                    iterations=k, converged=True, history=tuple(history), admissibility=viol, consistency=cons,
                    dilatancy=dil, forces=state if status == "converged" else empty, mechanism=last.mechanism,
                    message=f"fixed point after {k} iterations (Gilbert, Casapulla and Ahmed 2006)"
                    + ("; polished state" if polished is not None else ""),
                )
            error = max(viol, cons)
            if pending is not None:
                step, before = pending
                pending = None
                if not error < before:
                    # the safeguard (module docstring, 5.): back to the plain step, no more extrapolation
                    log.debug("iteration %d: extrapolation rejected (error %.3g W, was %.3g W)", k, error, before)
                    fn = step
                    extrapolating = False
                    continue
            plain.append((fn, state[:, 0] - fn, history[-1]))
            step = fn + self.relaxation * (state[:, 0] - fn)
            guess = None
            if extrapolating and len(plain) == plain.maxlen:
                iterates, steps, lambdas = (np.array(v) for v in zip(*plain, strict=True))
                guess = slow_mode_limit(iterates, steps, lambdas, self.relaxation)
            if guess is None:
                fn = step
            else:
                log.debug("iteration %d: extrapolated along a slow mode, capacities moved by %.3g W", k,
                          float(np.abs(guess - step).max()) / W)
                pending = (step, error)
                fn = guess
                plain.clear()
        return done(status="not_converged", iterations=self.max_iter, history=tuple(history), admissibility=viol,
                    consistency=cons, forces=empty, mechanism=last.mechanism if last is not None else None,
                    message=f"no fixed point after {self.max_iter} iterations: last lambda {history[-1]:.6g}, "
                    f"law violation {viol:.3g} W, sliding contacts off their capacity by {cons:.3g} W")

    def _settled(self, history: list[float]) -> bool:
        """Whether the last three values of ``lambda`` (the associative one included) lie
        within ``tol`` (relative, absolute below 1) of each other, and a creep between them
        would end within ``tol`` too (module docstring, 3.)."""
        if len(history) < 3:
            return False
        last = history[-3:]
        bound = self.tol * max(abs(history[-1]), 1.0)
        if max(last) - min(last) > bound:
            return False
        d1, d2 = last[1] - last[0], last[2] - last[1]
        if d1 * d2 > 0 and abs(d2) > 1e-3 * bound:
            rho = d2 / d1
            return rho < 1.0 and abs(d2) * rho / (1.0 - rho) <= bound
        return True

    def _sliding(self, res: LimitResult) -> NDArray[np.bool_]:
        """Contacts whose tangential relative speed in the mechanism of ``res`` exceeds
        :data:`DILATANCY_TOL` of the mechanism's largest vertex speed."""
        if res.mechanism is None:
            return np.zeros(self.model.n_contacts, dtype=bool)
        d = contact_velocities(self.model, res.mechanism.velocities)
        return np.linalg.norm(d[:, 1:], axis=1) > DILATANCY_TOL

    def _fixed_point_errors(
        self, forces: NDArray[np.float64], fn_used: NDArray[np.float64], sliding: NDArray[np.bool_]
    ) -> tuple[float, float]:
        """``(violation, consistency)`` of a state, both over ``W``: the largest violation of
        the material's own Coulomb law, and the consistency error at the sliding contacts
        (module docstring, 3.)."""
        mat, W = self.material, self.model.assembly.total_weight
        viol = cone_violation(self.model, mat.friction, forces, **mat.strengths) / W
        f = forces[sliding]
        cap = mat.friction * f[:, 0] + mat.cohesion * self.model.contact_area[sliding]
        gap = np.maximum(np.abs(f[:, 0] - fn_used[sliding]), cap - np.linalg.norm(f[:, 1:], axis=1))
        return viol, float(gap.max(initial=0.0)) / W

    def _polish(
        self,
        sub: LimitSolver,
        rhs: NDArray[np.float64],
        coulomb: ConeRows,
        fn_used: NDArray[np.float64],
        sliding: NDArray[np.bool_],
    ) -> NDArray[np.float64] | None:
        """The polished state of the sub-problem ``sub`` at its ``lambda_k`` (``rhs``; module
        docstring, 4.); None when that solve fails or its state misses equilibrium or the
        sub-problem's law by more than 1e-8 (of ``W`` and ``W L``)."""
        f = sub.formulation
        held = np.where(sliding, fn_used, np.nan)
        settings = sub.options.settings(refine=True, kkt=f.kkt)
        sol = solve_once(least_violation_problem(f, rhs, coulomb, held), settings)
        if not sol.solved:
            log.debug("polish: clarabel %s", sol.status)
            return None
        t = float(sol.x[-1])
        near = solve_once(nearest_least_violation_problem(f, rhs, coulomb, held, fn_used, t + max(1e-2 * abs(t), 1e-9)),
                          settings)
        F = f.forces(near.x if near.solved else sol.x)
        log.debug("polish: least violation %.3g W, nearest state %s", t, near.status)
        eq, law = f.residuals(F, rhs)
        if eq > 1e-8 or law > 1e-8:
            log.debug("polish: residual %.3g, law %.3g", eq, law)
            return None
        return F.reshape(self.model.n_contacts, self.model.dim)

    def _nearest(
        self,
        solver: LimitSolver,
        b_fixed: NDArray[np.float64],
        b_live: NDArray[np.float64],
        lam: float,
        normal_ref: NDArray[np.float64],
    ) -> NDArray[np.float64] | None:
        """Among the states of ``solver``'s law in equilibrium at ``lam`` (its
        ``lambda_max``: the optimal face), the one nearest to the normal forces
        ``normal_ref`` with the least tangential forces
        (:func:`tce.core.problem.nearest_state_problem`: unique, and the same in every frame),
        taken at ``lam - b |lam|``, then at ``lam - b max(|lam|, 1)``, for each ``b`` of
        :data:`NEAREST_BACKOFF` in turn, because the face at ``lambda_max`` itself has no
        interior: where ``lambda`` is small (a scheme creeping towards 0) the relative step
        leaves a slab thinner than the solver's tolerance, the solve fails there or not
        depending on the order of the contacts, and the state of the step after would be the
        solver's own choice. None when that solve fails or misses equilibrium or the law by
        more than 1e-8 (of ``W`` and ``W L``) at every step."""
        f = solver.formulation
        settings = solver.options.settings(refine=True, kkt=f.kkt)
        steps = dict.fromkeys(b * s for b in NEAREST_BACKOFF for s in (abs(lam), max(abs(lam), 1.0)))
        for backoff in steps:
            rhs = b_fixed + (lam - backoff) * b_live
            sol = solve_once(nearest_state_problem(f, rhs, normal_ref), settings)
            F = f.forces(sol.x)
            eq, law = f.residuals(F, rhs) if sol.solved else (np.inf, np.inf)
            if eq <= 1e-8 and law <= 1e-8:
                return F.reshape(self.model.n_contacts, self.model.dim)
            log.debug("nearest state %.1e below lambda_max: clarabel %s, residual %.3g, law %.3g", backoff, sol.status, eq, law)
        return None

    def _dilatancy(self, res: LimitResult, forces: NDArray[np.float64]) -> float:
        """Largest normal opening, in the mechanism of ``res``, of a contact that slides while
        carrying load in ``forces`` (above its tension cut-off and below crushing), relative
        to the mechanism's largest vertex speed."""
        if res.mechanism is None:
            return float("nan")
        d = contact_velocities(self.model, res.mechanism.velocities)
        mat, W = self.material, self.model.assembly.total_weight
        area = self.model.contact_area
        fn = forces[:, 0]
        loaded = fn + mat.tensile_strength * area > self.tol * W
        if mat.compressive_strength is not None:
            loaded &= mat.compressive_strength * area - fn > self.tol * W
        return float(np.abs(d[:, 0][loaded & self._sliding(res)]).max(initial=0.0))


def nonassociative_limit(
    analysis: Analysis,
    alpha: float | None = None,
    max_iter: int = 100,
    tol: float = 1e-6,
    relaxation: float = 0.5,
    loads: LoadPattern | None = None,
) -> NonAssocResult:
    """The associative/non-associative bracket of ``analysis`` for lateral loads in direction
    ``alpha`` (degrees), or for the live loads of the pattern ``loads``, on the model the
    scene runs on; iteration 0 is :meth:`tce.core.analysis.Analysis.limit` (cached). See
    :class:`NonAssocSolver`."""
    pattern = as_pattern(alpha, loads)
    kind = analysis.model_kind(loads=pattern)
    solver = NonAssocSolver(analysis.model(kind), analysis.material, max_iter=max_iter, tol=tol, relaxation=relaxation)
    return solver.solve(start=analysis.limit(loads=pattern), loads=pattern)
