"""The contact law as cone rows, and the scaling that makes the conic data dimensionless.

The contact law of a model is a set of rows ``M F + h in K`` on the force vector ``F``
(``(nc * dim,)``, kN), with ``K`` a product of a zero cone, a nonnegative cone and
second-order cones of dimension 3, in that row order (:class:`ConeRows`). The problems of
:mod:`tce.core.problem` put them in Clarabel's form ``A x + s = b, s in K`` with ``A = -M``
and ``b = h / W``: the unknown ``x`` is ``F`` divided by the reference force ``W`` (the
total weight of the free blocks, :class:`Scaling`); equilibrium force rows are divided by
``W`` and moment rows by ``W L`` (``L`` the assembly size). Answers are therefore
independent of the units a user picks (``docs/conventions.md``).

Contact laws (per contact, ``fn`` first; ``h = 0`` for all of them):

- spatial, mu > 0: ``(mu fn, ft1, ft2)`` in a second-order cone;
- planar, mu > 0: ``mu fn - ft >= 0`` and ``mu fn + ft >= 0``;
- mu = 0: tangential components fixed to zero, ``fn >= 0``;
- mu None (Heyman): ``fn >= 0`` only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .model import Model

__all__ = ["ConeRows", "Scaling", "cone_rows", "cone_violation", "law_violation"]


@dataclass(frozen=True)
class ConeRows:
    """Rows ``M F + h`` in ``zero^n_zero x nonneg^n_nonneg x SOC(3)^n_soc``, stacked in that order.

    Attributes
    ----------
    M : (n_zero + n_nonneg + 3 n_soc, nc * dim) sparse
        Row operator on the force vector (homogeneous: the same on scaled forces).
    n_zero, n_nonneg, n_soc : int
        Rows in the zero cone, rows in the nonnegative cone, number of 3D second-order cones.
    h : (n_rows,) ndarray or None
        Offset of each row (kN); None is zero (every law of :func:`cone_rows`).
    """

    M: sp.csr_matrix
    n_zero: int
    n_nonneg: int
    n_soc: int
    h: NDArray[np.float64] | None = None

    @property
    def n_rows(self) -> int:
        """Number of rows of ``M``."""
        return self.n_zero + self.n_nonneg + 3 * self.n_soc

    def offset(self) -> NDArray[np.float64]:
        """``h`` as an array (zeros when None), kN."""
        return np.zeros(self.n_rows) if self.h is None else np.asarray(self.h, dtype=float)

    @property
    def zero(self) -> sp.csr_matrix:
        return self.M[: self.n_zero]

    @property
    def nonneg(self) -> sp.csr_matrix:
        return self.M[self.n_zero : self.n_zero + self.n_nonneg]

    @property
    def soc(self) -> sp.csr_matrix:
        return self.M[self.n_zero + self.n_nonneg :]


def cone_rows(model: Model, friction: float | None) -> ConeRows:
    """The contact law of ``model`` for friction ``friction`` as cone rows (see module doc)."""
    nc, dim = model.n_contacts, model.dim
    idx = np.arange(nc) * dim
    n = model.n_vars

    def sel(cols: NDArray[np.int64], vals: float | NDArray[np.float64] = 1.0) -> sp.csr_matrix:
        data = np.broadcast_to(np.asarray(vals, dtype=float), cols.shape)
        return sp.csr_matrix((data, (np.arange(len(cols)), cols)), shape=(len(cols), n))

    if friction is None:
        return ConeRows(sel(idx), 0, nc, 0)
    mu = float(friction)
    if mu == 0.0:
        tang = (idx[:, None] + np.arange(1, dim)[None, :]).ravel()
        return ConeRows(sp.vstack([sel(tang), sel(idx)]).tocsr(), len(tang), nc, 0)
    if dim == 2:
        plus = sel(idx, mu) + sel(idx + 1, 1.0)
        minus = sel(idx, mu) - sel(idx + 1, 1.0)
        rows = sp.vstack([minus, plus]).tocsr()
        return ConeRows(rows, 0, 2 * nc, 0)
    # interleave (mu fn, ft1, ft2) per contact
    cols = (idx[:, None] + np.arange(3)[None, :]).ravel()
    vals = np.tile([mu, 1.0, 1.0], nc)
    return ConeRows(sel(cols, vals), 0, 0, nc)


def cone_violation(model: Model, friction: float | None, forces: NDArray[np.float64]) -> float:
    """Largest violation of the contact law by ``forces`` ((nc, dim), same units as forces).

    The violation of a contact is ``max(0, -fn)`` for Heyman and ``max(0, ||ft|| - mu fn,
    -fn)`` with friction; with ``mu = 0`` it is ``max(|ft|, -fn)``.
    """
    f = np.asarray(forces).reshape(model.n_contacts, model.dim)
    if not len(f):
        return 0.0
    fn = f[:, 0]
    worst = max(0.0, -float(fn.min()))
    if friction is not None:
        ft = np.abs(f[:, 1]) if model.dim == 2 else np.sqrt(f[:, 1] ** 2 + f[:, 2] ** 2)
        worst = max(worst, float((ft - float(friction) * fn).max()))
    return worst


def law_violation(rows: ConeRows, forces: NDArray[np.float64]) -> float:
    """Largest violation of ``M F + h in K`` by ``forces`` (same units as the rows, kN).

    Zero rows count ``|v|``, nonnegative rows ``max(0, -v)``, a second-order cone
    ``(t, u)`` counts ``max(0, ||u|| - t)``.
    """
    v = rows.M @ np.ravel(forces) + rows.offset()
    nz, nn = rows.n_zero, rows.n_nonneg
    parts = [np.abs(v[:nz]), np.maximum(0.0, -v[nz : nz + nn])]
    if rows.n_soc:
        c = v[nz + nn :].reshape(-1, 3)
        parts.append(np.maximum(0.0, np.linalg.norm(c[:, 1:], axis=1) - c[:, 0]))
    return float(max((p.max(initial=0.0) for p in parts), default=0.0))


@dataclass(frozen=True)
class Scaling:
    """Reference force (kN) and length (m) that make the conic data dimensionless."""

    force: float
    length: float

    @classmethod
    def of(cls, model: Model) -> Scaling:
        return cls(force=model.assembly.total_weight, length=model.assembly.size)

    def rows(self, model: Model) -> NDArray[np.float64]:
        """Per-row divisor of the equilibrium rows: ``W`` (force) or ``W L`` (moment)."""
        return np.where(model.row_is_moment, self.force * self.length, self.force)
