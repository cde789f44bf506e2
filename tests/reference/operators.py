"""Reference operators of a rigid-block assembly, built vertex by vertex from the definitions.

Conventions (``docs/conventions.md``): an interface between blocks A and B has its unit normal
``n`` from A into B and its frame ``(n, t1, t2)`` (:func:`reference.geometry.frame`); each of its
vertices carries a force ``(fn, ft1, ft2)`` in that frame, which acts with + on B and - on A.
Unknowns are ordered interface by interface (in the assembly's order, leaving out interfaces
between two supports, which carry none), vertex by vertex, component by component.

- Equilibrium of each free block (in block order), 6 rows ``(Fx, Fy, Fz, Mx, My, Mz)`` about
  its centroid: ``A_eq F + b_dead + lam * b_lateral(alpha) = 0``, where ``b_dead`` is the
  self-weight ``(0, 0, -W)`` and ``b_lateral(alpha)`` the horizontal load ``W (cos a, sin a, 0)``,
  both applied at the centroid (no moment about it).
- ``B_sup F`` stacks, support by support (in block order), the wrench the support exerts on
  the structure: the force of each contact on the structure and its moment about the
  support's centroid, global frame.
- Compliance: ``1 / (k s a)`` per component, ``k`` the normal stiffness for fn and the shear
  stiffness for ft1, ft2, ``s`` the interface's stiffness multiplier, ``a`` the vertex's
  tributary area.
- Contact law: the violation of a contact is ``max(0, -fn)`` without a friction limit and
  ``max(0, -fn, ||ft|| - mu fn)`` with friction coefficient ``mu``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import Blocks, frame, tributary_areas


@dataclass(frozen=True)
class Contact:
    """Raw data of one interface: block indices, vertices (m), unit normal from A into B, and
    stiffness multiplier."""

    a: int
    b: int
    points: np.ndarray
    normal: np.ndarray
    stiffness: float = 1.0


def contacts_of(assembly) -> list[Contact]:
    """The interfaces of a tce ``Assembly`` as raw data (its input, not its derived frames)."""
    return [Contact(i.a, i.b, np.array(i.points), np.array(i.normal), float(i.stiffness)) for i in assembly.interfaces]


def used(contacts: list[Contact], support) -> list[Contact]:
    """The interfaces that carry unknowns: all but those between two supports."""
    return [c for c in contacts if not (support[c.a] and support[c.b])]


def _cross(r, f) -> np.ndarray:
    return np.array([r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]])


@dataclass(frozen=True)
class Operators:
    """Reference operators (dense) of an assembly; shapes as in ``tce.core.model.Model``
    (spatial): ``A_eq (6 nf, 3 nv)``, ``B_sup (6 ns, 3 nv)``, ``b_dead (6 nf,)``,
    ``vertices (nv, 3)``, ``frames (nv, 3, 3)``, ``area (nv,)``, ``stiffness (nv,)``."""

    A_eq: np.ndarray
    B_sup: np.ndarray
    b_dead: np.ndarray
    weights: np.ndarray
    vertices: np.ndarray
    frames: np.ndarray
    area: np.ndarray
    stiffness: np.ndarray

    def b_lateral(self, alpha: float) -> np.ndarray:
        """Lateral load for lambda = 1 in direction ``alpha`` (degrees from +x towards +y)."""
        a = math.radians(alpha)
        out = np.zeros((len(self.weights), 6))
        for k, w in enumerate(self.weights):
            out[k, 0] = w * math.cos(a)
            out[k, 1] = w * math.sin(a)
        return out.ravel()

    def compliance(self, normal_stiffness: float, shear_stiffness: float) -> np.ndarray:
        """Diagonal of the compliance (m/kN) per unknown."""
        out = np.empty(3 * len(self.area))
        for v, (a, s) in enumerate(zip(self.area, self.stiffness)):
            out[3 * v] = 1.0 / (normal_stiffness * s * a)
            out[3 * v + 1] = out[3 * v + 2] = 1.0 / (shear_stiffness * s * a)
        return out


def build(blocks: Blocks, contacts: list[Contact]) -> Operators:
    """Reference operators of the blocks ``blocks`` joined by the interfaces ``contacts``."""
    support = blocks.support
    free = [k for k in range(len(support)) if not support[k]]
    sups = [k for k in range(len(support)) if support[k]]
    row_free = {k: 6 * i for i, k in enumerate(free)}
    row_sup = {k: 6 * i for i, k in enumerate(sups)}
    items = used(contacts, support)
    nv = sum(len(c.points) for c in items)
    A = np.zeros((6 * len(free), 3 * nv))
    B = np.zeros((6 * len(sups), 3 * nv))
    verts, frames, area, stiff = [], [], [], []
    col = 0
    for c in items:
        f = frame(c.normal)
        trib = tributary_areas(c.points, c.normal)
        for p, a in zip(c.points, trib):
            verts.append(p)
            frames.append(f)
            area.append(a)
            stiff.append(c.stiffness)
            for j in range(3):
                d = f[j]
                for block, sign in ((c.b, 1.0), (c.a, -1.0)):  # +f on B, -f on A
                    force = sign * d  # the force on this block
                    if block in row_free:
                        r = row_free[block]
                        A[r : r + 3, col] += force
                        A[r + 3 : r + 6, col] += _cross(p - blocks.centroid[block], force)
                    else:  # a support: it exerts the opposite force on the structure
                        r = row_sup[block]
                        B[r : r + 3, col] += -force
                        B[r + 3 : r + 6, col] += _cross(p - blocks.centroid[block], -force)
                col += 1
    w = blocks.weight[free]
    b_dead = np.zeros((len(free), 6))
    for k, wk in enumerate(w):
        b_dead[k, 2] = -wk
    return Operators(A, B, b_dead.ravel(), w, np.array(verts), np.array(frames), np.array(area), np.array(stiff))


def cone_violation(forces, friction: float | None) -> float:
    """Largest contact-law violation of ``forces`` ((nc, dim), fn first), in force units."""
    worst = 0.0
    for f in np.asarray(forces, dtype=float):
        fn = f[0]
        v = max(0.0, -fn)
        if friction is not None:
            v = max(v, math.sqrt(float(np.sum(f[1:] ** 2))) - friction * fn)
        worst = max(worst, v)
    return worst


def in_plane_rows(m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For a vertical plane of normal ``m`` (horizontal), the 3x6 maps of a block wrench to its
    in-plane part ``(e . F, z . F, m . M)`` with ``e = m x z``, and to its out-of-plane part
    ``(m . F, e . M, z . M)``."""
    e = _cross(m, np.array([0.0, 0.0, 1.0]))
    z = np.array([0.0, 0.0, 1.0])
    zero = np.zeros(3)
    inplane = np.array([np.r_[e, zero], np.r_[z, zero], np.r_[zero, m]])
    outplane = np.array([np.r_[m, zero], np.r_[zero, e], np.r_[zero, z]])
    return inplane, outplane


def semicircular_arch_contacts(inner_radius: float, thickness: float, depth: float, voussoirs: int) -> list[Contact]:
    """The joints of the chord-faced semicircular arch of :func:`reference.geometry.semicircular_arch`
    (blocks ``left, v01 .. vN, right``): joint ``k`` at angle ``pi (1 - k/N)`` joins block ``k`` to
    block ``k + 1``; its normal is the tangent of the circle towards decreasing angle."""
    ri, ro, d = inner_radius, inner_radius + thickness, depth / 2.0
    out = []
    for k in range(voussoirs + 1):
        a = math.pi * (1.0 - k / voussoirs)
        c, s = math.cos(a), math.sin(a)
        if k in (0, voussoirs):  # the springings lie exactly on z = 0
            c, s = (-1.0, 0.0) if k == 0 else (1.0, 0.0)
        pts = np.array([[ri * c, -d, ri * s], [ro * c, -d, ro * s], [ro * c, d, ro * s], [ri * c, d, ri * s]])
        out.append(Contact(k, k + 1, pts, np.array([s, 0.0, -c])))
    return out
