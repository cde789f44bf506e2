"""Scenes of the battery: every structure type x material kind x load kind x settlement.

A :class:`Scene` is what one analysis needs (assembly, material, load pattern, support
motions); :func:`scene` builds one from the names drawn by hypothesis (or listed by a fixed
regression), with its loads placed on the structure it loads. :func:`answer` runs the
scene through tce (direct limit, load path, one TCE solve, the non-associative estimate for
a non-associative material) and keeps what the relations compare: outcomes, lambda_max,
statuses and support reactions.

Sizes are small on purpose (few voussoirs, two courses, six sectors): the relations do not
depend on the mesh, and the battery must stay within its budget (issue 21: 4 minutes on 2
cores).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cache
from pathlib import Path

import numpy as np

from tce.analysis.loadpath import load_path
from tce.analysis.nonassoc import nonassociative_limit
from tce.core.analysis import Analysis
from tce.core.loads import DistributedLoad, LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.arch import pointed_arch, segmental_arch, semicircular_arch, semicircular_arch_on_piers
from tce.structures.assembly import Assembly
from tce.structures.dome import hemispherical_dome
from tce.structures.io import load_assembly
from tce.structures.vault import barrel_vault, groin_vault

from .transform import Similarity

ROOT = Path(__file__).resolve().parents[2]
WALL = ROOT / "studies" / "data" / "wall.json"

#: every generator of tce.structures (the study types) and a block file, small
BUILDERS: dict[str, Callable[[], Assembly]] = {
    "semicircular_arch": lambda: semicircular_arch(voussoirs=8),
    "ring_arch": lambda: semicircular_arch(thickness=0.3, voussoirs=5, rings=2, stagger=True),
    "pointed_arch": lambda: pointed_arch(voussoirs=8),
    "segmental_arch": lambda: segmental_arch(voussoirs=6),
    "arch_on_piers": lambda: semicircular_arch_on_piers(voussoirs=8, pier_height=0.6),
    "barrel_vault": lambda: barrel_vault(voussoirs=6, courses=2, depth=0.5, bond="running"),
    "groin_vault": lambda: groin_vault(voussoirs=4),
    "dome": lambda: hemispherical_dome(radius=2.0, thickness=0.3, sectors=6, courses=3),
    "file": lambda: load_assembly(WALL, supports=["base"]),
}
STRUCTURES = tuple(BUILDERS)
#: the structures with a planar model (a vertical symmetry plane)
PLANAR = ("semicircular_arch", "ring_arch", "pointed_arch", "segmental_arch", "arch_on_piers", "file")

#: material kinds (issue 21): Heyman, friction, cohesion, strengths, compliant, non-associative
MATERIALS: dict[str, Material] = {
    "heyman": Material(),
    "friction": Material(friction=0.6),
    "cohesion": Material(friction=0.6, cohesion=2.0, tensile_strength=1.0),
    "strengths": Material(friction=0.8, compressive_strength=3000.0),
    "compliant": Material(friction=0.8, normal_stiffness=1e6, shear_stiffness=5e5),
    "non_associative": Material(friction=0.5, flow="non-associative"),
}

#: load kinds: the lateral pattern, or a live (scaled) or fixed point / on_top / distributed load;
#: ``lateral`` is left to its default (issue 37): the lateral pattern joins only the fixed loads
LOADS = ("lateral", "point", "on_top", "distributed", "point_fixed", "on_top_fixed", "distributed_fixed")

#: settlements of the last support: none, in the structure's plane (along x for every
#: structure of the suite), across it
SETTLEMENTS = {
    "none": None,
    "in_plane": [1e-3, 0.0, -5e-4, 0.0, 0.0, 0.0],
    "across": [0.0, 1e-3, 0.0, 2e-4, 0.0, 0.0],
}


@cache
def structure(name: str) -> Assembly:
    """The structure ``name``, built once (assemblies are immutable)."""
    return BUILDERS[name]().validate()


@dataclass(frozen=True)
class Scene:
    """One analysis: an assembly, a material, a load pattern and support motions (m, rad)."""

    assembly: Assembly
    material: Material
    pattern: LoadPattern
    settlements: dict[str, list[float]] = field(default_factory=dict)

    def mapped(self, t: Similarity) -> Scene:
        """The whole scene moved by ``t`` (geometry, loads, motions, material units)."""
        return Scene(t.assembly(self.assembly), t.material(self.material), t.pattern(self.pattern), t.settlements(self.settlements))


def _loaded_block(asm: Assembly) -> int:
    """A free block a third of the way along the free blocks (off any symmetry plane of the
    structure's span, so that a load on it is not symmetric)."""
    free = asm.free_indices
    return free[len(free) // 3]


def scene(structure_name: str, material: str, load: str, settlement: str, alpha: float = 0.0) -> Scene:
    """The scene of the names (module constants); ``alpha`` is the lateral direction (degrees)."""
    asm = structure(structure_name)
    w = asm.total_weight
    k = _loaded_block(asm)
    c = asm.centroids[k]
    scaled = not load.endswith("_fixed")
    kind = load.removesuffix("_fixed")
    # a live load of a tenth of the weight; a fixed one of a twentieth (the structure stands)
    f = (0.0, 0.0, -(0.1 if scaled else 0.05) * w)
    if kind == "lateral":
        pattern = LoadPattern(alpha=alpha)
    elif kind == "point":
        pattern = LoadPattern(alpha=alpha, point=[PointLoad(force=f, block=asm.names[k], scaled=scaled)])
    elif kind == "on_top":
        pattern = LoadPattern(alpha=alpha, point=[PointLoad(force=f, on_top=(c[0], c[1]), scaled=scaled)])
    elif kind == "distributed":
        free = list(asm.free_indices)
        hx = 0.125 * float(np.ptp(asm.centroids[free, 0]))
        # within the free blocks across (a wall on a wider slab: not over the slab)
        ys = np.concatenate([asm.blocks[i].shape.vertices[:, 1] for i in free])
        hy = min(hx, 0.45 * (ys.max() - ys.min()))
        pattern = LoadPattern(
            alpha=alpha,
            distributed=[DistributedLoad(x=(c[0] - hx, c[0] + hx), y=(c[1] - hy, c[1] + hy),
                                         pressure=-f[2] / (4 * hx * hy), scaled=scaled)],
        )
    else:
        raise ValueError(load)
    # lambda multiplies the live load alone, or the lateral pattern beside a fixed load
    assert kind == "lateral" or pattern.lateral is not scaled
    motion = SETTLEMENTS[settlement]
    sett = {} if motion is None else {asm.support_names[-1]: list(motion)}
    return Scene(asm, MATERIALS[material], pattern, sett)


@dataclass(frozen=True)
class Answer:
    """What tce says about a scene.

    Attributes
    ----------
    outcome, lambda_max : str, float
        The load path's outcome and lambda_max.
    direct_status, lambda_direct : str, float
        The direct limit analysis.
    lam, status : float, str
        The multiplier of the TCE solve and its status.
    reactions : dict
        Support name -> wrench ``(F, M)`` about the support's centroid (kN, kN m); NaN
        unless the solve is optimal.
    about : (3,) ndarray
        The point the total reaction is taken about.
    total : (6,) ndarray
        Sum of the reactions, moments about ``about``.
    unique : bool or None
        The solve's ``unique``.
    nonassoc : tuple of (str, float), optional
        Status and lambda_nonassoc of the non-associative estimate.
    weight : float
        Total weight of the free blocks (kN), the scale of the reactions.
    size : float
        Size of the assembly (m), the scale of the moments.
    model : str
        The model of the TCE solve (``planar``, ``spatial``).
    interfaces : dict
        ``(block A, block B)`` -> pressure point (m) and resultant on B (kN) of each
        interface of the model at ``lam`` (NaN unless optimal).
    """

    outcome: str
    lambda_max: float
    direct_status: str
    lambda_direct: float
    lam: float
    status: str
    reactions: dict[str, np.ndarray]
    about: np.ndarray
    total: np.ndarray
    unique: bool | None
    nonassoc: tuple[str, float] | None
    weight: float
    size: float
    interfaces: dict[tuple[str, str], tuple[np.ndarray, np.ndarray]]
    model: str


def path_settings(lambda_direct: float) -> tuple[float, float]:
    """Load step and cap for a scene whose direct limit is ``lambda_direct``: four
    increments to the limit (the relations need the same settings on both sides, not the
    defaults, which are tuned to the lateral pattern)."""
    if math.isfinite(lambda_direct) and lambda_direct > 0:
        return lambda_direct / 4.0 * (1 + 1e-3), 2.0 * lambda_direct
    return 0.05, 1.0


def answer(sc: Scene, lam: float | None = None, step: tuple[float, float] | None = None,
           model: str = "auto", about: np.ndarray | None = None) -> Answer:
    """Run ``sc`` through tce. ``lam`` (default: half the direct limit) is the multiplier of
    the TCE solve; ``step`` the load path's (step, cap) (default :func:`path_settings`);
    ``about`` the point of the total reaction (default: the origin)."""
    an = Analysis(sc.assembly, sc.material, model=model)  # type: ignore[arg-type]
    lim = an.limit(loads=sc.pattern)
    if lam is None:
        lam = 0.5 * lim.lambda_max if lim.ok and math.isfinite(lim.lambda_max) and lim.lambda_max > 0 else 0.0
    step_, cap = step or path_settings(lim.lambda_max if lim.ok else math.nan)
    lp = load_path(an, settlements=sc.settlements, step=step_, lam_cap=cap, loads=sc.pattern)
    r = an.solve(lam, settlements=sc.settlements, loads=sc.pattern)
    names = sc.assembly.support_names
    wrenches = np.asarray(r.support_wrenches, dtype=float).reshape(len(names), 6)
    about = np.zeros(3) if about is None else np.asarray(about, dtype=float)
    cent = sc.assembly.centroids[list(sc.assembly.support_indices)]
    total = np.concatenate([wrenches[:, :3].sum(0), (wrenches[:, 3:] + np.cross(cent - about, wrenches[:, :3])).sum(0)])
    names_ = sc.assembly.names
    itf = [sc.assembly.interfaces[k] for k in r.interface_map.interfaces]
    interfaces = {(names_[i.a], names_[i.b]): (p, f) for i, p, f in zip(itf, r.pressure_points, r.resultants, strict=True)}
    nonassoc = None
    if sc.material.flow == "non-associative":
        na = nonassociative_limit(an, loads=sc.pattern)
        nonassoc = (na.status, float(na.lambda_nonassoc))
    return Answer(
        outcome=lp.status, lambda_max=float(lp.lambda_max), direct_status=lim.status,
        lambda_direct=float(lim.lambda_max), lam=float(lam), status=r.status,
        reactions=dict(zip(names, wrenches, strict=True)), about=about, total=total,
        unique=r.unique, nonassoc=nonassoc, weight=sc.assembly.total_weight, size=sc.assembly.size,
        interfaces=interfaces, model=r.model,
    )


def with_pattern(sc: Scene, pattern: LoadPattern) -> Scene:
    """``sc`` under another load pattern."""
    return replace(sc, pattern=pattern)
