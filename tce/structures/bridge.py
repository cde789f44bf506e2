"""Arch bridges: segmental rings of several spans on piers between two abutments.

Axes as for arches (``docs/conventions.md``): the bridge spans along x and is centred on
x = 0, its width (``depth``) runs along y from ``-depth/2`` to ``+depth/2``, z is up, the
intrados springings at z = 0. Every span is the segmental ring of
:func:`tce.structures.arch.segmental_arch` (same span, rise, thickness and number of
voussoirs); its voussoirs are named ``s1v01``, ``s1v02``, ... for span 1 (from the left), or
with several rings (``rings``, ``stagger``: :func:`tce.structures.arch.ring_arch`) ``s1r1v01``,
... (span 1, ring 1 the intrados ring), the faces between rings of kind ``"ring"``.
A pier is the prism under the two springing joints it carries, ``pier_width`` wide between
the intrados springings, its base ``pier_height`` below the springings; an abutment is the
prism under its springing joint (a skewback), its base at the same level. The supports
(whose motion a settlement scenario may prescribe) are ``abutment_left``,
``abutment_right`` and, with ``piers = "free"`` (the default), a foundation block
``foundation1`` ... under each free pier ``pier1`` ... (a pier may rock or slide: the spans
act together); with ``piers = "fixed"`` the piers are the supports (the spans act alone).
"""

from __future__ import annotations

import numpy as np

from .arch import RingLayout, Rings, _at_depth, _joints, ring_fractions, segmental_arch
from .assembly import Assembly, Block, Interface
from .geometry import prism
from .params import check_blocks, check_choice, check_positive, check_whole

__all__ = ["arch_bridge"]


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
) -> Assembly:
    """A bridge of ``spans`` equal segmental spans on piers between two abutments.

    Parameters
    ----------
    spans : int
        Number of spans (>= 1).
    span, rise, thickness : float
        Clear span, intrados rise and ring thickness of every span (m);
        ``rise <= span / 2``.
    depth : float
        Width of the bridge along y (m).
    voussoirs : int
        Voussoirs per span (>= 1).
    unit_weight : float
        Unit weight of the masonry (kN/m^3).
    pier_width : float
        Clear distance between the intrados springings of two adjacent spans (m); at least
        the two skewbacks' horizontal extent, so that the pier's top is a plane between them.
    pier_height : float
        Height of piers and abutments below the springings (m).
    piers : {"free", "fixed"}
        Free piers on support foundations (as wide as the pier, ``pier_width`` tall, as deep
        as the bridge), or piers that are supports.
    rings : int or list of float
        Rings of every span: a number of equal rings (default 1), or their thicknesses from the
        intrados out (m), summing to ``thickness``.
    stagger : bool
        With several rings: the half-brick rule (True) or aligned joints (False, the default).

    Returns
    -------
    Assembly
        Blocks ``abutment_left, s1v01 .. s1vN, pier1, s2v01, ..., abutment_right`` (then
        ``foundation1, ...`` with free piers);
        ``meta["generator"] == "arch_bridge"``.

    Raises
    ------
    ValueError
        A non-positive size, ``rise > span / 2``, or piers narrower than their skewbacks.
    """
    check_positive(span=span, rise=rise, thickness=thickness, depth=depth, unit_weight=unit_weight,
                   pier_width=pier_width, pier_height=pier_height)
    n_spans = check_whole(spans, "spans")
    fractions = ring_fractions(rings, thickness)
    R = len(fractions) - 1
    check_blocks(n_spans * (R * (check_whole(voussoirs, "voussoirs") + int(R > 1)) + 2) + 1,
                 f"spans x (rings x (voussoirs{' + 1' if R > 1 else ''}) + 2) + 1 = {n_spans} x ({R} x "
                 f"({voussoirs}{' + 1' if R > 1 else ''}) + 2) + 1")
    check_choice(piers, "piers", ("free", "fixed"))
    ring = segmental_arch(span, rise, thickness, depth, voussoirs, unit_weight)
    n = ring.meta["voussoirs"]
    many = R > 1
    if many:  # the joints at every half voussoir, as the rings' layout takes them
        half = segmental_arch(span, rise, thickness, depth, 2 * n, unit_weight)
        jh = np.array([itf.points[0, [0, 2]] for itf in half.interfaces])
        eh = np.array([itf.points[1, [0, 2]] for itf in half.interfaces])
    # joint ends (x, z) of one ring, centred on x = 0, from its interfaces' front vertices
    ji = np.array([itf.points[0, [0, 2]] for itf in ring.interfaces])
    je = np.array([itf.points[1, [0, 2]] for itf in ring.interfaces])
    skew = float(je[-1, 0] - ji[-1, 0])  # horizontal extent of a skewback
    if n_spans > 1 and pier_width < 2.0 * skew * (1.0 - 1e-12):
        raise ValueError(f"pier_width must be >= {2.0 * skew:.6g} m (the two skewbacks it carries), got {pier_width!r}")
    pitch = float(span) + float(pier_width)
    centres = (np.arange(n_spans) - (n_spans - 1) / 2.0) * pitch
    d = float(depth) / 2.0
    base = -float(pier_height)

    loops, names, support = [], [], []

    def add(loop: np.ndarray, name: str, is_support: bool) -> None:
        loops.append(loop)
        names.append(name)
        support.append(is_support)

    def skewback(a: np.ndarray, e: np.ndarray) -> np.ndarray:
        """Section of the abutment under the joint from ``a`` (intrados) to ``e`` (extrados)."""
        return np.array([a, e, [e[0], base], [a[0], base]])

    width = len(str(n)) if n >= 10 else 2
    add(skewback(ji[0] + [centres[0], 0.0], je[0] + [centres[0], 0.0]), "abutment_left", True)
    joints = []  # (intrados, extrados) of every joint, left to right: joint k joins blocks k and k + 1
    laid = []  # with rings: (layout, first voussoir, the block on its left) of every span
    for s, cx in enumerate(centres):
        off = np.array([cx, 0.0])
        a, e = ji + off, je + off
        if many:
            layout = RingLayout(jh + off, eh + off, fractions, stagger)
            laid.append((layout, len(loops), len(loops) - 1))
            for loop, name in zip(layout.loops, layout.names):
                add(loop, f"s{s + 1}{name}", False)
        else:
            for k in range(n):
                add(np.array([a[k], a[k + 1], e[k + 1], e[k]]), f"s{s + 1}v{k + 1:0{width}d}", False)
            joints += zip(a, e)
        if s < n_spans - 1:
            nxt = ji + [centres[s + 1], 0.0], je + [centres[s + 1], 0.0]
            add(np.array([a[-1], e[-1], nxt[1][0], nxt[0][0], [nxt[0][0][0], base], [a[-1][0], base]]), f"pier{s + 1}",
                piers == "fixed")
    add(skewback(ji[-1] + [centres[-1], 0.0], je[-1] + [centres[-1], 0.0]), "abutment_right", True)

    feet = []  # (pier, foundation, x0, x1) of every free pier, its base from x0 to x1
    if piers == "free":
        for k, name in enumerate(list(names)):
            if name.startswith("pier"):
                x0, x1 = loops[k][0, 0], loops[k][3, 0]
                feet.append((k, len(names), x0, x1))
                add(np.array([[x0, base], [x1, base], [x1, base - pier_width], [x0, base - pier_width]]),
                    f"foundation{name[4:]}", True)
    shapes = [prism(_at_depth(loop, -d), _at_depth(loop, d)) for loop in loops]
    blocks = tuple(Block(name, shape, float(unit_weight), sup) for name, shape, sup in zip(names, shapes, support))
    centroids = np.array([shape.centroid for shape in shapes])
    if many:
        interfaces = []
        for layout, first, left in laid:
            right = first + len(layout.loops)  # the pier after the span, or the right abutment
            interfaces += layout.interfaces(first, left, right, centroids, d)
    else:
        interfaces = _joints(np.array([a for a, _ in joints]), np.array([e for _, e in joints]), d, centroids)
    for pier, foot, x0, x1 in feet:
        pts = np.array([[x0, -d, base], [x1, -d, base], [x1, d, base], [x0, d, base]])
        interfaces.append(Interface(pier, foot, pts, np.array([0.0, 0.0, -1.0])))
    meta = dict(generator="arch_bridge", spans=n_spans, span=float(span), rise=float(rise), thickness=float(thickness),
                depth=float(depth), voussoirs=n, unit_weight=float(unit_weight), pier_width=float(pier_width),
                pier_height=float(pier_height), piers=piers)
    if many:
        meta.update(rings=rings if isinstance(rings, int) else [float(v) for v in rings], stagger=bool(stagger))
    return Assembly(blocks, tuple(interfaces), meta)
