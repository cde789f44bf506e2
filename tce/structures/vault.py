"""Vault generators: the barrel vault and the groin (cross) vault.

Axes (as for the arch, ``docs/conventions.md``): z is up, the springings lie in the plane
z = 0, the origin is at the centre of the springing plane. Lengths in m, unit weights in
kN/m^3. Every block has exactly planar faces (chord intrados and extrados, plane joints);
each interface is the common face of its two blocks, built with them, its normal from
block A (the lower index) into block B.

Barrel vault (:func:`barrel_vault`)
    The semicircular arch of :func:`tce.structures.arch.semicircular_arch` (span along x)
    extruded along y over ``depth``, cut into ``courses`` rings of equal depth. In **stack
    bond** every course has the same radial joints, at equal angles; in **running bond** the
    odd courses (the 2nd, 4th, ...) are shifted by half a voussoir: they have a half voussoir
    at each springing and one voussoir more. Blocks ``c01v01 .. cCCvNN`` course by course from
    ``y = -depth/2``, voussoirs from the left springing (``x < 0``) to the right one.
    Interfaces: the radial joints within a course, the joints between neighbouring courses
    (the overlap of their sections in the plane between them) and the springing joints.

    Supports (``supports=``): ``"walls"`` (default) puts the vault on two support blocks
    ``left`` and ``right``, each the prism under its springing line over the whole depth (a
    wall settles as one body; the names are the arch's, so an arch study's settlements
    apply unchanged). ``"courses"`` gives every course its own pair ``left01, right01 ..
    leftCC, rightCC``, for settlements that vary along the vault.

Groin vault (:func:`groin_vault`)
    Two barrel vaults crossing over a rectangular bay of clear spans ``span_x`` and
    ``span_y``. The barrel spanning x has the semicircular section of intrados radius
    ``Ri = span_x / 2`` and thickness ``t``; the barrel spanning y has the same section
    stretched horizontally by ``k = span_y / span_x`` (semi-elliptical for a rectangular
    bay, with the same rise), so that the two intrados and the two extrados meet exactly
    in the vertical diagonal planes ``y = +-k x``: the groins. The plan of the vault,
    ``|x| <= Ro, |y| <= k Ro`` (``Ro = Ri + t``), is cut by the diagonals into four webs:
    north and south belong to the barrel spanning x, east and west to the one spanning y.
    Each web is an arch of ``voussoirs`` voussoirs (an even number, so that a crown joint
    lies in the web's mid-plane), strips from the groin to the face of the vault, cut along
    the diagonal planes; the two voussoirs that meet at a groin share a whole face there.
    Blocks ``n01 .. nNN``, ``w01 ..``, ``s01 ..``, ``e01 ..`` (north, west, south, east web),
    each web numbered from its left springing to its right one as seen from the centre of
    the bay. Interfaces: the radial joints within each web, the groin joints, and the
    springing joints (triangles, two at each corner: the springings of the two webs that
    meet there).

    Supports (``supports=``): ``"corners"`` (default) puts the vault on four corner piers
    ``ne, nw, sw, se``, each the prism under the corner square ``Ri <= |x| <= Ro``,
    ``k Ri <= |y| <= k Ro``. ``"springings"`` splits each corner pier along the diagonal
    into ``ne_n`` (under the north web), ``ne_e`` (under the east web), and so on (eight
    supports), so that the four springing lines can move apart.
"""

from __future__ import annotations

import numpy as np
import shapely
from numpy.typing import ArrayLike, NDArray
from shapely.geometry import Polygon

from .arch import _at_depth, _mirror_joints, semicircle_joints
from .assembly import Assembly, Block, Interface
from .geometry import Polyhedron, newell_normal, prism
from .params import check_blocks, check_choice, check_positive, check_whole

__all__ = ["barrel_vault", "groin_vault"]

BONDS = ("stack", "running")
BARREL_SUPPORTS = ("walls", "courses")
GROIN_SUPPORTS = ("corners", "springings")


def _solid(bottom: ArrayLike, top: ArrayLike) -> Polyhedron:
    """The prism between two loops (:func:`tce.structures.geometry.prism`), with the vertices
    the two loops share merged (a strip that ends in an edge gets no zero-length edge)."""
    poly = prism(bottom, top)
    v = poly.vertices
    tol = 1e-12 * max(poly.size, 1.0)
    index = np.arange(len(v))
    for i in range(len(v)):
        for j in range(i):
            if index[j] == j and np.linalg.norm(v[i] - v[j]) <= tol:
                index[i] = j
                break
    if np.all(index == np.arange(len(v))):
        return poly
    keep = np.unique(index)
    renum = {int(old): new for new, old in enumerate(keep)}
    faces = []
    for f in poly.faces:
        g = [renum[int(index[i])] for i in f]
        g = [x for k, x in enumerate(g) if x != g[k - 1]]  # drop repeated neighbours (cyclic)
        if len(set(g)) >= 3:
            faces.append(tuple(g))
    return Polyhedron(v[keep], faces)


class _Builder:
    """Blocks and interfaces of a generated assembly, with the interface convention applied."""

    def __init__(self, unit_weight: float) -> None:
        self.unit_weight = float(unit_weight)
        self.blocks: list[Block] = []
        self.index: dict[str, int] = {}
        self.interfaces: list[Interface] = []

    def block(self, name: str, shape: Polyhedron, support: bool = False) -> int:
        self.index[name] = len(self.blocks)
        self.blocks.append(Block(name, shape, self.unit_weight, support))
        return self.index[name]

    def joint(self, a: str, b: str, points: ArrayLike) -> None:
        """The interface between blocks ``a`` and ``b`` on the planar polygon ``points``:
        ordered so that A has the lower index, normal from A into B, vertices counter-clockwise
        about the normal."""
        ia, ib = sorted((self.index[a], self.index[b]))
        p = np.asarray(points, dtype=float)
        n = newell_normal(p)
        if n @ (self.blocks[ib].centroid - self.blocks[ia].centroid) < 0:
            p = p[::-1]
        self.interfaces.append(Interface(ia, ib, p))

    def assembly(self, meta: dict) -> Assembly:
        return Assembly(tuple(self.blocks), tuple(self.interfaces), meta)


def _section_overlap(p: NDArray[np.float64], q: NDArray[np.float64], min_area: float) -> NDArray[np.float64] | None:
    """Overlap of two convex sections ``(x, z)``, or None when its area is below ``min_area``."""
    inter = shapely.intersection(Polygon(p), Polygon(q))
    if not isinstance(inter, Polygon) or inter.area <= min_area:
        return None
    return np.asarray(inter.exterior.coords)[:-1]


def _course_angles(n: int, shifted: bool) -> NDArray[np.float64]:
    """Joint angles (rad, from the left springing ``pi`` to the right one ``0``) of a course
    of ``n`` voussoirs, or of ``n + 1`` with half voussoirs at the springings when ``shifted``."""
    if not shifted:
        return np.linspace(np.pi, 0.0, n + 1)
    step = np.pi / n
    return np.concatenate([[np.pi], np.pi - step / 2.0 - step * np.arange(n), [0.0]])


def barrel_vault(
    inner_radius: float = 1.0,
    thickness: float = 0.2,
    depth: float = 1.5,
    voussoirs: int = 12,
    courses: int = 6,
    bond: str = "stack",
    unit_weight: float = 20.0,
    support_height: float | None = None,
    supports: str = "walls",
) -> Assembly:
    """Semicircular barrel vault in courses of voussoirs on two walls (see module docstring).

    Parameters
    ----------
    inner_radius : float
        Intrados radius (m); the clear span is twice it.
    thickness : float
        Radial thickness (m).
    depth : float
        Length of the vault along y (m), split into ``courses`` equal courses.
    voussoirs : int
        Voussoirs per course (>= 1); a shifted course of the running bond has one more.
    courses : int
        Number of courses along y (>= 1).
    bond : {"stack", "running"}
        Joint pattern of neighbouring courses.
    unit_weight : float
        Unit weight (kN/m^3).
    support_height : float, optional
        Height of the support blocks below the springings (m); default: the thickness.
    supports : {"walls", "courses"}
        One support block per springing line (``left``, ``right``), or one per springing of
        each course (``left01, right01, ...``).

    Returns
    -------
    Assembly
        Supports first, then the voussoirs course by course; ``meta["generator"] ==
        "barrel_vault"`` with the parameters.

    Raises
    ------
    ValueError
        A parameter out of range, naming it.
    """
    check_positive(inner_radius=inner_radius, thickness=thickness, depth=depth, unit_weight=unit_weight)
    n = check_whole(voussoirs, "voussoirs")
    nc = check_whole(courses, "courses")
    check_blocks((n + 3) * nc, f"at most (voussoirs + 3) x courses = ({n} + 3) x {nc}")  # shifted courses and supports
    check_choice(bond, "bond", BONDS)
    check_choice(supports, "supports", BARREL_SUPPORTS)
    h = float(thickness) if support_height is None else support_height
    check_positive(support_height=h)
    ri, ro = float(inner_radius), float(inner_radius) + float(thickness)
    ys = np.linspace(-depth / 2.0, depth / 2.0, nc + 1)
    sections = []  # per course: list of voussoir sections (4, 2) in x-z
    for c in range(nc):
        ji, je = semicircle_joints(ri, ro, _course_angles(n, bond == "running" and c % 2 == 1))
        sections.append([np.array([ji[i], ji[i + 1], je[i + 1], je[i]]) for i in range(len(ji) - 1)])
    wc = max(2, len(str(nc)))
    wv = max(2, len(str(n + 1)))

    def name(c: int, i: int) -> str:
        return f"c{c + 1:0{wc}d}v{i + 1:0{wv}d}"

    def support(side: str, c: int) -> str:
        """The support block under the springing ``side`` of course ``c``."""
        return side if supports == "walls" else f"{side}{c + 1:0{wc}d}"

    out = _Builder(unit_weight)
    ends = {"left": (-ro, -ri), "right": (ri, ro)}
    spans = [(0, nc)] if supports == "walls" else [(c, c + 1) for c in range(nc)]
    for side, (x0, x1) in ends.items():
        for c0, c1 in spans:
            loop = np.array([[x0, 0.0], [x1, 0.0], [x1, -h], [x0, -h]])
            out.block(support(side, c0), prism(_at_depth(loop, ys[c0]), _at_depth(loop, ys[c1])), support=True)
    for c, secs in enumerate(sections):
        for i, q in enumerate(secs):
            out.block(name(c, i), prism(_at_depth(q, ys[c]), _at_depth(q, ys[c + 1])))

    def rectangle(a: NDArray[np.float64], b: NDArray[np.float64], c: int) -> NDArray[np.float64]:
        seg = np.array([a, b])
        return np.vstack([_at_depth(seg, ys[c]), _at_depth(seg[::-1], ys[c + 1])])

    for c, secs in enumerate(sections):
        m = len(secs)
        out.joint(support("left", c), name(c, 0), rectangle(secs[0][0], secs[0][3], c))
        for i in range(1, m):
            out.joint(name(c, i - 1), name(c, i), rectangle(secs[i][0], secs[i][3], c))
        out.joint(name(c, m - 1), support("right", c), rectangle(secs[m - 1][1], secs[m - 1][2], c))
    min_area = 1e-9 * (ro - ri) ** 2
    for c in range(nc - 1):
        for i, p in enumerate(sections[c]):
            for j, q in enumerate(sections[c + 1]):
                if bond == "stack":
                    overlap = p if i == j else None
                else:
                    overlap = _section_overlap(p, q, min_area)
                if overlap is not None:
                    out.joint(name(c, i), name(c + 1, j), _at_depth(overlap, ys[c + 1]))
    meta = dict(generator="barrel_vault", inner_radius=ri, thickness=float(thickness), depth=float(depth),
                voussoirs=n, courses=nc, bond=bond, unit_weight=float(unit_weight), support_height=float(h),
                supports=supports)
    return out.assembly(meta)


#: rotations of the plan by 0, 90, 180 and 270 degrees about z, and the web each gives
_WEBS = ("n", "w", "s", "e")
_CORNERS = ("ne", "nw", "sw", "se")


def _turn(points: ArrayLike, r: int, stretch: float) -> NDArray[np.float64]:
    """``points`` turned by ``r`` quarter turns about z (exact), then y scaled by ``stretch``."""
    p = np.array(points, dtype=float)
    for _ in range(r % 4):
        p[:, [0, 1]] = np.column_stack([-p[:, 1], p[:, 0]])
    p[:, 1] *= stretch
    return p


def groin_vault(
    span_x: float = 2.0,
    span_y: float | None = None,
    thickness: float = 0.2,
    voussoirs: int = 8,
    unit_weight: float = 20.0,
    support_height: float | None = None,
    supports: str = "corners",
) -> Assembly:
    """Groin (cross) vault over a rectangular bay on four corner piers (see module docstring).

    Parameters
    ----------
    span_x : float
        Clear span of the bay along x (m): the intrados of the barrel spanning x is a
        semicircle of radius ``span_x / 2``.
    span_y : float, optional
        Clear span along y (m); default ``span_x`` (a square bay).
    thickness : float
        Radial thickness of the barrel spanning x (m); the barrel spanning y is this section
        stretched horizontally by ``span_y / span_x``.
    voussoirs : int
        Voussoirs per web (an even number >= 2), at equal angles of the semicircle.
    unit_weight : float
        Unit weight (kN/m^3).
    support_height : float, optional
        Height of the support blocks below the springings (m); default: the thickness.
    supports : {"corners", "springings"}
        Four corner piers, or a support under each web's springing (eight).

    Returns
    -------
    Assembly
        Supports first, then the webs n, w, s, e; ``meta["generator"] == "groin_vault"``.

    Raises
    ------
    ValueError
        A parameter out of range, naming it.
    """
    span_y = span_x if span_y is None else span_y
    check_positive(span_x=span_x, span_y=span_y, thickness=thickness, unit_weight=unit_weight)
    n = check_whole(voussoirs, "voussoirs", 2)
    if n % 2:
        raise ValueError(f"voussoirs must be an even number (a crown joint in each web's mid-plane), got {voussoirs!r}")
    check_blocks(4 * n + 8, f"4 webs x voussoirs + up to 8 supports = 4 x {n} + 8")
    check_choice(supports, "supports", GROIN_SUPPORTS)
    h = float(thickness) if support_height is None else support_height
    check_positive(support_height=h)
    k = float(span_y) / float(span_x)
    ri = float(span_x) / 2.0
    ro = ri + float(thickness)
    ji, je = semicircle_joints(ri, ro, np.linspace(np.pi, 0.0, n + 1))
    # right half as the exact mirror of the left one, so that the groin faces of two webs match
    ji, je = _mirror_joints(ji[: n // 2 + 1], n), _mirror_joints(je[: n // 2 + 1], n)
    sections = [np.array([ji[i], ji[i + 1], je[i + 1], je[i]]) for i in range(n)]

    def on_groin(xz: NDArray[np.float64]) -> NDArray[np.float64]:
        """Section points of the north web carried to its groins: y = |x|."""
        return np.column_stack([xz[:, 0], np.abs(xz[:, 0]), xz[:, 1]])

    def at_face(xz: NDArray[np.float64]) -> NDArray[np.float64]:
        """Section points of the north web at the face of the vault: y = Ro."""
        return np.column_stack([xz[:, 0], np.full(len(xz), ro), xz[:, 1]])

    w = max(2, len(str(n)))
    out = _Builder(unit_weight)
    # corner regions, in the frame of the north web's east corner (r = 0: ne)
    upper = np.array([[ri, ri, 0.0], [ri, ro, 0.0], [ro, ro, 0.0]])  # under the north web
    lower = np.array([[ri, ri, 0.0], [ro, ro, 0.0], [ro, ri, 0.0]])  # under the east web
    square = np.array([[ri, ri, 0.0], [ro, ri, 0.0], [ro, ro, 0.0], [ri, ro, 0.0]])
    down = np.array([0.0, 0.0, -h])
    pier = {}  # (corner r, web) -> support block name
    for r, corner in enumerate(_CORNERS):
        east = _WEBS[(r + 3) % 4]  # the web clockwise of web r (east of north)
        if supports == "corners":
            top = _turn(square, r, k)
            out.block(corner, prism(top + down, top), support=True)
            pier[r, _WEBS[r]] = pier[r, east] = corner
        else:
            for part, web in ((upper, _WEBS[r]), (lower, east)):
                top = _turn(part, r, k)
                out.block(f"{corner}_{web}", prism(top + down, top), support=True)
                pier[r, web] = f"{corner}_{web}"

    def name(r: int, i: int) -> str:
        return f"{_WEBS[r]}{i + 1:0{w}d}"

    for r in range(4):
        for i, q in enumerate(sections):
            out.block(name(r, i), _solid(_turn(on_groin(q), r, k), _turn(at_face(q), r, k)))
    for r in range(4):
        for i in range(1, n):
            seg = np.array([ji[i], je[i]])
            out.joint(name(r, i - 1), name(r, i), _turn(np.vstack([on_groin(seg), at_face(seg[::-1])]), r, k))
        # groin east of web r: its voussoirs i >= n/2 against voussoirs n-1-i of the web east of it
        for i in range(n // 2, n):
            out.joint(name(r, i), name((r + 3) % 4, n - 1 - i), _turn(on_groin(sections[i]), r, k))
        # springings: the east one on corner r, the west one on corner r+1
        out.joint(pier[r, _WEBS[r]], name(r, n - 1), _turn(upper, r, k))
        out.joint(pier[(r + 1) % 4, _WEBS[r]], name(r, 0), _turn(lower, r + 1, k))
    meta = dict(generator="groin_vault", span_x=float(span_x), span_y=float(span_y), thickness=float(thickness),
                voussoirs=n, unit_weight=float(unit_weight), support_height=float(h), supports=supports,
                inner_radius=ri, rise=ri)
    return out.assembly(meta)
