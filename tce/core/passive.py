"""Passive restraint of the fill as bounded unknowns of the direct limit analysis and of the TCE.

The model (:mod:`tce.core.fill`, ``kp``): on each exposed top-surface piece ``k`` of a free
block, a horizontal force ``p_k`` from the fill into the ring, ``0 <= p_k <= P_k`` (kN), at
the point of the piece's fill column. The limit problem of :class:`tce.core.limit.LimitSolver`
becomes::

    max lam   s.t.   A_eq F + G p + b_fixed + lam b_live = 0,   F admissible,   0 <= p <= P

with ``G`` ``(m_eq, k)`` the unit forces' wrenches in ``A_eq``'s row layout (the columns of
:class:`Restraint`). By LP duality a mechanism of velocities ``v`` pays
``sum_k P_k max(0, -v . G_k)``: each piece resists with its full capacity when it moves into
the fill (against ``G_k``'s force) and does nothing when it moves away.

The TCE force states (:class:`tce.core.solve.TCESolver`, hence load paths and studies) take the
same unknowns with the same bounds and no complementary energy
(:func:`tce.core.problem.restrained_tce_problem`), so a load path's last admissible multiplier
brackets the direct limit with the restraint. The cvxpy backend and the non-associative
estimate refuse a pattern with ``kp`` > 0 (:func:`refuse_passive`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .fill import Fill, passive_bounds
from .loads import LoadPattern, _block_rows
from .surface import LoadError
from .model import Model

__all__ = ["Restraint", "passive_restraint", "refuse_passive"]


@dataclass(frozen=True, eq=False)
class Restraint:
    """Bounded extra forces of a limit problem.

    Attributes
    ----------
    G : (m_eq, k) ndarray
        Each force's unit wrench in the model's row layout (kN, kN m per kN).
    capacity : (k,) ndarray
        Upper bound of each force (kN, > 0); the lower bound is 0.
    blocks : (k,) ndarray of int
        The block each force acts on (assembly index).
    points, directions : (k, 3) ndarray
        Point of application (m) and unit direction of each force.
    """

    G: NDArray[np.float64]
    capacity: NDArray[np.float64]
    blocks: NDArray[np.int64]
    points: NDArray[np.float64]
    directions: NDArray[np.float64]

    @property
    def size(self) -> int:
        """Number of bounded forces."""
        return len(self.capacity)


def passive_restraint(model: Model, fill: Fill | None) -> Restraint | None:
    """The passive restraint of ``fill`` on ``model`` (:func:`tce.core.fill.passive_bounds`),
    or None when there is none (no fill, ``kp`` = 0, or no inclined exposed face)."""
    if fill is None or fill.kp == 0.0:
        return None
    bounds = passive_bounds(model.assembly, fill)
    if not bounds:
        return None
    assembly = model.assembly
    cols = []
    for block, point, d, _ in bounds:
        w = np.zeros((len(assembly.blocks), 6))
        w[block, :3] = d
        w[block, 3:] = np.cross(point - assembly.centroids[block], d)
        cols.append(_block_rows(model, w))
    return Restraint(
        G=np.column_stack(cols), capacity=np.array([b[3] for b in bounds]),
        blocks=np.array([b[0] for b in bounds], dtype=np.int64),
        points=np.array([b[1] for b in bounds]), directions=np.array([b[2] for b in bounds]),
    )


def refuse_passive(pattern: LoadPattern, what: str) -> None:
    """Raise :class:`tce.core.surface.LoadError` (key ``fill.kp``) when ``pattern`` has a
    passive restraint that ``what`` (the cvxpy TCE solve, the non-associative estimate) would
    leave out silently; the direct limit and the Clarabel TCE solves (hence load paths and
    studies) carry it."""
    if pattern.fill is not None and pattern.fill.kp != 0.0:
        raise LoadError("fill.kp", f"{pattern.fill.kp:g} in {what}",
                        "the passive restraint is carried by the direct limit and the Clarabel TCE solver "
                        "(Analysis.solve, load paths, studies); give kp = 0 here")
