"""The validation atlas: tce against published values, case by case (``tce check --validation``).

Each :class:`ValidationCase` names its source, the published value and where it is printed,
the reference (the publication's own model and assumptions computed without tce: a continuous
LP, a closed form, a mechanism by hand), computes tce's value under the same assumptions at a
coarse discretisation (a few seconds a case), and states its discretisation error against the
reference, the tolerance (at most twice that error, or the precision of the comparison where
tce's blocks are the publication's) and why. It also states whether the reference rounds to
the published value at its printed digits. The convergence with the discretisation is in
``docs/validation.md`` (drawn by ``docs/make_validation_figures.py``);
``tests/validation/literature/`` checks every case and these rules.

Sources:

- Cocchetti, G. & Rizzi, E. (2020). Analytical and numerical analysis on the collapse modes
  of least-thickness circular masonry arches at decreasing friction. *Frattura ed Integrità
  Strutturale* 51, 356-375, doi:10.3221/IGF-ESIS.51.26, Table 3 ("CR2020" below).
- Makris, N. & Alexakis, H. (2013). The effect of stereotomy on the shape of the thrust-line
  and the minimum thickness of semicircular masonry arches. *Archive of Applied Mechanics* 83,
  1511-1533; the values as stated in Makris's seminar abstract of the same title (Cambridge
  University Engineering Department, 1 November 2013): Milankovitch's radial-joint
  ``t/R = 0.1075`` and the vertical-joint ``t/R = 0.1095`` ("MA2013").
- The paper (*3D exploration of internal stresses due to lateral loads and foundation
  movements in a semicircular arch*): ``lambda_0max = 0.243`` (Fig. 8) and
  ``lambda_90max = 0.178`` (Fig. 9), printed to three digits.
- LACT3 v1.0 (Y. Hua, M. Buzzetti, N. Pingaro, L. C. M. da Silva, G. Milani, 2025; repository
  GabrieleMilani/LACT3_v1.0), its solver test: the collapse tilt of its sample wall, 16.73 deg
  at a friction angle of 26 deg (:mod:`tce.quality.walls`), and of its sample arch ``arch_1``,
  17.10 deg at 30 deg (:func:`tilting_arch`): a code's test values, not a publication's.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache, partial

import numpy as np
import pandas as pd

from ..analysis.nonassoc import nonassociative_limit
from ..analysis.thickness import arch_minimum_thickness, minimum_thickness
from ..core.analysis import Analysis
from ..core.loads import LoadPattern
from ..core.material import Material
from ..core.result import Result
from ..structures.arch import segmental_arch, semicircular_arch
from ..structures.dome import hemispherical_dome
from ..structures.assembly import Assembly, Block, Interface
from ..structures.geometry import box
from .walls import lact3_wall, tilt_angle

__all__ = [
    "CASES",
    "ValidationCase",
    "block_on_strips",
    "arch_in_strips",
    "crown_thrust",
    "dome_min_ratio",
    "format_validation",
    "friction_bound",
    "nonassoc_min_ratio",
    "run_validation",
    "stress_block_column",
    "tilting_arch",
]

#: voussoirs of the arch cases in the command and the suite (the figures go to 640)
VOUSSOIRS = 160
#: depth (m) and unit weight (kN/m^3) of the arch cases; answers are dimensionless
DEPTH, UNIT_WEIGHT = 0.25, 20.0


@dataclass(frozen=True)
class ValidationCase:
    """One published value and how tce reproduces it.

    Attributes
    ----------
    name : str
        Short key (``tce check --validation --select`` matches it).
    source, where : str
        Short citation (the module docstring gives the full ones); table or figure.
    quantity : str
        What is compared, with its symbol.
    published : float
    compute : callable
        ``() -> float``: tce's value for the model ``discretisation`` describes.
    discretisation : str
    tolerance : float
        Largest accepted ``|tce - reference|`` (absolute): at most twice ``error`` where tce
        discretises what the publication does not; otherwise the precision stated in ``why``
        (of the solver, of a reading off a figure, of a printed value).
    why : str
        Why that tolerance, and what the difference is where there is one.
    reference : float, optional
        The value of the publication's own model and assumptions computed independently of
        tce (a continuous LP, a closed form, a mechanism by hand): what tce's value converges
        to. Default: the published value itself (no independent computation).
    error : float, optional
        The stated discretisation error of tce's value against ``reference`` (absolute; None
        where tce's blocks are the publication's, so that there is nothing to converge).
    digits : int, optional
        Decimals printed in the source; default those of ``published`` as a float prints.
    rounds : bool
        Whether ``reference`` rounds to ``published`` at its printed digits (False: the
        table says it does not, and by how much).
    """

    name: str
    source: str
    where: str
    quantity: str
    published: float
    compute: Callable[[], float]
    discretisation: str
    tolerance: float
    why: str
    reference: float | None = None
    error: float | None = None
    digits: int | None = None
    rounds: bool = True

    @property
    def expected(self) -> float:
        """What tce's value is compared with: ``reference``, or the published value."""
        return self.published if self.reference is None else self.reference

    @property
    def decimals(self) -> int:
        """Decimals of the printed value."""
        if self.digits is not None:
            return self.digits
        text = repr(float(self.published))
        return len(text.split(".")[1]) if "." in text and "e" not in text else 0

    def at_printed_digits(self) -> float:
        """``expected`` rounded to the decimals the source prints."""
        return round(self.expected, self.decimals)


# ------------------------------------------------------------------------------ arch cases
#: where a voussoir's self-weight acts: at its own centroid (``ring``, what a rigid voussoir
#: carries), or that of its ring sector lumped on the centreline arc (``centreline``, CR2020's
#: assumption: docs/validation.md)
WEIGHTS = ("ring", "centreline")


def _arch(t: float, n: int, joints: str = "radial") -> Assembly:
    """Semicircular arch of centreline radius 1 m and thickness ``t`` (m)."""
    return semicircular_arch(1.0 - t / 2.0, t, DEPTH, n, UNIT_WEIGHT, joints=joints)


def centreline_weights(arch: Assembly) -> LoadPattern:
    """Fixed point loads (kN) that move the self-weight of each voussoir of ``arch`` (an
    :func:`_arch` of ``n`` voussoirs, thickness ``t``, radial joints) to the centreline arc:
    its own weight lifted at its centroid, and the weight of its ring sector,
    ``gamma d t R pi / n``, hung at the centroid of the centreline arc it spans (radius
    ``R sin(a) / a`` on its bisector, ``a = pi / (2 n)``, ``R = 1``)."""
    n, t = arch.meta["voussoirs"], arch.meta["thickness"]
    a = math.pi / (2.0 * n)
    radius, weight = math.sin(a) / a, UNIT_WEIGHT * DEPTH * t * 2.0 * a
    points = []
    for k, i in enumerate(arch.free_indices):
        block = arch.blocks[i]
        phi = math.pi * (1.0 - (k + 0.5) / n)
        points += [dict(force=[0.0, 0.0, block.weight], block=block.name, scaled=False),
                   dict(force=[0.0, 0.0, -weight], block=block.name, scaled=False,
                        at=[radius * math.cos(phi), 0.0, radius * math.sin(phi)])]
    return LoadPattern(point=points)  # lambda multiplies the lateral pattern; these solves are at lambda = 0


def _solve(t: float, n: int, mu: float | None, joints: str = "radial", weights: str = "ring") -> Result:
    if weights not in WEIGHTS or (weights == "centreline" and joints != "radial"):
        raise ValueError(f"weights must be one of {WEIGHTS} (centreline with radial joints), got {weights!r}")
    arch = _arch(t, n, joints)
    loads = centreline_weights(arch) if weights == "centreline" else None
    return Analysis(arch, Material(friction=mu)).solve(0.0, loads=loads)


def _stands(t: float, n: int, mu: float | None, joints: str = "radial", weights: str = "ring") -> bool:
    return _solve(t, n, mu, joints, weights).status == "optimal"


def _least(stands: Callable[[float], bool], lo: float, hi: float, tol: float) -> float:
    """The least value in ``[lo, hi]`` for which ``stands`` holds (bisected to ``tol``, absolute;
    ``stands`` false at ``lo``, true at ``hi``, monotone)."""
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if stands(mid) else (mid, hi)
    return hi


@cache
def min_ratio(n: int = VOUSSOIRS, mu: float | None = None, joints: str = "radial", tol: float = 1e-6,
              weights: str = "ring") -> float:
    """``t/R`` of the thinnest semicircular arch of ``n`` voussoirs that stands (friction ``mu``),
    its self-weight as ``weights`` says (:data:`WEIGHTS`); bracketed to ``tol`` relative
    (``tol / 10`` absolute with centreline weights: t/R > 0.1 there)."""
    if weights == "ring":
        return arch_minimum_thickness(1.0, n, DEPTH, Material(friction=mu), tol=tol, joints=joints).ratio
    if not _stands(0.5, n, mu, joints, weights):
        raise ValueError(f"the arch of {n} voussoirs does not stand at t/R = 0.5 with mu = {mu}")
    return _least(lambda t: _stands(t, n, mu, joints, weights), 0.01, 0.5, tol * 0.1)


def friction_bound(t: float, n: int = VOUSSOIRS, lo: float = 0.2, hi: float = 0.8, tol: float = 1e-7,
                   weights: str = "ring") -> float:
    """Least friction coefficient at which the arch of thickness ratio ``t`` stands (bisection).

    Raises
    ------
    ValueError
        If the arch does not stand at ``hi`` or already stands at ``lo``.
    """
    if not _stands(t, n, hi, weights=weights) or _stands(t, n, lo, weights=weights):
        raise ValueError(f"the friction bound of t/R = {t} is not in [{lo}, {hi}]")
    return _least(lambda mu: _stands(t, n, mu, weights=weights), lo, hi, tol)


def crown_thrust(t: float, n: int = VOUSSOIRS, mu: float | None = None, weights: str = "ring") -> float:
    """Horizontal thrust of the arch of thickness ratio ``t`` on its left support, made
    dimensionless as CR2020's ``h = H / (gamma d R t)`` (their self-weight per radian), read
    from any admissible state (near the minimum thickness the thrusts close on one value;
    NaN if none)."""
    r = _solve(t, n, mu, weights=weights)
    if r.status != "optimal":
        return math.nan
    return abs(float(r.support_wrenches[0, 0])) / (UNIT_WEIGHT * DEPTH * 1.0 * t)


@cache
def _mu_sliding(weights: str = "ring") -> float:
    """tce's mu_ms: the least friction at which the arch stands at all (t/R = 0.25 > eta_ms)."""
    return friction_bound(0.25, lo=0.29, hi=0.33, weights=weights)


# --------------------------------------------------------------------------- crushing case
def block_on_strips(strips: int, b: float = 0.4, d: float = 0.3, h: float = 1.0, unit_weight: float = 20.0) -> Assembly:
    """One block (``b`` wide along x, ``d`` deep, ``h`` tall, m) on a wider support slab, its base
    joint given as ``strips`` interfaces, strips of width ``b / strips`` along x."""
    support = Block("base", box([-b, -d, -0.2], [b, d, 0.0]), unit_weight, True)
    block = Block("block", box([-b / 2, -d / 2, 0.0], [b / 2, d / 2, h]), unit_weight, False)
    x = np.linspace(-b / 2, b / 2, strips + 1)
    faces = tuple(
        Interface(0, 1, np.array([[x0, -d / 2, 0.0], [x1, -d / 2, 0.0], [x1, d / 2, 0.0], [x0, d / 2, 0.0]]),
                  np.array([0.0, 0.0, 1.0]))
        for x0, x1 in zip(x[:-1], x[1:])
    )
    return Assembly((support, block), faces, {})


def stress_block_column(strips: int = 40, fc: float = 40.0) -> float:
    """lambda_max of :func:`block_on_strips` (defaults: 0.4 x 0.3 x 1 m, 20 kN/m^3) under the
    lateral pattern, compressive strength ``fc`` (kN/m^2), Heyman friction.

    The closed form (rigid-plastic stress block, docs/materials.md): the compressed zone is
    ``x = W / (fc d)`` at the toe and the resultant at ``x / 2`` from it, so moments about that
    point under the lateral load ``lam W`` at the centroid (height ``h / 2``) give
    ``lam = (b - W / (fc d)) / h``, reached exactly when ``x`` is a whole number of strips.
    """
    return Analysis(block_on_strips(strips), Material(compressive_strength=fc)).limit(0.0).lambda_max


def _stress_block_closed_form(b: float = 0.4, d: float = 0.3, h: float = 1.0, fc: float = 40.0,
                              unit_weight: float = 20.0) -> float:
    w = unit_weight * b * d * h
    return (b - w / (fc * d)) / h


def arch_in_strips(assembly: Assembly, strips: int) -> Assembly:
    """The same blocks with every interface cut into ``strips`` equal strips across the joint.

    Each quadrilateral interface of an arch spanning x (depth along y) has its two edges
    normal to y (intrados to extrados) cut into ``strips`` equal parts, joined across the
    depth; a compressive strength then bounds each strip's force, and the joint approaches
    the rigid-plastic stress block as the strips are refined. Each strip keeps its
    interface's normal and stiffness; ``meta["strips"]`` records the number.

    Raises
    ------
    ValueError
        ``strips`` is not a whole number >= 1, or an interface is not a quadrilateral.
    """
    if isinstance(strips, bool) or not isinstance(strips, (int, np.integer)) or strips < 1:
        raise ValueError(f"strips must be a whole number >= 1, got {strips!r}")
    faces = []
    for face in assembly.interfaces:
        p = np.asarray(face.points, dtype=float)
        if len(p) != 4:
            raise ValueError(f"interface {face.a}-{face.b} has {len(p)} vertices, not 4")
        # the edges 0-1 and 3-2, or 1-2 and 0-3, that lie in planes of constant y
        if abs(p[1, 1] - p[0, 1]) < 1e-12 and abs(p[2, 1] - p[3, 1]) < 1e-12:
            front, back = (p[0], p[1]), (p[3], p[2])
        else:
            front, back = (p[1], p[2]), (p[0], p[3])
        s = np.linspace(0.0, 1.0, strips + 1)[:, None]
        f = front[0] + s * (front[1] - front[0])
        b = back[0] + s * (back[1] - back[0])
        faces += [Interface(face.a, face.b, np.array([f[k], f[k + 1], b[k + 1], b[k]]), face.normal, face.stiffness)
                  for k in range(strips)]
    return Assembly(assembly.blocks, tuple(faces), dict(assembly.meta, strips=strips))


# ------------------------------------------------------------------------------ dome cases
#: sectors and courses of the dome case in the command and the suite (the figures go to 32 courses)
DOME_SECTORS, DOME_COURSES = 6, 8


@cache
def dome_min_ratio(sectors: int = DOME_SECTORS, courses: int = DOME_COURSES, tol: float = 1e-5) -> float:
    """``t/R`` of the thinnest hemispherical dome (mid-surface radius ``R = 1`` m, closed crown,
    ``sectors`` x ``courses`` voussoirs, Heyman's material) that stands under self-weight.

    The sectors do not change the value (a lune's equations per radian do not depend on its
    angle); the courses do: a voussoir's intrados and extrados are chords, so the value
    converges on the spherical shell's as the courses are refined (docs/validation.md).
    """
    return minimum_thickness(
        lambda t: hemispherical_dome(1.0, t, sectors, courses, unit_weight=UNIT_WEIGHT),
        0.02, 0.08, Material(), tol=tol,
    ).ratio


# ---------------------------------------------------------------------------------- cases
_CR = "Cocchetti & Rizzi 2020"
_MA = "Makris & Alexakis 2013"
_PAPER = "the paper"
_RADIAL = f"{VOUSSOIRS} radial voussoirs"
_CL = f"{_RADIAL}, weights on the centreline"
_CR_LP = ("the continuous ring's LP with CR2020's weights on the centreline arc (tests/reference/continuous_arch.py, "
          "2000 cuts)")
_CR_STEPS = ("the joints (every 1.125 deg) sample the hinges and sliding sections of the continuous ring, so the "
             "value converges in steps with the voussoirs, not as a power of them (docs/validation.md)")

#: CR2020's continuous ring with its weights on the centreline (tests/reference/continuous_arch.py, 2000
#: cuts): mu_rm at t/R x (1 + 1e-6), mu_ms, t/R and h at mu_ms + 1e-7; and tolerances twice the
#: discretisation errors of tce's values at 160 voussoirs against them
MU_RM_REF, MU_RM_ERR = 0.3958318, 6e-6
MU_MS_REF = 0.3092153
ETA_MS_REF, ETA_MS_ERR = 0.2006366, 3.5e-5
H_MS_REF, H_MS_ERR = 0.4857144, 5.1e-5

CASES: tuple[ValidationCase, ...] = (
    ValidationCase(
        "cr_eta_rotational", _CR, "Table 3", "least thickness t/R, purely rotational (mu > mu_rm)", 0.107426,
        lambda: min_ratio(mu=None, weights="centreline"), f"{_CL}, no sliding", 3.8e-5,
        f"tce with CR2020's assumption (each voussoir's weight on the centreline arc) and no sliding (the same "
        f"for any mu > mu_rm: tests/validation/literature/test_lit_cocchetti_rizzi.py) against {_CR_LP}: "
        f"0.10742605; at 160 voussoirs tce gives 0.1074077, 1.9e-5 below: {_CR_STEPS}. Tolerance twice that",
        reference=0.10742605, error=1.9e-5,
    ),
    ValidationCase(
        "cr_thrust_rotational", _CR, "Table 3", "crown thrust h = H/(gamma d R t) at the least thickness", 0.621772,
        lambda: crown_thrust(min_ratio(mu=None, weights="centreline") * (1 + 1e-6), weights="centreline"), _CL, 2e-5,
        f"{_CR_LP}: 0.621772 (its thrusts at t/R x (1 + 1e-6) span 0.6217711 to 0.6217720); tce 0.621763 at 160 "
        "voussoirs, 9e-6 below: tolerance twice the discretisation error 1e-5",
        reference=0.621772, error=1e-5,
    ),
    ValidationCase(
        "cr_mu_rotational", _CR, "Table 3, Fig. 7", "friction mu_rm below which sliding joins the hinges", 0.395832,
        lambda: friction_bound(min_ratio(mu=None, weights="centreline") * (1 + 1e-6), lo=0.3, hi=0.5,
                               weights="centreline"),
        _CL, 2 * MU_RM_ERR,
        f"the least mu at which the least-thickness arch (t/R x (1 + 1e-6)) stands; {_CR_LP}: {MU_RM_REF}; tce "
        f"0.3958264 at 160 voussoirs: tolerance twice the discretisation error {MU_RM_ERR:.1e}",
        reference=MU_RM_REF, error=MU_RM_ERR,
    ),
    ValidationCase(
        "cr_mu_sliding", _CR, "Table 3, Fig. 7", "least friction mu_ms with any equilibrium", 0.309215,
        _mu_sliding, f"{_RADIAL}, t/R = 0.25", 6.6e-5,
        "the least mu at which the arch stands at t/R = 0.25 (> eta_ms; below mu_ms no thickness stands); the "
        f"continuous LP gives {MU_MS_REF} with either weight distribution; tce 0.309183 at 160 voussoirs, 3.3e-5 "
        f"below: {_CR_STEPS} (0.309215 at 320). Tolerance twice that",
        reference=MU_MS_REF, error=3.3e-5,
    ),
    ValidationCase(
        "cr_eta_sliding", _CR, "Table 3", "least thickness t/R at mu_ms", 0.200637,
        lambda: min_ratio(mu=_mu_sliding() + 1e-7, weights="centreline"), f"{_CL}, tce's own mu_ms + 1e-7",
        2 * ETA_MS_ERR,
        f"taken at tce's own mu_ms (t/R is steep there); {_CR_LP} at its own mu_ms + 1e-7: {ETA_MS_REF}; tce "
        f"0.2006715 at 160 voussoirs: tolerance twice the discretisation error {ETA_MS_ERR:.1e}",
        reference=ETA_MS_REF, error=ETA_MS_ERR,
    ),
    ValidationCase(
        "cr_thrust_sliding", _CR, "Table 3", "crown thrust h at mu_ms", 0.485714,
        lambda: crown_thrust(min_ratio(mu=_mu_sliding() + 1e-7, weights="centreline") * (1 + 1e-6),
                             mu=_mu_sliding() + 1e-7, weights="centreline"),
        f"{_CL}, tce's own mu_ms", 2 * H_MS_ERR,
        f"the thrust of the least-thickness state at mu_ms: {H_MS_REF} in {_CR_LP} (either weight distribution); "
        f"tce 0.485664 at 160 voussoirs: tolerance twice the discretisation error {H_MS_ERR:.1e}",
        reference=H_MS_REF, error=H_MS_ERR,
    ),
    ValidationCase(
        "ma_radial", _MA, "abstract (Milankovitch)", "least thickness t/R, radial joints, no sliding", 0.1075,
        lambda: min_ratio(mu=None), _RADIAL, 4e-5,
        "the continuous ring's LP (its own centroids, Milankovitch's assumption) 0.1074776, which rounds to the "
        "printed 0.1075; tce 0.107458 at 160 voussoirs, 2.0e-5 below (0.107477 at 320): tolerance twice that",
        reference=0.1074776, error=2e-5,
    ),
    ValidationCase(
        "ma_vertical", _MA, "abstract", "least thickness t/R, vertical joints, no sliding", 0.1095,
        lambda: min_ratio(mu=None, joints="vertical"), f"{VOUSSOIRS} voussoirs, vertical joints", 1.8e-5,
        "the continuous ring's LP with vertical cuts 0.1094599, which rounds to the printed 0.1095; tce "
        "0.109451 at 160 voussoirs, 9e-6 below: tolerance twice that",
        reference=0.1094599, error=9e-6,
    ),
    ValidationCase(
        "heyman_dome", "Heyman 1977", "cited (page not read)", "least thickness t/R, hemispherical dome, no hoop tension",
        0.042, dome_min_ratio, f"{DOME_SECTORS} sectors x {DOME_COURSES} courses", 1.24e-3,
        "the spherical shell's axisymmetric LP (tests/reference/continuous_dome.py, R the mid-surface radius) "
        "0.0428399, which rounds to 0.043, not to the printed 0.042 (against the extrados radius it is 0.04194, "
        "which does: Heyman's R is not known here); tce 0.0422201 at 8 courses (the LP of the same facetted "
        "courses to 1e-7), 6.2e-4 below the shell's: tolerance twice that",
        reference=0.0428399, error=6.2e-4, rounds=False,
    ),
    ValidationCase(
        "paper_in_plane", _PAPER, "Fig. 8", "lambda_0max, 14 voussoirs, mu 0.8", 0.243,
        lambda: Analysis(semicircular_arch(), Material(friction=0.8)).limit(0.0).lambda_max,
        "the paper's arch (14 voussoirs)", 1e-6,
        "the paper's own 14 voussoirs (nothing to converge): the 4-hinge mechanism worked out by hand "
        "(tests/reference/mechanism.py) gives 0.2428243, which rounds to the printed 0.243; tolerance: the "
        "limit's precision",
        reference=0.2428243,
    ),
    ValidationCase(
        "paper_out_of_plane", _PAPER, "Fig. 9", "lambda_90max, 14 voussoirs, mu 0.8", 0.178,
        lambda: Analysis(semicircular_arch(), Material(friction=0.8)).limit(90.0).lambda_max,
        "the paper's arch (14 voussoirs)", 1e-6,
        "the paper's own 14 voussoirs: the arch rocking about its springing edges, (d/2)/z_c = 0.1787600 "
        "(z_c the height of the voussoirs' centroid), which rounds to 0.179, not to the printed 0.178 (one unit "
        "of its last digit below: truncated, or another model); tolerance: the limit's precision",
        reference=0.1787600, rounds=False,
    ),
    ValidationCase(
        "stress_block", "closed form (not published)", "docs/materials.md", "lambda of one block with fc, (B - W/(fc D))/H",
        _stress_block_closed_form(), lambda: stress_block_column(40), "base joint in 40 strips", 1e-9,
        "exact when the compressed zone W/(fc D) is a whole number of strips (here 0.2 m = 20 strips)",
    ),
)

# ------------------------------------------------------- non-associative friction (the 27-block arch)
#: voussoirs of Gilbert, Casapulla & Ahmed's arch ("a semicircular arch composed of 27 blocks")
GCA_VOUSSOIRS = 27


def nonassoc_min_ratio(mu: float, n: int = GCA_VOUSSOIRS, check: float = 1e-3) -> float:
    """Least ``t/R`` of the ``n``-voussoir arch (friction ``mu``) for joints that slide
    without dilatancy: :func:`min_ratio`, confirmed when, at ``t/R (1 + check)``,
    :func:`tce.analysis.nonassoc.nonassociative_limit` (in-plane lateral pattern) converges to
    ``lambda_nonassoc = lambda_assoc > 0`` (the arch then stands for either flow rule, and
    below ``t/R`` for neither). NaN when the check fails."""
    ratio = min_ratio(n, mu=mu, tol=1e-7)
    t = ratio * (1.0 + check)
    r = nonassociative_limit(Analysis(_arch(t, n), Material(friction=mu, flow="non-associative")), 0.0)
    closed = r.status == "converged" and r.lambda_assoc > 0 and abs(r.lambda_nonassoc - r.lambda_assoc) <= 1e-6 * r.lambda_assoc
    return ratio if closed else math.nan


_GCA = "Gilbert, Casapulla & Ahmed 2006"
_GCA_WHERE = "figure of t against mu (read off)"
_GCA_ARCH = f"{GCA_VOUSSOIRS} radial voussoirs"
_GCA_READ = ("tolerance: the reading; read off the figure (centreline radius 10 assumed: Heyman's mode I at 1.072 gives "
             "t/R 0.1072) to +-1 px: +-0.0011 in t/R")

NONASSOC_CASES: tuple[ValidationCase, ...] = (
    *(
        ValidationCase(
            f"gca_eta_{key}", _GCA, _GCA_WHERE, f"least t/R, 27 blocks, mu {mu} ({mode}), non-associative", read,
            partial(nonassoc_min_ratio, mu), f"{_GCA_ARCH}, mu = {mu}", 1.1e-3, f"{_GCA_READ}; tce {note}",
        )
        for key, mu, mode, read, note in (
            ("mode1", 0.8, "mode I", 0.1072, "0.106721 (associative and non-associative alike: six hinges, nothing slides)"),
            ("0375", 0.375, "mode II", 0.1265, "0.125966; the sliding joints of mode II are statically determinate, "
             "so the bracket is closed and the non-associative least thickness is the associative one"),
            ("035", 0.35, "mode II", 0.1517, "0.151185, bracket closed"),
            ("0325", 0.325, "mode II", 0.1785, "0.178207, bracket closed"),
            ("0311", 0.3109, "their least mu", 0.1954, "0.194868, bracket closed (mu of the leftmost point +-0.0007: "
             "t/R moves by 0.0015 per 0.001 of mu there)"),
        )
    ),
    ValidationCase(
        "gca_mu_rm", _GCA, _GCA_WHERE, "friction below which sliding joins the hinges (mode I / II), 27 blocks",
        0.3958, lambda: friction_bound(min_ratio(GCA_VOUSSOIRS) * (1 + 1e-5), n=GCA_VOUSSOIRS, lo=0.3, hi=0.5),
        _GCA_ARCH, 7e-4,
        "read off the vertical line between modes I and II (+-0.0007, the tolerance); tce 0.395275 at 27 voussoirs "
        "(CR2020: 0.395832 with the weights on the centreline)",
    ),
)

#: the figure's vertical line between modes II and III, read off (+-0.0007): it stands at their
#: leftmost computed point (mu 0.3109, t/R 0.1954: the case gca_eta_0311), not at a least friction,
#: so it is drawn beside tce's (docs/make_validation_figures.py) and not compared
GCA_MODE_III_LINE = 0.3108

CASES = CASES + NONASSOC_CASES

# ------------------------------------------------------------------- walls on a tilting table
_LACT3 = "LACT3 v1.0 (code, 2025)"

WALL_CASES: tuple[ValidationCase, ...] = (
    ValidationCase(
        "lact3_wall_tilt", _LACT3, "LACT3_SolverTest.m (its test; no paper read)",
        "collapse tilt (deg), its sample wall with a door and a window, phi 26 deg, c = 0, associative", 16.73,
        lambda: tilt_angle(lact3_wall(), 26.0), "the sample wall: 182 blocks on a slab, table tilted towards +x", 0.015,
        "a code's own test value, not a publication's: LACT3 steps the tilt up, halving the step below its "
        "converging tolerance (0.01 deg), reports the last tilt at which the wall still carries load, printed "
        "to 0.01 deg; the collapse tilt is within 0.015 deg of the printed one. tce 16.7376 (lambda = tan theta); "
        "towards -x the same wall fails at 10.63 deg",
    ),
)

CASES = CASES + WALL_CASES

# ------------------------------------------------------- the arch on a tilting table (LACT3's arch_1)
#: LACT3's sample arch (Hua, Buzzetti, Pingaro, da Silva & Milani, ``sample/arch_1.dxf``, mm there):
#: a semicircle of 27 radial voussoirs of 20/3 deg, intrados radius 317 mm, extrados 373.3 mm,
#: whose lowest voussoir on each side is part of the base, so that 25 voussoirs stand on two
#: skewbacks inclined at pi/27 above the springing line; friction angle 30 deg, no cohesion.
TILT_RADII = (0.317, 0.3733)
TILT_VOUSSOIRS = 25
TILT_FRICTION_ANGLE = 30.0


def tilting_arch(voussoirs: int = TILT_VOUSSOIRS, depth: float = 0.1) -> Assembly:
    """LACT3's arch_1 (m): the circular ring of :data:`TILT_RADII` between skewbacks at
    ``pi/27`` above the springing line (embrace ``25 pi/27``), cut into ``voussoirs`` equal
    radial voussoirs (25 in the source), as :func:`tce.structures.arch.segmental_arch`:
    intrados span ``2 ri cos(pi/27)``, rise ``ri (1 - sin(pi/27))``, thickness ``re - ri``."""
    ri, re = TILT_RADII
    start = math.pi / 27.0
    return segmental_arch(2.0 * ri * math.cos(start), ri * (1.0 - math.sin(start)), re - ri, depth, voussoirs,
                          UNIT_WEIGHT)


TILTING_CASES: tuple[ValidationCase, ...] = (
    ValidationCase(
        "lact3_arch_tilt", _LACT3, "LACT3_SolverTest.m (its test; no paper read)",
        "collapse tilt (deg) of its sample arch, 25 voussoirs, phi 30 deg, c = 0, associative", 17.10,
        lambda: tilt_angle(tilting_arch(), TILT_FRICTION_ANGLE),
        f"their arch: {TILT_VOUSSOIRS} radial voussoirs, mu = tan 30 deg", 0.02,
        "a code's own test value, not a publication's: LACT3 prints, to 0.01 deg, the last tilt at "
        "which the arch stands, found by halving a 1 deg step until it is below 0.01 deg (LACT3.m's "
        "defaults): at most 0.016 deg below the collapse, and 0.005 of rounding; tce 17.1057 = "
        "atan(0.3077487), which the LP of the same voussoirs (tests/reference/lateral_arch.py) gives "
        "to 1e-11; four hinges, no joint slides, so the friction angle does not enter",
        digits=2,
    ),
)

CASES = CASES + TILTING_CASES

COLUMNS = ["case", "source", "where", "quantity", "published", "reference", "rounded", "rounds", "tce", "difference",
           "tolerance", "ok", "discretisation", "time_s"]


def run_validation(cases: Sequence[ValidationCase] = CASES, select: str | None = None) -> pd.DataFrame:
    """One row per case (or those whose name contains ``select``), columns :data:`COLUMNS`:
    ``reference`` is what tce's value is compared with (:attr:`ValidationCase.expected`),
    ``rounded`` that value at the printed digits and ``rounds`` whether it equals the
    published value there; ``difference`` is ``tce - reference``; ``ok`` whether
    ``|difference| <= tolerance`` and ``rounds`` is what the case states (a NaN is never ok)."""
    rows = []
    for case in cases:
        if select and select.lower() not in case.name.lower():
            continue
        t0 = time.perf_counter()
        value = float(case.compute())
        diff = value - case.expected
        rounded = case.at_printed_digits()
        rounds = math.isclose(rounded, case.published, rel_tol=0.0, abs_tol=1e-12 * max(1.0, abs(case.published)))
        rows.append(dict(case=case.name, source=case.source, where=case.where, quantity=case.quantity,
                         published=case.published, reference=case.expected, rounded=rounded, rounds=rounds,
                         tce=value, difference=diff, tolerance=case.tolerance,
                         ok=bool(abs(diff) <= case.tolerance and rounds == case.rounds),
                         discretisation=case.discretisation, time_s=time.perf_counter() - t0))
    return pd.DataFrame(rows, columns=COLUMNS)


def format_validation(table: pd.DataFrame) -> str:
    """The table as plain text (values to 7 significant digits; ``rounds``: whether the
    reference rounds to the published value at its printed digits)."""
    cols = ["case", "source", "where", "published", "reference", "rounds", "tce", "difference", "tolerance", "ok",
            "time_s"]
    return table[cols].to_string(
        index=False, justify="left",
        formatters={"published": "{:.6g}".format, "reference": "{:.7g}".format, "tce": "{:.7g}".format,
                    "difference": "{:+.1e}".format, "tolerance": "{:.1e}".format, "time_s": "{:.1f}".format},
    )
