"""Walls of the validation atlas: the LACT3 sample wall on a tilting table.

LACT3 (Limit Analysis Code for Tilting Table Tests, v1.0, released 6 February 2025 by Y. Hua,
M. Buzzetti, N. Pingaro, L. C. M. da Silva and G. Milani; public repository
``GabrieleMilani/LACT3_v1.0``) computes the tilt at which a 2D assemblage of rigid blocks
with associative Mohr-Coulomb joints collapses, by upper- and lower-bound linear programs.
Its automated solver test (``LACT3_SolverTest.m``, ``testwall``) checks that both bounds
vanish for its sample wall (``sample/wall.dxf``) at a tilt of 16.73 deg with a friction angle of
26 deg and no cohesion: the code's own value (the paper its README asks to cite, "A
computerized tool for the kinematic limit analysis of 2D masonry structures failing on a
tilting table", was not found).

:func:`lact3_wall` rebuilds that wall (its 182 blocks coincide with the file's). A table
tilted by ``theta`` loads every block with ``W sin(theta)`` along the table and
``W cos(theta)`` across it; without cohesion the problem is homogeneous in the loads, so the
wall collapses when tce's lateral multiplier ``lambda`` reaches ``tan(theta)``
(:func:`tilt_angle`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.analysis import Analysis
from ..core.material import Material
from ..structures.assembly import Assembly, Block
from ..structures.contacts import detect_interfaces
from ..structures.geometry import Polyhedron, prisms

__all__ = ["LACT3_DOOR", "LACT3_WINDOW", "lact3_wall", "tilt_angle", "tilted"]

#: the door of the LACT3 wall: x from 0.25 to 0.5 m, open in courses 1 to 24 (0 is the bottom course)
LACT3_DOOR = (0.25, 0.5, 1, 24)
#: the window: x from 0.875 to 1.375 m, open in courses 2 to 23; course 24 spans it with one lintel
LACT3_WINDOW = (0.875, 1.375, 2, 23)


def _course(c: int, length: float, unit: float, openings: tuple[tuple[float, float, int, int], ...],
            lintel: tuple[float, float] | None) -> list[tuple[float, float]]:
    """The x-intervals of course ``c`` of a running bond (even courses start with a whole unit,
    odd ones with a half), cut at the openings open in that course, with the units over
    ``lintel`` (x-interval) joined into one."""
    if c % 2 == 0:
        edges = np.arange(0.0, length + 1e-9, unit)
    else:
        edges = np.r_[0.0, np.arange(unit / 2, length, unit), length]
    out = []
    for x0, x1 in zip(edges[:-1], edges[1:]):
        cut = [(o0, o1) for o0, o1, c0, c1 in openings if c0 <= c <= c1 and x0 < o1 - 1e-9 and x1 > o0 + 1e-9]
        if not cut:
            out.append((float(x0), float(x1)))
            continue
        o0, o1 = cut[0]
        if x0 < o0 - 1e-9:
            out.append((float(x0), o0))
        if x1 > o1 + 1e-9:
            out.append((o1, float(x1)))
    if lintel is not None:
        over = [s for s in out if s[1] > lintel[0] + 1e-9 and s[0] < lintel[1] - 1e-9]
        out = sorted([s for s in out if s not in over] + [(over[0][0], over[-1][1])])
    return out


def lact3_wall(unit_weight: float = 25.0, depth: float = 1.0) -> Assembly:
    """The sample wall of LACT3 v1.0 (``sample/wall.dxf``), upright on a support slab.

    A wall 2.0 m long and 1.5 m high of 27 courses (1.5/27 m each) of 0.25 m units in running
    bond (half units at the ends of the odd courses), with a door 0.25 m wide next to its left
    end pier (:data:`LACT3_DOOR`) and a window 0.5 m wide (:data:`LACT3_WINDOW`) spanned by a
    0.75 m lintel in course 24; units are cut at the jambs. 182 blocks on a slab 2.5 m long.

    Parameters
    ----------
    unit_weight : float
        kN/m^3 (without cohesion the tilt angle does not depend on it).
    depth : float
        Thickness of the wall along y (m).

    Returns
    -------
    Assembly
        The slab (a support named ``"base"``) and the blocks, interfaces found from the geometry.
    """
    length, courses, height, unit = 2.0, 27, 1.5, 0.25
    h = height / courses
    lintel_course = LACT3_WINDOW[3] + 1
    rects = [(-0.25, length + 0.25, -0.15, 0.0)]
    for c in range(courses):
        lintel = LACT3_WINDOW[:2] if c == lintel_course else None
        rects += [(x0, x1, c * h, (c + 1) * h) for x0, x1 in _course(c, length, unit, (LACT3_DOOR, LACT3_WINDOW), lintel)]
    x0, x1, z0, z1 = np.array(rects).T
    zero = np.zeros_like(x0)
    loops = np.stack([np.stack([x0, zero, z0], 1), np.stack([x1, zero, z0], 1), np.stack([x1, zero, z1], 1),
                      np.stack([x0, zero, z1], 1)], axis=1)  # (n, 4, 3), the face at y = 0
    shift = np.array([0.0, depth, 0.0])
    solids = prisms(loops, loops + shift)
    blocks = tuple(Block("base" if k == 0 else f"b{k}", solid, unit_weight, k == 0) for k, solid in enumerate(solids))
    return Assembly(blocks, tuple(detect_interfaces(blocks)))


def tilted(assembly: Assembly, degrees: float) -> Assembly:
    """``assembly`` on a table tilted by ``degrees`` about the y axis (vertices, interface
    points and normals rotated), positive lowering the +x end so that gravity pulls towards
    +x along the table, as LACT3 tilts its table."""
    q = Rotation.from_euler("y", degrees, degrees=True).as_matrix()
    blocks = tuple(replace(b, shape=Polyhedron(b.shape.vertices @ q.T, b.shape.faces)) for b in assembly.blocks)
    faces = tuple(replace(f, points=np.asarray(f.points) @ q.T, normal=np.asarray(f.normal) @ q.T)
                  for f in assembly.interfaces)
    return Assembly(blocks, faces, assembly.meta)


def tilt_angle(assembly: Assembly, friction_angle: float, alpha: float = 0.0) -> float:
    """Collapse tilt (degrees) of ``assembly`` on a table tilted towards ``alpha`` (degrees
    in plan, tce's lateral direction), for joints of friction angle ``friction_angle``
    (degrees), no cohesion, associative flow: ``atan(lambda_max)``; NaN unless the limit
    problem ends ``optimal``."""
    r = Analysis(assembly, Material(friction=math.tan(math.radians(friction_angle)))).limit(alpha, mechanism=False)
    return math.degrees(math.atan(r.lambda_max)) if r.status == "optimal" else math.nan
