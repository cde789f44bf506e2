"""Samples of one geometry solved together: a batch of :class:`WarmLimit` problems in one call.

A prototype of the batched solve ``docs/reliability.md`` ("Batched solves on a GPU") describes,
behind the optional extra ``batched`` (``pip install tce[batched]``, the Moreau solver: a
batched conic interior point derived from Clarabel.rs, Apache-2.0). Every sample of a
:class:`~tce.analysis.reliability.WarmLimit` has the same sparsity pattern of ``A``, the same
``q`` and the same cones; only the values of ``A`` (friction) and ``b`` (cohesion, tension,
the load factors) change. Moreau's ``CompiledSolver`` is built once from that pattern and
cones and solves a batch of value sets per call, on the CPU (``moreau-cpu``) or on an NVIDIA
GPU (``moreau-cuda12``/``-cuda13``, Python 3.12+).

Each answer is judged as the warm solver's is (``Solved`` or ``AlmostSolved``, then
:meth:`WarmLimit.violation` at 1e-8 on the scaled problem); an answer that is not clean, and
is not a ``PrimalInfeasible`` certificate, is solved again by the :class:`WarmLimit` itself
(its Clarabel solve, then the fresh :class:`~tce.core.limit.LimitSolver` that proves an
unbounded limit), so the statuses are those of :class:`WarmLimit`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..core.clarabel_solver import SOLVED
from .reliability import Sample, WarmLimit

__all__ = ["BatchedLimit"]


class BatchedLimit:
    """Direct ``lambda_max`` of many samples of one :class:`WarmLimit`, solved in batches by Moreau.

    Parameters
    ----------
    warm : WarmLimit
        The model, the variables and the tolerances (Clarabel's settings of ``warm`` are
        passed on: gap, feasibility and infeasibility tolerances, ``tol_ktratio``,
        ``max_iter``).
    batch_size : int
        Problems per solver call (the last batch of a call is padded by repeating its last
        sample).
    device : {"cpu", "cuda"}
        Moreau's backend; ``cuda`` needs ``moreau-cuda12`` or ``-cuda13`` and an NVIDIA GPU.

    Attributes
    ----------
    resolved : int
        Samples so far whose batched answer was solved again by ``warm``.

    Raises
    ------
    ImportError
        Moreau is not installed (``pip install tce[batched]``).
    """

    def __init__(self, warm: WarmLimit, batch_size: int = 256, device: str = "cpu") -> None:
        try:
            import moreau
        except ImportError as exc:  # pragma: no cover - the message is the point
            raise ImportError("BatchedLimit needs the Moreau solver: pip install tce[batched]") from exc
        self.warm = warm
        self.batch_size = int(batch_size)
        A = warm.base.A.tocsc()
        # the CSR order of A's nonzeros as positions in its CSC data (Moreau takes CSR)
        tagged = sp.csc_matrix((np.arange(1, A.nnz + 1, dtype=float), A.indices, A.indptr), shape=A.shape).tocsr()
        self._csr = tagged.data.astype(np.int64) - 1
        kinds = [k for k, _ in warm.base.cones]
        if kinds != sorted(kinds, key=["zero", "nonneg", "soc"].index):
            raise ValueError(f"cones must come as zero, nonneg, soc blocks; got {kinds}")
        cones = moreau.Cones(num_zero_cones=sum(d for k, d in warm.base.cones if k == "zero"),
                             num_nonneg_cones=sum(d for k, d in warm.base.cones if k == "nonneg"),
                             so_cone_dims=[d for k, d in warm.base.cones if k == "soc"])
        c = warm.settings
        ipm = moreau.IPMSettings(tol_gap_abs=c.tol_gap_abs, tol_gap_rel=c.tol_gap_rel, tol_feas=c.tol_feas,
                                 tol_infeas_abs=c.tol_infeas_abs, tol_infeas_rel=c.tol_infeas_rel,
                                 tol_ktratio=c.tol_ktratio)
        n, m = A.shape[1], A.shape[0]
        self.solver = moreau.CompiledSolver(
            n=n, m=m, P_row_offsets=np.zeros(n + 1, dtype=np.int64), P_col_indices=np.zeros(0, dtype=np.int64),
            A_row_offsets=tagged.indptr.astype(np.int64), A_col_indices=tagged.indices.astype(np.int64), cones=cones,
            settings=moreau.Settings(solver="ipm", device=device, batch_size=self.batch_size, max_iter=c.max_iter,
                                     ipm_settings=ipm))
        self._q = np.tile(warm.base.q, (self.batch_size, 1))
        #: samples whose batched answer was solved again by the WarmLimit (not clean, undecided)
        self.resolved = 0

    def __call__(self, samples: Sequence[Sample]) -> tuple[NDArray[np.str_], NDArray[np.float64]]:
        """Statuses and ``lambda_max`` of the samples, in order (:class:`WarmLimit`'s statuses;
        ``lambda_max`` NaN unless ``optimal``, inf when unbounded).

        Raises
        ------
        KeyError, ValueError
            A sample lacks a variable or has a value the material refuses, as :class:`WarmLimit`.
        """
        data = [self.warm.data(s) for s in samples]
        statuses: list[str] = []
        values: list[float] = []
        for start in range(0, len(data), self.batch_size):
            part = data[start:start + self.batch_size]
            pad = part + [part[-1]] * (self.batch_size - len(part))
            A = np.stack([a for a, _ in pad])
            b = np.stack([b for _, b in pad])
            self.solver.setup(np.zeros((self.batch_size, 0)), A[:, self._csr])
            sol = self.solver.solve(self._q, b)
            for i, status in enumerate(self.solver.info.status[: len(part)]):
                x = np.asarray(sol.x[i])
                if status.name == "PrimalInfeasible":
                    out = ("infeasible", math.nan)
                elif status.name in SOLVED and self.warm.violation(A[i], b[i], x) <= 1e-8:
                    out = ("optimal", float(x[-1]))
                else:
                    out = self.warm(samples[start + i])
                    self.resolved += 1
                statuses.append(out[0])
                values.append(out[1])
        return np.array(statuses, dtype=str), np.array(values, dtype=float)
