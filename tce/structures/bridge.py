"""Arch bridges: segmental barrels of several spans on piers between two abutments, in one or
several rings through their thickness and in courses across their width, square or skew.

Axes as for arches (``docs/conventions.md``): the bridge spans along x (the road's axis) and
is centred on x = 0, its width (``depth``) runs along y from ``-depth/2`` to ``+depth/2``, z is
up, the intrados springings at z = 0 on the centreline y = 0.

The square bridge (``skew = 0``)
    Every span is the segmental ring of :func:`tce.structures.arch.segmental_arch` (same
    span, rise, thickness and number of voussoirs), or with several rings (``rings``,
    ``stagger``) the rings of :func:`tce.structures.arch.ring_arch` (the faces between rings
    of kind ``"ring"``), extruded across the width and cut into ``courses`` courses of equal
    width by vertical planes ``y = const`` (the course joints). In **stack bond** every course
    has the same radial joints; in **running bond** every other course (the 2nd, 4th, ...) is
    shifted by half a voussoir: it has a half voussoir at each springing and one voussoir more
    (the barrel vault's bond, :func:`tce.structures.vault.barrel_vault`; with one ring only).
    The voussoirs of span 1 (from the left) are named ``s1v01``, ``s1v02``, ...; with several
    rings ``s1r1v01`` (ring 1 the intrados ring); with several courses ``s1c01v01`` or
    ``s1c01r1v01`` (course from ``y = -depth/2``). A pier is the prism under the two springing
    joints it carries, ``pier_width`` wide between the intrados springings, its base
    ``pier_height`` below the springings; an abutment is the prism under its springing joint
    (a skewback), its base at the same level. Abutments, piers and pier foundations are each
    one block across the whole width (a wall settles as one body); every course has its own
    joint with them. The supports (whose motion a settlement scenario may prescribe) are
    ``abutment_left``, ``abutment_right`` and, with ``piers = "free"`` (the default), a
    foundation block ``foundation1`` ... under each free pier ``pier1`` ... (a pier may rock
    or slide: the spans act together); with ``piers = "fixed"`` the piers are the supports
    (the spans act alone).

The skew bridge (``skew = phi`` degrees)
    The square bridge sheared in plan, ``(x, y, z) -> (x + y tan(phi), y, z)``: the "false
    skew" (or oblique) barrel, whose bed joints, abutment and pier faces are parallel to each
    other, at ``phi`` from the y axis (the vertical planes ``x = x0 + y tan(phi)``), and whose
    course joints and faces stay parallel to the road's axis (planes ``y = const``). Every
    vertical section parallel to the road (``y = const``, a face of the bridge included) is
    the square bridge's section, so ``span`` is the skew span, measured along x; the square
    span, perpendicular to the abutments, is ``span cos(phi)``, and the ring's thickness
    normal to the bed joints is smaller than ``thickness`` in the same way. A shear keeps
    volumes, planes and contact polygons (the interfaces are the square bridge's, sheared,
    their normals those of the sheared planes). This is not the helicoidal ("English") skew
    arch, whose bed joints are spirals square to the faces.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from .arch import RingLayout, Rings, _at_depth, ring_fractions, segmental_arch
from .assembly import Assembly, Block, Interface
from .backing import Backing, with_backing
from .geometry import Polyhedron, prism
from .params import check_blocks, check_choice, check_positive, check_whole
from .vault import BONDS, _section_overlap

__all__ = ["MAX_SKEW", "arch_bridge"]

#: largest skew angle (degrees): bed joints 60 degrees off square, far beyond a false skew
#: arch's practice (the thrust along the road crosses them obliquely)
MAX_SKEW = 60.0


def _ring_joints(ring: Assembly, shifted: bool) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Intrados and extrados ends ``(x, z)`` of the joints of one ring of ``ring`` (the segmental
    arch, centred on x = 0), or of the ring shifted by half a voussoir (a half voussoir at each
    springing, one voussoir more) when ``shifted``."""
    ji = np.array([itf.points[0, [0, 2]] for itf in ring.interfaces])
    je = np.array([itf.points[1, [0, 2]] for itf in ring.interfaces])
    if not shifted:
        return ji, je
    zc = ring.meta["rise"] - ring.meta["radius"]  # the circle's centre (0, zc)
    ang = np.arctan2(je[:, 1] - ji[:, 1], je[:, 0] - ji[:, 0])  # radial joints: the direction from the centre
    mid = 0.5 * (ang[:-1] + ang[1:])
    r, t = ring.meta["radius"], ring.meta["thickness"]
    cs = np.column_stack([np.cos(mid), np.sin(mid)])
    return (np.vstack([ji[0], r * cs + [0.0, zc], ji[-1]]), np.vstack([je[0], (r + t) * cs + [0.0, zc], je[-1]]))


def arch_bridge(
    spans: int = 1,
    span: float = 6.0,
    rise: float = 1.5,
    thickness: float = 0.4,
    depth: float = 3.0,
    voussoirs: int = 12,
    unit_weight: float = 20.0,
    pier_width: float = 1.0,
    pier_height: float = 3.0,
    piers: str = "free",
    rings: Rings = 1,
    stagger: bool = False,
    courses: int = 1,
    bond: str = "stack",
    skew: float = 0.0,
    backing: Backing | None = None,
) -> Assembly:
    """A bridge of ``spans`` equal segmental spans on piers between two abutments (module docstring).

    Parameters
    ----------
    spans : int
        Number of spans (>= 1).
    span, rise, thickness : float
        Clear span (along x: the skew span), intrados rise and ring thickness of every span,
        in every vertical section parallel to x (m); ``rise <= span / 2``.
    depth : float
        Width of the bridge along y (m).
    voussoirs : int
        Voussoirs per span and course (>= 1); a shifted course of the running bond has one more.
    unit_weight : float
        Unit weight of the masonry (kN/m^3).
    pier_width : float
        Clear distance along x between the intrados springings of two adjacent spans (m); at
        least the two skewbacks' horizontal extent, so that the pier's top is a plane between them.
    pier_height : float
        Height of piers and abutments below the springings (m).
    piers : {"free", "fixed"}
        Free piers on support foundations (as wide as the pier, ``pier_width`` tall, as wide
        as the bridge), or piers that are supports.
    rings : int or list of float
        Rings of every span: a number of equal rings (default 1), or their thicknesses from the
        intrados out (m), summing to ``thickness``.
    stagger : bool
        With several rings: the half-brick rule (True) or aligned joints (False, the default).
    courses : int
        Voussoir courses across the width (>= 1); 1: one block across.
    bond : {"stack", "running"}
        Joint pattern of neighbouring courses; ``"running"`` with one ring only.
    skew : float
        Skew angle (degrees, ``|skew| <= MAX_SKEW``): the angle of the abutment faces and bed
        joints from the y axis, positive from +y towards +x; 0: a square bridge.
    backing : Backing, optional
        Backing behind the haunches of every span up to a height above the springings, as
        blocks (over a pier one block on its top, between the two spans) or as a heavier
        fill (:mod:`tce.structures.backing`); with one course and no skew.

    Returns
    -------
    Assembly
        Blocks ``abutment_left``, the voussoirs of span 1 (course by course), ``pier1``, the
        voussoirs of span 2, ..., ``abutment_right``, then ``foundation1, ...`` with free
        piers; interfaces: span by span, course by course the joints from the left support to
        the right one (with rings: those of :meth:`tce.structures.arch.RingLayout.interfaces`),
        then the course joints between neighbouring courses, then the pier foundations;
        ``meta["generator"] == "arch_bridge"`` with the parameters.

    Raises
    ------
    ValueError
        A non-positive size, ``rise > span / 2``, piers narrower than their skewbacks, ring
        thicknesses that do not sum to the thickness, a running bond with several rings, a
        skew beyond :data:`MAX_SKEW`, or backing with several courses or a skew.
    """
    check_positive(span=span, rise=rise, thickness=thickness, depth=depth, unit_weight=unit_weight,
                   pier_width=pier_width, pier_height=pier_height)
    n_spans = check_whole(spans, "spans")
    n = check_whole(voussoirs, "voussoirs")
    nc = check_whole(courses, "courses")
    fractions = ring_fractions(rings, thickness)
    n_rings = len(fractions) - 1
    check_blocks(n_spans * (nc * n_rings * (n + 1) + 2) + 1,
                 f"at most spans x (courses x rings x (voussoirs + 1) + 2) + 1 = {n_spans} x ({nc} x {n_rings} x "
                 f"({n} + 1) + 2) + 1")
    check_choice(piers, "piers", ("free", "fixed"))
    check_choice(bond, "bond", BONDS)
    if n_rings > 1 and bond == "running" and nc > 1:
        raise ValueError("bond = 'running' across the width is built with one ring only; fix: bond = 'stack' or rings = 1")
    if not (math.isfinite(float(skew)) and abs(float(skew)) <= MAX_SKEW):
        raise ValueError(f"skew must be a number of degrees from {-MAX_SKEW:g} to {MAX_SKEW:g}, got {skew!r}")
    if backing is not None and (nc > 1 or float(skew) != 0.0):
        raise ValueError("backing is built on a bridge of one course and no skew; fix: courses = 1 and skew = 0, or no "
                         "backing")
    ring = segmental_arch(span, rise, thickness, depth, n, unit_weight)
    sections = [_ring_joints(ring, bond == "running" and c % 2 == 1) for c in range(nc)]
    if n_rings > 1:  # the joints at every half voussoir, as the rings' layout takes them
        jh, eh = _ring_joints(segmental_arch(span, rise, thickness, depth, 2 * n, unit_weight), False)
    ji, je = sections[0]
    reach = float(je[-1, 0] - ji[-1, 0])  # horizontal extent of a skewback
    if n_spans > 1 and pier_width < 2.0 * reach * (1.0 - 1e-12):
        raise ValueError(f"pier_width must be >= {2.0 * reach:.6g} m (the two skewbacks it carries), got {pier_width!r}")
    pitch = float(span) + float(pier_width)
    centres = (np.arange(n_spans) - (n_spans - 1) / 2.0) * pitch
    d = float(depth) / 2.0
    ys = np.linspace(-d, d, nc + 1)
    base = -float(pier_height)
    wv = max(2, len(str(len(sections[-1][0]) - 1)))
    wc = max(2, len(str(nc)))

    loops: list[NDArray[np.float64]] = []  # section (x, z) of every block
    extent: list[tuple[float, float]] = []  # its y range
    names: list[str] = []
    support: list[bool] = []

    def add(loop: NDArray[np.float64], name: str, is_support: bool, y0: float = -d, y1: float = d) -> int:
        loops.append(loop)
        extent.append((y0, y1))
        names.append(name)
        support.append(is_support)
        return len(names) - 1

    def skewback(a: NDArray[np.float64], e: NDArray[np.float64]) -> NDArray[np.float64]:
        """Section of the abutment under the joint from ``a`` (intrados) to ``e`` (extrados)."""
        return np.array([a, e, [e[0], base], [a[0], base]])

    def course(c: int) -> str:
        return f"c{c + 1:0{wc}d}" if nc > 1 else ""

    # bed joints of one ring (block a, block b, intrados end, extrados end, course), left to right
    beds: list[tuple[int, int, NDArray[np.float64], NDArray[np.float64], int]] = []
    laid: list[tuple[RingLayout, int, int, int, int]] = []  # with rings: (layout, first voussoir, left, right, course)
    joined: list[tuple[int, int, NDArray[np.float64], float]] = []  # course joints (a, b, section, y)
    min_area = 1e-9 * float(thickness) ** 2
    outer: list[tuple[NDArray[np.float64], list[int]]] = []  # per span: the extrados and the voussoirs under it
    pier_blocks: list[int] = []
    left = add(skewback(ji[0] + [centres[0], 0.0], je[0] + [centres[0], 0.0]), "abutment_left", True)
    for s, cx in enumerate(centres):
        off = np.array([cx, 0.0])
        course_blocks = []  # the voussoirs of every course
        for c, (ci, ce) in enumerate(sections):
            if n_rings > 1:
                layout = RingLayout(jh + off, eh + off, fractions, stagger)
                laid.append((layout, len(loops), left, -1, c))
                course_blocks.append([add(loop, f"s{s + 1}{course(c)}{name}", False, ys[c], ys[c + 1])
                                      for loop, name in zip(layout.loops, layout.names)])
            else:
                a, e = ci + off, ce + off
                course_blocks.append([add(np.array([a[k], a[k + 1], e[k + 1], e[k]]),
                                          f"s{s + 1}{course(c)}v{k + 1:0{wv}d}", False, ys[c], ys[c + 1])
                                      for k in range(len(a) - 1)])
        if n_rings > 1:  # the outer ring's voussoirs hold the extrados
            lay, top = laid[-1][0], laid[-1][0].first[-1]
            outer.append((lay.je[lay.joints[-1]], course_blocks[0][top:top + len(lay.joints[-1]) - 1]))
        else:
            outer.append((sections[0][1] + off, course_blocks[0]))
        right = len(names)  # the pier or abutment added next
        laid = [(lay, first, lft, right if r < 0 else r, c) for lay, first, lft, r, c in laid]
        if n_rings == 1:
            for c, (ci, ce) in enumerate(sections):
                chain = [left, *course_blocks[c], right]
                beds += [(chain[k], chain[k + 1], ci[k] + off, ce[k] + off, c) for k in range(len(ci))]
        for c in range(nc - 1):
            for i in course_blocks[c]:
                for j in course_blocks[c + 1]:
                    sec = _section_overlap(loops[i], loops[j], min_area) if bond == "running" else \
                        (loops[i] if i - course_blocks[c][0] == j - course_blocks[c + 1][0] else None)
                    if sec is not None:
                        joined.append((i, j, sec, ys[c + 1]))
        if s < n_spans - 1:
            a, e = ji + off, je + off
            na, ne = ji[0] + [centres[s + 1], 0.0], je[0] + [centres[s + 1], 0.0]
            left = add(np.array([a[-1], e[-1], ne, na, [na[0], base], [a[-1][0], base]]), f"pier{s + 1}",
                       piers == "fixed")
            pier_blocks.append(left)
    add(skewback(ji[-1] + [centres[-1], 0.0], je[-1] + [centres[-1], 0.0]), "abutment_right", True)

    feet = []  # (pier, foundation, x0, x1) of every free pier, its base from x0 to x1
    if piers == "free":
        for k, name in enumerate(list(names)):
            if name.startswith("pier"):
                x0, x1 = loops[k][0, 0], loops[k][3, 0]
                feet.append((k, len(names), x0, x1))
                add(np.array([[x0, base], [x1, base], [x1, base - pier_width], [x0, base - pier_width]]),
                    f"foundation{name[4:]}", True)

    shear = np.eye(3)
    shear[0, 1] = math.tan(math.radians(float(skew)))  # x -> x + y tan(skew)
    normals = np.linalg.inv(shear).T  # a plane's normal maps by the inverse transpose

    def sheared(points: NDArray[np.float64]) -> NDArray[np.float64]:
        return points @ shear.T

    square = [prism(_at_depth(loop, y0), _at_depth(loop, y1)) for loop, (y0, y1) in zip(loops, extent)]
    shapes = [Polyhedron(sheared(p.vertices), p.faces) for p in square]
    blocks = tuple(Block(name, shape, float(unit_weight), sup) for name, shape, sup in zip(names, shapes, support))
    centroids = np.array([shape.centroid for shape in shapes])

    def interface(a: int, b: int, points: NDArray[np.float64], normal: NDArray[np.float64], kind: str = "") -> Interface:
        """The interface on ``points`` (square bridge), its ``normal`` turned from block ``a`` into ``b``."""
        m = normals @ normal
        if m @ (centroids[b] - centroids[a]) < 0:
            m = -m
        return Interface(a, b, sheared(points), m, kind=kind)

    interfaces = []
    for a, b, i, e, c in beds:
        pts = np.array([_at_depth(i[None], ys[c])[0], _at_depth(e[None], ys[c])[0],
                        _at_depth(e[None], ys[c + 1])[0], _at_depth(i[None], ys[c + 1])[0]])
        t = e - i
        interfaces.append(interface(a, b, pts, np.array([t[1], 0.0, -t[0]])))
    if laid:
        square_centroids = np.array([p.centroid for p in square])
        for layout, first, lft, rgt, c in laid:
            # the layout's faces (segments (p, q) of the section across the whole width) moved
            # onto the course's width, their normal perpendicular to the segment as the layout's
            scale, mid = (ys[c + 1] - ys[c]) / (2.0 * d), (ys[c + 1] + ys[c]) / 2.0
            for itf in layout.interfaces(first, lft, rgt, square_centroids, d):
                pts = itf.points.copy()
                pts[:, 1] = mid + scale * pts[:, 1]
                t = pts[1, [0, 2]] - pts[0, [0, 2]]
                interfaces.append(interface(itf.a, itf.b, pts, np.array([t[1], 0.0, -t[0]]), itf.kind))
    interfaces += [interface(a, b, _at_depth(sec, y), np.array([0.0, 1.0, 0.0])) for a, b, sec, y in joined]
    for pier, foot, x0, x1 in feet:
        pts = np.array([[x0, -d, base], [x1, -d, base], [x1, d, base], [x0, d, base]])
        interfaces.append(interface(pier, foot, pts, np.array([0.0, 0.0, -1.0])))
    meta = dict(generator="arch_bridge", spans=n_spans, span=float(span), rise=float(rise), thickness=float(thickness),
                depth=float(depth), voussoirs=n, unit_weight=float(unit_weight), pier_width=float(pier_width),
                pier_height=float(pier_height), piers=piers, courses=nc, bond=bond, skew=float(skew))
    if n_rings > 1:
        meta.update(rings=rings if isinstance(rings, int) else [float(v) for v in rings], stagger=bool(stagger))
    asm = Assembly(blocks, tuple(interfaces), meta)
    if backing is None:
        return asm
    return with_backing(asm, [e for e, _ in outer], [v for _, v in outer], float(depth), backing, pier_blocks)
