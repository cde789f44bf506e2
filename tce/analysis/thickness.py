"""Minimum thickness: the geometric safety factor of an arch (or any family of structures).

:func:`minimum_thickness` bisects a geometric parameter ``t`` between a value where the
structure stands and one where it does not; "stands" means the TCE with no support motion
is ``optimal`` under self-weight, or under a load pattern at a fixed multiplier ``lam`` of
its live part. :func:`arch_minimum_thickness` applies it to the semicircular arch of fixed
centreline radius ``R`` and reports ``t / R`` (Milankovitch's continuous value under
self-weight: ``t/R = 0.1075``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

from ..core.analysis import Analysis
from ..core.loads import LoadPattern
from ..structures.arch import semicircular_arch
from ..structures.params import check_positive, check_whole
from ..structures.assembly import Assembly
from ..core.material import Material
from ..core.result import Result

__all__ = ["ThicknessResult", "arch_minimum_thickness", "minimum_thickness"]


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class ThicknessResult(Result):
    """Outcome of a minimum-thickness bisection (``status`` ``optimal``: a bracket was found;
    ``thickness`` is verified standing whatever ``undecided`` says).

    Attributes
    ----------
    thickness : float
        Smallest thickness found to stand (m): the upper end of the final bracket.
    lower : float
        Largest thickness found not to stand (m).
    ratio : float
        ``thickness / reference`` (for arches, the centreline radius).
    undecided : int
        Solves whose status was ``numerical`` (treated as "does not stand").
    """

    HEADLINE = ("thickness", "lower", "ratio", "n_solves", "undecided")

    thickness: float
    lower: float
    ratio: float
    n_solves: int
    undecided: int = 0


def minimum_thickness(
    build: Callable[[float], Assembly],
    lo: float,
    hi: float,
    material: Material | None = None,
    tol: float = 1e-6,
    reference: float = 1.0,
    loads: LoadPattern | None = None,
    lam: float = 0.0,
    progress: Callable[[int, int], None] | None = None,
) -> ThicknessResult:
    """Bisect the thinnest ``t`` in ``[lo, hi]`` for which ``build(t)`` stands under self-weight
    (or the pattern ``loads`` at multiplier ``lam``).

    Parameters
    ----------
    build : callable
        ``t -> Assembly`` (t in m).
    lo, hi : float
        A thickness that does not stand and one that does (m); checked.
    material : Material, optional
        Default: Heyman (unlimited friction), rigid.
    tol : float
        Relative width of the final bracket, ``(hi - lo) / hi``.
    reference : float
        Length that ``ratio`` divides by (m).
    loads : LoadPattern, optional
        Loads beside the self-weight, resolved against each structure built (block names
        and ``on_top`` points must fit every thickness tried); default: self-weight alone.
    lam : float
        Multiplier of the pattern's live part (>= 0; default 0: its fixed part only).
    progress : callable, optional
        ``progress(solves done, solves expected)`` after each solve (the expected count is
        an upper bound until the last call, where both are equal).

    Raises
    ------
    ValueError
        When ``hi`` does not stand or ``lo`` does, or ``lam`` is negative or not finite.
    """
    check_positive(lo=lo, hi=hi, tol=tol, reference=reference)
    if not (math.isfinite(lam) and lam >= 0):
        raise ValueError(f"lam must be a finite number >= 0, got {lam!r}")
    if not lo < hi:
        raise ValueError(f"need lo < hi, got lo={lo}, hi={hi}")
    material = material or Material()
    t0 = time.perf_counter()
    n = undecided = 0
    solve_time = 0.0

    # solves: the two ends, then one per halving of the bracket down to tol * lo (an upper bound)
    expected = 2 + max(0, math.ceil(math.log2((hi - lo) / (tol * lo))))

    def stands(t: float) -> bool:
        nonlocal n, undecided, solve_time
        n += 1
        r = Analysis(build(t), material).solve(lam, loads=loads)
        undecided += r.status == "numerical"
        solve_time += r.solve_time
        if progress is not None:
            progress(n, max(expected, n))
        return r.status == "optimal"

    if not stands(hi):
        raise ValueError(f"the structure does not stand at the upper thickness {hi} m: raise it")
    if stands(lo):
        raise ValueError(f"the structure already stands at the lower thickness {lo} m: lower it")
    while (hi - lo) > tol * hi:
        mid = 0.5 * (lo + hi)
        if stands(mid):
            hi = mid
        else:
            lo = mid
    if progress is not None:
        progress(n, n)
    return ThicknessResult(
        status="optimal", message=f"bracket [{lo:.9g}, {hi:.9g}] m after {n} solves ({undecided} undecided)",
        solve_time=solve_time, wall_time=time.perf_counter() - t0,
        thickness=hi, lower=lo, ratio=hi / reference, n_solves=n, undecided=undecided,
    )


def arch_minimum_thickness(
    centre_radius: float = 1.0,
    voussoirs: int = 14,
    depth: float = 0.25,
    material: Material | None = None,
    tol: float = 1e-6,
    loads: LoadPattern | None = None,
    lam: float = 0.0,
    progress: Callable[[int, int], None] | None = None,
    joints: str = "radial",
) -> ThicknessResult:
    """Minimum thickness of a semicircular arch with fixed centreline radius (m).

    The intrados radius is ``centre_radius - t/2``; ``ratio`` is ``t / centre_radius``;
    ``loads``, ``lam`` and ``progress`` as in :func:`minimum_thickness`; ``joints``
    (``radial`` or ``vertical``) as in :func:`tce.structures.arch.semicircular_arch`.
    """
    check_positive(centre_radius=centre_radius, depth=depth)
    n = check_whole(voussoirs, "voussoirs")

    def build(t: float) -> Assembly:
        return semicircular_arch(centre_radius - t / 2, t, depth, n, joints=joints)

    return minimum_thickness(
        build, 0.01 * centre_radius, 0.5 * centre_radius, material, tol, reference=centre_radius, loads=loads,
        lam=lam, progress=progress,
    )
