"""The contact law as cone rows, and the scaling that makes the conic data dimensionless.

The contact law of a model is a set of rows ``M F + h in K`` on the force vector ``F``
(``(nc * dim,)``, kN), with ``K`` a product of a zero cone, a nonnegative cone and
second-order cones of dimension 3, in that row order (:class:`ConeRows`). The problems of
:mod:`tce.core.problem` put them in Clarabel's form ``A x + s = b, s in K`` with ``A = -M``
and ``b = h / W``: the unknown ``x`` is ``F`` divided by the reference force ``W`` (the
total weight of the free blocks, :class:`Scaling`); equilibrium force rows are divided by
``W`` and moment rows by ``W L`` (``L`` the assembly size). Answers are therefore
independent of the units a user picks (``docs/conventions.md``).

Contact laws of the paper's dry joint (per contact, ``fn`` first; ``h = 0`` for all of them):

- spatial, mu > 0: ``(mu fn, ft1, ft2)`` in a second-order cone;
- planar, mu > 0: ``mu fn - ft >= 0`` and ``mu fn + ft >= 0``;
- mu = 0: tangential components fixed to zero, ``fn >= 0``;
- mu None (Heyman): ``fn >= 0`` only.

Beyond it (:class:`tce.core.material.Material`, ``docs/materials.md``), with ``A`` the
contact's tributary area (m^2) and ``g = c A`` (kN) its shear capacity at zero normal force,
the offsets ``h`` carry the strengths:

- cohesion: ``(mu fn + g, ft1, ft2)`` in the cone (planar ``mu fn + g -+ ft >= 0``), and
  ``fn + t A >= 0`` as its own row (the shifted cone no longer implies it); with mu = 0 and
  ``g > 0`` the cone is ``(g, ft1, ft2)``: a purely cohesive (Tresca) joint;
- tensile strength: ``fn + t A >= 0``;
- compressive strength: ``fc A - fn >= 0``.

Every bound is linear in the area, so a planar contact (the vertices projecting onto one
end of an interface's trace, :mod:`tce.core.model`) gets the bounds of the summed area and
the planar model stays exact: the proportional lift of a planar state meets every vertex's
bound, and summing the vertex bounds of a spatial state gives the planar ones.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .model import Model

__all__ = [
    "LawCheck","ConeRows", "Scaling", "cone_rows", "cone_violation", "law_violation"]


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
        Offset of each row (kN); None is zero (the paper's laws in :func:`cone_rows`).
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


Law = float | NDArray[np.float64]


def _per_contact(model: Model, friction: float | NDArray[np.float64] | None, cohesion: Law, tensile_strength: Law,
                 compressive_strength: Law | None, shear_capacity: NDArray[np.float64] | None
                 ) -> tuple[NDArray[np.float64], ...]:
    """``(mu, t A, fc A, g, extended)`` per contact (NaN mu: unlimited friction; ``inf``: no
    bound; kN; ``extended``: a cohesion, a tensile strength or a shear capacity is given):
    a law given as scalars or as ``(nc,)`` arrays (:meth:`tce.core.material.Material.contact_law`),
    with ``g = c A + shear_capacity`` the shear capacity at zero normal force. Checks that the
    contacts have an area where a compressive strength needs one."""
    nc = model.n_contacts
    area = np.asarray(model.contact_area, dtype=float)

    def each(v: Law | None, absent: float) -> NDArray[np.float64]:
        return np.broadcast_to(np.asarray(absent if v is None else v, dtype=float), (nc,))

    mu, fc = each(friction, np.nan), each(compressive_strength, np.inf)
    if np.any(np.isfinite(fc) & (area <= 0)):
        bad = int(np.count_nonzero(np.isfinite(fc) & (area <= 0)))
        raise ValueError(
            f"compressive_strength needs a tributary area at every contact: {bad} contact(s) have none "
            "(interfaces given by fewer than 3 points)"
        )
    g = each(cohesion, 0.0) * area
    if shear_capacity is not None:
        extra = np.asarray(shear_capacity, dtype=float)
        if extra.shape != (nc,) or not np.all(np.isfinite(extra)) or np.any(extra < 0):
            raise ValueError(f"shear_capacity must be {nc} finite numbers >= 0 (kN)")
        g = g + extra
    with np.errstate(invalid="ignore"):  # inf strength times a zero area: no bound
        floor = np.where(np.isinf(each(tensile_strength, 0.0)), np.inf, each(tensile_strength, 0.0) * area)
        ceiling = np.where(np.isinf(fc), np.inf, fc * area)
    extended = (each(cohesion, 0.0) > 0) | (each(tensile_strength, 0.0) > 0) | (shear_capacity is not None)
    return mu, floor, ceiling, g, extended


def cone_rows(
    model: Model,
    friction: float | NDArray[np.float64] | None,
    *,
    cohesion: Law = 0.0,
    tensile_strength: Law = 0.0,
    compressive_strength: Law | None = None,
    shear_capacity: NDArray[np.float64] | None = None,
) -> ConeRows:
    """The contact law of ``model`` as cone rows (see module doc).

    Parameters
    ----------
    model : Model
    friction : float, (nc,) array or None
        mu >= 0, or None for unlimited friction (Heyman); per contact, NaN is unlimited.
    cohesion, tensile_strength : float or (nc,) array
        ``c`` and ``t`` (kN/m^2), times each contact's tributary area
        (:attr:`tce.core.model.Model.contact_area`). A tensile strength of ``inf`` with
        unlimited friction is a bonded contact: no row at all.
    compressive_strength : float, (nc,) array or None
        ``fc`` (kN/m^2): ``fn <= fc A`` per contact; None (or ``inf``): unlimited.
    shear_capacity : (nc,) array, optional
        Shear capacity (kN) added to ``c A`` at each contact: the friction capacity fixed
        from earlier normal forces in the non-associative scheme
        (:mod:`tce.analysis.nonassoc`, with ``friction = 0``).

    Returns
    -------
    ConeRows
        The paper's laws (no cohesion, tension or crushing) give exactly the rows listed in
        the module docstring with ``h = None``. Each contact gets the rows of its own law:
        its normal row ``fn + t A >= 0`` where its friction is unlimited or zero, or it has
        cohesion, tension or a shear capacity; a compressive row where its strength is
        finite; its friction rows (tangential components fixed to zero where ``mu = 0``
        and ``g = 0``) where its friction is limited.
    """
    nc, dim = model.n_contacts, model.dim
    idx = np.arange(nc) * dim
    n = model.n_vars
    mu, floor, ceiling, g, extended = _per_contact(model, friction, cohesion, tensile_strength,
                                                   compressive_strength, shear_capacity)

    def sel(cols: NDArray[np.int64], vals: float | NDArray[np.float64] = 1.0) -> sp.csr_matrix:
        data = np.broadcast_to(np.asarray(vals, dtype=float), cols.shape)
        return sp.csr_matrix((data, (np.arange(len(cols)), cols)), shape=(len(cols), n))

    zero: list[sp.csr_matrix] = []
    nonneg: list[tuple[sp.csr_matrix, NDArray[np.float64]]] = []
    soc: tuple[sp.csr_matrix, NDArray[np.float64]] | None = None
    heyman = np.isnan(mu)
    # normal force: fn + t A >= 0 (implied by the cone for plain Coulomb with mu > 0; none when bonded)
    normal = (heyman | (mu == 0.0) | extended) & np.isfinite(floor)
    if normal.any():
        nonneg.append((sel(idx[normal]), floor[normal]))
    crush = np.isfinite(ceiling)
    if crush.any():
        nonneg.append((sel(idx[crush], -1.0), ceiling[crush]))
    if not heyman.all():
        free = ~heyman & ((mu > 0) | (g > 0))  # contacts whose tangential force may be nonzero
        locked = idx[~heyman & ~free]
        zero.append(sel((locked[:, None] + np.arange(1, dim)[None, :]).ravel()))
        c = idx[free]
        if dim == 2:
            cap = sel(c, mu[free])
            nonneg.append((cap - sel(c + 1), g[free]))
            nonneg.append((cap + sel(c + 1), g[free]))
        else:
            # interleave (mu fn + g, ft1, ft2) per contact
            k = len(c)
            rows = np.repeat(np.arange(k) * 3, 3) + np.tile(np.arange(3), k)
            cols = (c[:, None] + np.arange(3)[None, :]).ravel()
            vals = np.column_stack([mu[free], np.ones(k), np.ones(k)]).ravel()
            M = sp.csr_matrix((vals, (rows, cols)), shape=(3 * k, n))
            h = np.zeros(3 * k)
            h[0::3] = g[free]
            soc = (M, h)
    blocks = zero + [m for m, _ in nonneg] + ([soc[0]] if soc else [])
    M = sp.vstack(blocks).tocsr() if blocks else sp.csr_matrix((0, n))
    M.eliminate_zeros()
    n_zero = sum(z.shape[0] for z in zero)
    n_nonneg = sum(m.shape[0] for m, _ in nonneg)
    h = np.concatenate([np.zeros(n_zero)] + [v for _, v in nonneg] + ([soc[1]] if soc else []))
    return ConeRows(M, n_zero, n_nonneg, 0 if soc is None else soc[0].shape[0] // 3, h if np.any(h) else None)


class LawCheck:
    """The violation of a contact law by a force state, with its per-contact bounds computed
    once (a load path checks every answer with the same law).

    Per contact with area ``A`` and ``g = c A + shear_capacity``: ``max(0, -(fn + t A))``,
    ``max(0, fn - fc A)`` with a compressive strength, and ``||ft|| - mu fn - g`` with
    friction (``||ft|| - g`` for ``mu = 0``); nothing more for Heyman, nothing at all for a
    bonded contact. For the paper's law this is ``max(0, -fn, ||ft|| - mu fn)``. Arguments
    as :func:`cone_rows`.
    """

    def __init__(
        self,
        model: Model,
        friction: float | NDArray[np.float64] | None,
        *,
        cohesion: Law = 0.0,
        tensile_strength: Law = 0.0,
        compressive_strength: Law | None = None,
        shear_capacity: NDArray[np.float64] | None = None,
    ) -> None:
        mu, floor, ceiling, g, _ = _per_contact(model, friction, cohesion, tensile_strength, compressive_strength,
                                                shear_capacity)
        self.shape = (model.n_contacts, model.dim)
        self.floor = floor if np.any(floor) else None  # fn >= -t A
        self.ceiling = ceiling if np.isfinite(ceiling).any() else None
        self.limited = ~np.isnan(mu)
        self.friction = mu[self.limited] if self.limited.any() else None
        self.g = g[self.limited] if np.any(g) else None

    def __call__(self, forces: NDArray[np.float64]) -> float:
        """Largest violation by ``forces`` ((nc, dim) or flat, kN), in kN."""
        f = np.asarray(forces).reshape(self.shape)
        if not len(f):
            return 0.0
        fn = f[:, 0]
        worst = max(0.0, -float((fn if self.floor is None else fn + self.floor).min()))
        if self.ceiling is not None:
            worst = max(worst, float((fn - self.ceiling).max()))
        if self.friction is not None:
            fl = f[self.limited]
            ft = np.abs(fl[:, 1]) if self.shape[1] == 2 else np.sqrt(fl[:, 1] ** 2 + fl[:, 2] ** 2)
            excess = ft - self.friction * fl[:, 0]
            worst = max(worst, float((excess if self.g is None else excess - self.g).max(initial=0.0)))
        return worst


def cone_violation(
    model: Model,
    friction: float | NDArray[np.float64] | None,
    forces: NDArray[np.float64],
    *,
    cohesion: Law = 0.0,
    tensile_strength: Law = 0.0,
    compressive_strength: Law | None = None,
    shear_capacity: NDArray[np.float64] | None = None,
) -> float:
    """Largest violation of the contact law by ``forces`` ((nc, dim), kN), in kN (see
    :class:`LawCheck`, which keeps the bounds for repeated checks)."""
    return LawCheck(
        model, friction, cohesion=cohesion, tensile_strength=tensile_strength,
        compressive_strength=compressive_strength, shear_capacity=shear_capacity,
    )(forces)


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
