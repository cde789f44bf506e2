"""Conic data of a model in Clarabel's standard form, scaled to be dimensionless.

Clarabel solves ``min 1/2 x'Px + q'x  s.t.  Ax + s = b,  s in K`` with K a product of a
zero cone, a nonnegative cone and second-order cones, in that row order here. The unknown
``x`` is the force vector divided by the reference force ``W`` (the total weight of the
free blocks); equilibrium force rows are divided by ``W`` and moment rows by ``W L``
(``L`` the assembly size). Answers are therefore independent of the units a user picks.

Contact laws (per contact, ``fn`` first):

- spatial, mu > 0: ``(mu fn, ft1, ft2)`` in a second-order cone;
- planar, mu > 0: ``mu fn - ft >= 0`` and ``mu fn + ft >= 0``;
- mu = 0: tangential components fixed to zero, ``fn >= 0``;
- mu None (Heyman): ``fn >= 0`` only.
"""

from __future__ import annotations

from dataclasses import dataclass

import clarabel
import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .model import Model

__all__ = ["ConeRows", "cone_rows", "Scaling", "cone_violation"]


@dataclass(frozen=True)
class ConeRows:
    """Rows ``M`` with ``M x`` in (zero^nz x nonneg^nn x SOC(3)^ns), stacked in that order."""

    M: sp.csr_matrix
    n_zero: int
    n_nonneg: int
    n_soc: int

    def cones(self, leading_zero: int = 0, extra_nonneg: int = 0) -> list:
        """Clarabel cone list, with ``leading_zero`` equality rows before these rows and
        ``extra_nonneg`` nonnegative rows placed before this block's nonnegative rows."""
        out: list = []
        if leading_zero + self.n_zero:
            out.append(clarabel.ZeroConeT(leading_zero + self.n_zero))
        if extra_nonneg + self.n_nonneg:
            out.append(clarabel.NonnegativeConeT(extra_nonneg + self.n_nonneg))
        out += [clarabel.SecondOrderConeT(3)] * self.n_soc
        return out

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
    fn, ft = f[:, 0], f[:, 1:]
    viol = np.maximum(0.0, -fn)
    if friction is not None:
        viol = np.maximum(viol, np.linalg.norm(ft, axis=1) - float(friction) * fn)
    return float(viol.max(initial=0.0))


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
