"""Defects an inspection finds, applied to an assembly: missing blocks, other unit weights,
joints that carry nothing, joints that lost part of their depth, joints of another kind.

Each function returns a new assembly (the one given is left as it is) and names what it
cannot find. Blocks are named as in the assembly; a joint as ``"A|B"``, the names of its two
blocks (either order). Lengths in m, unit weights in kN/m^3.

- :func:`without_blocks`: blocks that are missing (with every interface they had);
- :func:`with_unit_weights`: blocks of another unit weight (a lighter or decayed unit);
- :func:`without_joints`: joints that carry no force at all (rings already separated over a
  stretch of the arch, an open joint through its whole depth);
- :func:`with_joint_loss`: joints that lost their contact over part of their depth: mortar lost
  (or an open crack) to a depth from either side. The depth is measured along the joint's
  contact polygon from its first edge's start towards its end, which for the joints of tce's
  arch and bridge generators runs from the intrados to the extrados (:mod:`tce.structures.arch`);
- :func:`with_kinds`: joints of another kind, which a material may give its own contact law
  (:attr:`tce.core.material.Material.interfaces`): a weaker mortar, a joint with a
  compressive strength of its own.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import replace

import numpy as np
import shapely

from .assembly import Assembly, AssemblyError

__all__ = ["with_joint_loss", "with_kinds", "with_unit_weights", "without_blocks", "without_joints"]


def _blocks(assembly: Assembly, names: Iterable[str]) -> set[int]:
    names = list(names)
    unknown = [n for n in names if n not in assembly.index]
    if unknown:
        raise AssemblyError(f"unknown block(s) {unknown}")
    return {assembly.index[n] for n in names}


def _joints(assembly: Assembly, joints: Iterable[str]) -> dict[int, str]:
    """Interface index of every joint ``"A|B"`` (either order) -> its name as given."""
    where = {}
    for k, i in enumerate(assembly.interfaces):
        a, b = assembly.names[i.a], assembly.names[i.b]
        where.setdefault(f"{a}|{b}", []).append(k)
        where.setdefault(f"{b}|{a}", []).append(k)
    out: dict[int, str] = {}
    for name in joints:
        if name not in where:
            raise AssemblyError(f"no joint {name!r}: name it 'A|B' by the names of its two blocks")
        out.update((k, name) for k in where[name])
    return out


def without_blocks(assembly: Assembly, names: Iterable[str]) -> Assembly:
    """``assembly`` without the blocks ``names`` and the interfaces they had."""
    gone = _blocks(assembly, names)
    keep = [k for k in range(len(assembly.blocks)) if k not in gone]
    new = {old: j for j, old in enumerate(keep)}
    interfaces = tuple(replace(i, a=new[i.a], b=new[i.b]) for i in assembly.interfaces if i.a in new and i.b in new)
    return Assembly(tuple(assembly.blocks[k] for k in keep), interfaces, dict(assembly.meta))


def with_unit_weights(assembly: Assembly, unit_weights: Mapping[str, float]) -> Assembly:
    """``assembly`` with the unit weights ``unit_weights`` (kN/m^3, > 0) of the named blocks."""
    _blocks(assembly, unit_weights)
    blocks = tuple(replace(b, unit_weight=float(unit_weights[b.name])) if b.name in unit_weights else b
                   for b in assembly.blocks)
    return replace(assembly, blocks=blocks)


def without_joints(assembly: Assembly, joints: Iterable[str]) -> Assembly:
    """``assembly`` without the interfaces of the joints ``joints`` (``"A|B"``): they carry nothing."""
    gone = _joints(assembly, joints)
    return replace(assembly, interfaces=tuple(i for k, i in enumerate(assembly.interfaces) if k not in gone))


def with_kinds(assembly: Assembly, kinds: Mapping[str, str]) -> Assembly:
    """``assembly`` with the joints of ``kinds`` (``"A|B"`` -> kind) of those kinds."""
    found = _joints(assembly, kinds)
    return replace(assembly, interfaces=tuple(replace(i, kind=kinds[found[k]]) if k in found else i
                                              for k, i in enumerate(assembly.interfaces)))


def with_joint_loss(assembly: Assembly, joint: str, intrados: float = 0.0, extrados: float = 0.0) -> Assembly:
    """``assembly`` with the joint ``joint`` (``"A|B"``) in contact only between the depths
    ``intrados`` and ``extrados`` (m, >= 0) from its two sides.

    The contact polygon keeps the part whose distance along its first edge's direction
    ``u`` (from its first vertex to its second: the intrados to the extrados for tce's arch
    generators) lies in ``[intrados, L - extrados]``, ``L`` the polygon's extent along ``u``.

    Raises
    ------
    AssemblyError
        An unknown joint, a negative depth, or depths that leave no contact.
    """
    if not (intrados >= 0 and extrados >= 0):
        raise AssemblyError(f"{joint}: the depths lost must be >= 0 m, got {intrados!r} and {extrados!r}")
    found = _joints(assembly, [joint])
    interfaces = list(assembly.interfaces)
    for k in found:
        itf = interfaces[k]
        p = itf.points
        u = p[1] - p[0]
        u = u - (u @ itf.normal) * itf.normal
        u /= np.linalg.norm(u)
        v = np.cross(itf.normal, u)
        s, t = (p - p[0]) @ u, (p - p[0]) @ v
        lo, hi = s.min() + intrados, s.max() - extrados
        if not hi > lo:
            raise AssemblyError(f"{joint}: losing {intrados:g} m and {extrados:g} m leaves no contact "
                                f"(the joint is {s.max() - s.min():.4g} m deep)")
        joint = shapely.Polygon(np.column_stack([s, t]))
        kept = joint.intersection(shapely.box(lo, t.min() - 1.0, hi, t.max() + 1.0))
        kept = shapely.geometry.polygon.orient(kept, 1.0 if joint.exterior.is_ccw else -1.0)
        ring = np.asarray(kept.exterior.coords)[:-1]
        interfaces[k] = replace(itf, points=p[0] + ring[:, :1] * u + ring[:, 1:] * v)
    return replace(assembly, interfaces=tuple(interfaces))
