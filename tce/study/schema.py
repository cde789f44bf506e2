"""Study files: a TOML description of a structure, its material, its loads and its scenarios.

A study is validated as a whole before anything runs (:func:`load_study`, format in
``docs/studies.md``): the schema (pydantic, strict: unknown keys refused with a "did you
mean", no NaN or infinities, no booleans or quoted numbers for numbers), limits (the study
name is one plain path component; at most :data:`MAX_INCREMENTS` load increments and
:data:`MAX_BLOCKS` blocks), then each distinct structure is built once (kept for the run:
:meth:`Study.assembly`) and every scenario's support names are checked against it;
scenario names must be distinct. Every problem is a :class:`StudyError` naming the file,
the key and the fix.

A valid study expands (:meth:`Study.scenarios`) into the cartesian product of its
settlement cases, its lateral directions (``[loads] alpha``) and its ``[sweep]`` lists,
in that order, each expanded :class:`Scenario` carrying everything a worker needs. The
loads (``[loads]``, its ``[[loads.point]]`` and ``[[loads.distributed]]`` tables) are a
:class:`tce.core.loads.LoadPattern`; they are resolved against every structure before
anything runs, and ``[sweep] load_x`` moves every scaled ``on_top`` point load.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
import tomllib
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Union, get_args, get_origin

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    TypeAdapter,
    ValidationError,
    ValidationInfo,
    field_validator,
    model_validator,
)

from .. import __version__, display
from ..messages import describe, did_you_mean
from ..analysis.loadpath import MAX_INCREMENTS
from ..core.loads import LoadError, LoadPattern, resolve
from ..core.material import Material
from ..core.fill import DISPERSION_2_TO_1
from ..core.vehicles import STANDARD, standard_vehicle
from ..structures.arch import pointed_arch, segmental_arch, semicircular_arch, semicircular_arch_on_piers
from ..structures import defects as _defects
from ..structures.assembly import Assembly, AssemblyError
from ..structures.backing import BACKING, Backing
from ..structures.bridge import MAX_SKEW, arch_bridge
from ..structures.dome import hemispherical_dome
from ..structures.io import MAX_BLOCKS, InputLimitError, load_assembly
from ..structures.vault import barrel_vault, groin_vault
from . import guards
from .guards import StudyError
from .names import slug
from .sections import PlotsSection, _Strict
from .uncertainty import MAX_JOBS, UncertaintySection, capacity_kind, draw

__all__ = [
    "MAX_BLOCKS",
    "MAX_INCREMENTS",
    "STRUCTURE_TYPES",
    "Scenario",
    "Study",
    "StudyError",
    "build_material",
    "build_structure",
    "check_uncertainty",
    "load_study",
    "parse_study",
]

#: swept parameters that change the structure (the others change material or settlement)
GEOMETRY_SWEEPS = ("inner_radius", "thickness", "depth", "radius")
#: swept parameters of the material
MATERIAL_SWEEPS = ("friction", "cohesion", "tensile_strength", "compressive_strength")
#: between a scenario's name and its samples in the name of a job of samples (:meth:`Study.jobs`)
SAMPLES_SEPARATOR = " samples "
#: ends the name of a scenario's job of FORM and subset simulation (:meth:`Study.jobs`)
ESTIMATORS_SUFFIX = " form+subset"
#: names a file or folder may not take on some systems (Windows), with or without an extension
RESERVED_NAMES = frozenset(
    ["CON", "PRN", "AUX", "NUL"] + [f"{p}{k}" for p in ("COM", "LPT") for k in range(1, 10)]
)


# Bounds of every quantity a study gives (SI: m, kN, kN/m^2, kN/m^3): beyond them a problem is
# meaningless for masonry or overflows the solver's arithmetic, and the value is refused naming its key.
#: lengths of a structure (m, > 0) and coordinates (within +-MAX_LENGTH): ten kilometres
MAX_LENGTH = 1e4
#: a force component or an axle load (kN)
MAX_FORCE = 1e6
#: cohesion, strengths and pressures (kN/m^2; 1e7 is ten times steel's yield stress)
MAX_STRESS = 1e7
#: unit weights (kN/m^3; steel's is 78.5)
MAX_UNIT_WEIGHT = 1e3
#: contact stiffnesses (kN/m^3): stiffer contacts are rigid to the last digit
MAX_STIFFNESS = 1e20
#: friction coefficient: beyond, no joint slides (leave friction out for Heyman's unlimited friction)
MAX_FRICTION = 100.0
#: dimensionless multipliers: load multipliers (lambda_step, lambda_cap, tolerance), settlement magnitudes
MAX_MULTIPLIER = 1e6
#: partial factors of [assessment]
MIN_FACTOR, MAX_FACTOR = 0.01, 100.0


def _within(limit: float) -> Any:
    """A number in [-limit, limit]."""
    return Annotated[float, Field(ge=-limit, le=limit)]


def _vector(n: int, limit: float) -> Any:
    """A list of ``n`` numbers in [-limit, limit]."""
    return Annotated[list[_within(limit)], Field(min_length=n, max_length=n)]


Length = Annotated[float, Field(gt=0, le=MAX_LENGTH)]
Depth = Annotated[float, Field(ge=0, le=MAX_LENGTH)]
Coordinate = _within(MAX_LENGTH)
UnitWeight = Annotated[float, Field(gt=0, le=MAX_UNIT_WEIGHT)]
Stress = Annotated[float, Field(ge=0, le=MAX_STRESS)]
Strength = Annotated[float, Field(gt=0, le=MAX_STRESS)]
Stiffness = Annotated[float, Field(gt=0, le=MAX_STIFFNESS)]
Friction = Annotated[float, Field(ge=0, le=MAX_FRICTION)]
Multiplier = Annotated[float, Field(gt=0, le=MAX_MULTIPLIER)]
Factor = Annotated[float, Field(ge=MIN_FACTOR, le=MAX_FACTOR)]
Angle = _within(360.0)
Vector6 = _vector(6, MAX_LENGTH)


class StudySection(_Strict):
    """``[study]``: the study's name (also its results folder), an optional description and the
    most solves the study may ask for (:func:`tce.study.guards.work`, stated before a run)."""

    name: str = Field(min_length=1, max_length=100, pattern=r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")
    description: str = ""
    max_solves: Annotated[int, Field(ge=1)] = guards.MAX_SOLVES

    @field_validator("name")
    @classmethod
    def _one_path_component(cls, v: str) -> str:
        # the pattern already excludes separators and a leading "." (so "." and "..")
        if v.endswith("."):
            raise ValueError(f"{v!r} ends with '.'; fix: end the name with a letter or digit")
        if v.split(".")[0].upper() in RESERVED_NAMES:
            raise ValueError(f"{v!r} is a reserved file name on some systems; fix: choose another name")
        return v


class _Generated(_Strict):
    """A ``[structure]`` section built by a generator of :mod:`tce.structures` (``builder``);
    every generator takes the unit weight (kN/m^3)."""

    builder: ClassVar[Callable[..., Assembly]]
    unit_weight: UnitWeight = 20.0

    def build(self) -> Assembly:
        """The assembly this section describes."""
        return type(self).builder(**self.model_dump(exclude={"type"}))


class BackingSection(_Strict):
    """``[structure] backing = { height, unit_weight, model }``: masonry or concrete behind the
    haunches up to ``height`` above the springing (m), as rigid blocks on the extrados or as a
    heavier fill (:class:`tce.structures.backing.Backing`)."""

    height: Depth
    unit_weight: UnitWeight = 20.0
    model: Literal["blocks", "fill"] = "blocks"


class _Backed(_Generated):
    """A generated arch that takes a ``backing``."""

    backing: BackingSection | None = None

    def build(self) -> Assembly:
        """The assembly this section describes, with its backing."""
        backing = None if self.backing is None else Backing(**self.backing.model_dump())
        return type(self).builder(**self.model_dump(exclude={"type", "backing"}), backing=backing)


class ArchStructure(_Backed):
    """``[structure] type = "semicircular_arch"``: :func:`tce.structures.arch.semicircular_arch`."""

    type: Literal["semicircular_arch"]
    inner_radius: Length = 1.0
    thickness: Length = 0.2
    depth: Length = 0.25
    voussoirs: Annotated[int, Field(ge=1, le=MAX_BLOCKS)] = 14
    support_height: Length | None = None
    joints: Literal["radial", "vertical"] = "radial"
    rings: Annotated[int, Field(ge=1, le=100)] | Annotated[list[Length], Field(min_length=1, max_length=100)] = 1
    stagger: bool = False

    builder = semicircular_arch


class PointedArchStructure(_Backed):
    """``[structure] type = "pointed_arch"``: :func:`tce.structures.arch.pointed_arch`."""

    type: Literal["pointed_arch"]
    span: Length = 2.0
    rise: Length | None = None
    centre_offset: Depth | None = None
    thickness: Length = 0.2
    depth: Length = 0.25
    voussoirs: Annotated[int, Field(ge=2)] = 14
    pier_height: Length | None = None
    rings: Annotated[int, Field(ge=1, le=100)] | Annotated[list[Length], Field(min_length=1, max_length=100)] = 1
    stagger: bool = False

    builder = pointed_arch


class SegmentalArchStructure(_Backed):
    """``[structure] type = "segmental_arch"``: :func:`tce.structures.arch.segmental_arch`."""

    type: Literal["segmental_arch"]
    span: Length = 2.0
    rise: Length = 0.5
    thickness: Length = 0.2
    depth: Length = 0.25
    voussoirs: Annotated[int, Field(ge=1)] = 12
    pier_height: Length | None = None
    rings: Annotated[int, Field(ge=1, le=100)] | Annotated[list[Length], Field(min_length=1, max_length=100)] = 1
    stagger: bool = False

    builder = segmental_arch


class ArchOnPiersStructure(_Backed):
    """``[structure] type = "arch_on_piers"``: :func:`tce.structures.arch.semicircular_arch_on_piers`."""

    type: Literal["arch_on_piers"]
    inner_radius: Length = 1.0
    thickness: Length = 0.2
    depth: Length = 0.25
    voussoirs: Annotated[int, Field(ge=1)] = 14
    pier_height: Length = 1.0
    rings: Annotated[int, Field(ge=1, le=100)] | Annotated[list[Length], Field(min_length=1, max_length=100)] = 1
    stagger: bool = False

    builder = semicircular_arch_on_piers


class ArchBridgeStructure(_Backed):
    """``[structure] type = "arch_bridge"``: :func:`tce.structures.bridge.arch_bridge`."""

    type: Literal["arch_bridge"]
    spans: Annotated[int, Field(ge=1)] = 1
    span: Length = 6.0
    rise: Length = 1.5
    thickness: Length = 0.4
    depth: Length = 3.0
    voussoirs: Annotated[int, Field(ge=1)] = 12
    pier_width: Length = 1.0
    pier_height: Length = 3.0
    piers: Literal["free", "fixed"] = "free"
    rings: Annotated[int, Field(ge=1, le=100)] | Annotated[list[Length], Field(min_length=1, max_length=100)] = 1
    stagger: bool = False
    courses: Annotated[int, Field(ge=1)] = 1
    bond: Literal["stack", "running"] = "stack"
    skew: Annotated[float, Field(ge=-MAX_SKEW, le=MAX_SKEW)] = 0.0

    builder = arch_bridge


class BarrelVaultStructure(_Generated):
    """``[structure] type = "barrel_vault"``: :func:`tce.structures.vault.barrel_vault`."""

    type: Literal["barrel_vault"]
    inner_radius: Length = 1.0
    thickness: Length = 0.2
    depth: Length = 1.5
    voussoirs: Annotated[int, Field(ge=1)] = 12
    courses: Annotated[int, Field(ge=1)] = 6
    bond: Literal["stack", "running"] = "stack"
    support_height: Length | None = None
    supports: Literal["walls", "courses"] = "walls"

    builder = barrel_vault


class GroinVaultStructure(_Generated):
    """``[structure] type = "groin_vault"``: :func:`tce.structures.vault.groin_vault`."""

    type: Literal["groin_vault"]
    span_x: Length = 2.0
    span_y: Length | None = None
    thickness: Length = 0.2
    voussoirs: Annotated[int, Field(ge=2, multiple_of=2)] = 8
    support_height: Length | None = None
    supports: Literal["corners", "springings"] = "corners"

    builder = groin_vault


class DomeStructure(_Generated):
    """``[structure] type = "dome"``: :func:`tce.structures.dome.hemispherical_dome`."""

    type: Literal["dome"]
    radius: Length = 5.0
    thickness: Length = 0.3
    sectors: Annotated[int, Field(ge=3)] = 16
    courses: Annotated[int, Field(ge=1)] = 8
    oculus: Annotated[float, Field(ge=0, lt=90)] = 0.0
    support_height: Length | None = None

    builder = hemispherical_dome


class FileStructure(_Strict):
    """``[structure] type = "file"``: blocks read by :func:`tce.structures.io.load_assembly`.

    ``path`` is relative to the study file (made absolute when the study is read);
    ``supports`` names the support blocks (default: the flags in the file).
    """

    type: Literal["file"]
    path: str = Field(min_length=1)
    supports: list[str] | None = None
    unit_weight: UnitWeight | None = None

    def build(self) -> Assembly:
        """The assembly this section describes."""
        return load_assembly(self.path, supports=self.supports, unit_weight=self.unit_weight)


_STRUCTURES = (
    ArchStructure,
    PointedArchStructure,
    SegmentalArchStructure,
    ArchOnPiersStructure,
    BarrelVaultStructure,
    GroinVaultStructure,
    DomeStructure,
    FileStructure,
    ArchBridgeStructure,
)
#: the ``[structure] type`` values, in the order docs/studies.md lists them
STRUCTURE_TYPES = tuple(get_args(cls.model_fields["type"].annotation)[0] for cls in _STRUCTURES)
#: ``[structure] type`` -> its section
_SECTIONS: dict[str, type[BaseModel]] = dict(zip(STRUCTURE_TYPES, _STRUCTURES, strict=True))
Structure = Annotated[Union[_STRUCTURES], Field(discriminator="type")]  # noqa: UP007 (a union of a tuple)


class MaterialSection(_Strict):
    """``[material]``: friction (absent: Heyman, unlimited), optional stiffnesses, cohesion,
    tensile and compressive strength (kN/m^2) and the flow rule (``docs/materials.md``)."""

    friction: Friction | None = None
    normal_stiffness: Stiffness | None = None
    shear_stiffness: Stiffness | None = None
    cohesion: Stress = 0.0
    tensile_strength: Stress = 0.0
    compressive_strength: Strength | None = None
    flow: Literal["associative", "non-associative"] = "associative"

    def build(self) -> Material:
        """The :class:`tce.core.material.Material` of this section."""
        return Material(**self.model_dump())


class RingInterfaceSection(_Strict):
    """``[ring_interface]``: the contact law of the faces between the rings of a multi-ring arch
    (interfaces of kind ``"ring"``, :mod:`tce.structures.arch`): friction, cohesion, tensile and
    compressive strength (kN/m^2), each ``[material]``'s when left out, or ``bonded = true``:
    rings that cannot separate (any tension and shear carried, ``Material(bonded=True)``)."""

    friction: Friction | None = None
    cohesion: Stress | None = None
    tensile_strength: Stress | None = None
    compressive_strength: Strength | None = None
    bonded: bool = False

    @model_validator(mode="after")
    def _bonded_alone(self) -> RingInterfaceSection:
        if self.bonded and self.model_dump(exclude_none=True, exclude={"bonded"}):
            raise ValueError("bonded rings carry any force; fix: leave friction, cohesion and strengths out, or set "
                             "bonded = false")
        return self


#: interface kind that ``[ring_interface]`` gives its law to
RING_KIND = "ring"


class BackingInterfaceSection(RingInterfaceSection):
    """``[backing_interface]``: the contact law of the faces of the backing blocks (with the
    extrados and with the abutments behind them; interfaces of kind ``"backing"``,
    :mod:`tce.structures.backing`): as ``[ring_interface]``, ``bonded = true`` for backing
    bonded to the extrados."""


class MortarLossSection(_Strict):
    """``[[defects.mortar_loss]]``: a joint (``"A|B"``) in contact only between the depths lost
    from its two sides (m; :func:`tce.structures.defects.with_joint_loss`): mortar lost, or a
    crack open, to that depth."""

    joint: str = Field(min_length=3)
    intrados: Annotated[float, Field(ge=0, le=MAX_LENGTH)] = 0.0
    extrados: Annotated[float, Field(ge=0, le=MAX_LENGTH)] = 0.0


class JointLawSection(_Strict):
    """``[[defects.joint_law]]``: the contact law of the joints ``joints`` (``"A|B"``): friction,
    cohesion, tensile and compressive strength (kN/m^2), each ``[material]``'s when left out."""

    joints: Annotated[list[Annotated[str, Field(min_length=3)]], Field(min_length=1)]
    friction: Friction | None = None
    cohesion: Stress | None = None
    tensile_strength: Stress | None = None
    compressive_strength: Strength | None = None


class DefectsSection(_Strict):
    """``[defects]``: what an inspection found (:mod:`tce.structures.defects`): blocks
    ``missing``, blocks of another ``unit_weight`` (kN/m^3), joints ``separated`` (they carry
    nothing: rings already apart there), joints that lost ``mortar_loss`` to a depth, and joints
    with a ``joint_law`` of their own."""

    missing: list[str] = Field(default_factory=list)
    unit_weight: dict[str, UnitWeight] = Field(default_factory=dict)
    separated: list[str] = Field(default_factory=list)
    mortar_loss: list[MortarLossSection] = Field(default_factory=list)
    joint_law: list[JointLawSection] = Field(default_factory=list)

    def apply(self, assembly: Assembly) -> Assembly:
        """``assembly`` with these defects: the joint laws' kinds (``joints1``, ``joints2``, ...),
        the depths lost, the joints separated, the unit weights, then the blocks missing."""
        asm = _defects.with_kinds(assembly, {j: joint_kind(k) for k, law in enumerate(self.joint_law)
                                             for j in law.joints})
        for loss in self.mortar_loss:
            asm = _defects.with_joint_loss(asm, loss.joint, loss.intrados, loss.extrados)
        asm = _defects.with_unit_weights(_defects.without_joints(asm, self.separated), self.unit_weight)
        return _defects.without_blocks(asm, self.missing)


def joint_kind(k: int) -> str:
    """Interface kind of the joints of the ``k``-th (0-based) ``[[defects.joint_law]]``."""
    return f"joints{k + 1}"


class PointLoadSection(_Strict):
    """``[[loads.point]]``: a force (kN) on a free block (``block``, ``at``) or on the top
    surface above a plan point (``on_top``); :class:`tce.core.loads.PointLoad`."""

    block: str | None = None
    at: _vector(3, MAX_LENGTH) | None = None
    on_top: _vector(2, MAX_LENGTH) | None = None
    force: _vector(3, MAX_FORCE)
    scaled: bool = True


class DistributedLoadSection(_Strict):
    """``[[loads.distributed]]``: a pressure (kN/m^2 of plan area, downwards) over a plan
    rectangle; :class:`tce.core.loads.DistributedLoad`."""

    x: _vector(2, MAX_LENGTH)
    y: _vector(2, MAX_LENGTH) | None = None
    pressure: _within(MAX_STRESS)
    scaled: bool = True


class VehicleSection(_Strict):
    """``[[loads.vehicle]]``: axles (``[offset (m), load (kN)]``) moving as one, on wheels
    (transverse offsets, m) with optional contact patches, or a ``standard`` vehicle of
    :data:`tce.core.vehicles.STANDARD` (its keys given here replace the standard's);
    :class:`tce.core.vehicles.Vehicle`."""

    standard: Literal[tuple(STANDARD)] | None = None  # type: ignore[valid-type]
    axles: list[_vector(2, MAX_FORCE)] | None = None
    wheels: list[Coordinate] | None = None
    patch: _vector(2, MAX_LENGTH) | None = None
    x: Coordinate | None = None
    y: Coordinate | None = None
    name: str | None = None
    scaled: bool | None = None

    @model_validator(mode="after")
    def _axles_or_standard(self) -> VehicleSection:
        if (self.standard is None) == (self.axles is None):
            raise ValueError(
                "give either axles or standard; fix: axles = [[0.0, 100.0], [1.2, 100.0]] "
                f"([offset (m), load (kN)]) or standard = one of {list(STANDARD)}"
            )
        return self

    def declaration(self) -> dict[str, Any]:
        """The keys of a :class:`tce.core.vehicles.Vehicle` (the standard's, replaced by those given)."""
        given = self.model_dump(exclude_none=True, exclude={"standard"})
        return dict(standard_vehicle(self.standard).to_dict(), **given) if self.standard else given


class FillSection(_Strict):
    """``[loads.fill]``: fill over the top surface (depth over the crown in m, unit weight in
    kN/m^3, its weight on or off, the wheel loads' spread angle in degrees from the vertical,
    the coefficient at rest ``k0``, the passive coefficient ``kp``: 0, the default, switches
    the passive restraint off); :class:`tce.core.fill.Fill`."""

    depth: Depth
    unit_weight: UnitWeight
    weight: bool = True
    dispersion: Annotated[float, Field(ge=0, le=60)] | Literal["boussinesq"] = DISPERSION_2_TO_1
    k0: Annotated[float, Field(ge=0, lt=1)] = 0.0
    kp: Annotated[float, Field(ge=0, le=1e3)] = 0.0

    @field_validator("kp")
    @classmethod
    def _passive_coefficient(cls, v: float) -> float:
        # tce.core.fill: 0 switches the passive restraint off; k0 < 1 <= kp keeps kp above k0
        if v != 0.0 and v < 1.0:
            raise ValueError("give 0 (no passive restraint) or a passive coefficient >= 1 (Rankine: "
                             "(1 + sin phi) / (1 - sin phi)); fix: e.g. kp = 3.0 for phi = 30 degrees")
        return v


class LoadsSection(_Strict):
    """``[loads]``: the load pattern (lateral directions in degrees, whether lambda multiplies
    the lateral pattern: absent, only when no point, distributed or vehicle load is live,
    :class:`tce.core.loads.LoadPattern`; point and distributed loads, vehicles), load-path step and bisection
    tolerance; ``critical_position`` searches the position of the moving loads of least
    lambda_max (:func:`tce.analysis.critical.critical_position`), from the positions
    ``positions`` (m) besides its own."""

    alpha: Angle | list[Angle] = 0.0
    lateral: bool | None = None
    point: list[PointLoadSection] = Field(default_factory=list)
    distributed: list[DistributedLoadSection] = Field(default_factory=list)
    vehicle: list[VehicleSection] = Field(default_factory=list)
    fill: FillSection | None = None
    critical_position: bool = False
    positions: list[Coordinate] | None = None
    lambda_step: Multiplier | None = None
    tolerance: Multiplier | None = None
    lambda_cap: Multiplier | None = None

    @property
    def alphas(self) -> list[float]:
        """The directions as a list."""
        return [float(a) for a in (self.alpha if isinstance(self.alpha, list) else [self.alpha])]

    def pattern(self, alpha: float, load_x: float | None = None) -> LoadPattern:
        """The load pattern in direction ``alpha``, moved to ``load_x`` (m) when given (a
        ``[sweep] load_x`` value); raises :class:`tce.core.loads.LoadError`."""
        pattern = LoadPattern(
            alpha=alpha,
            lateral=self.lateral,
            point=[p.model_dump(exclude_none=True) for p in self.point],
            distributed=[d.model_dump(exclude_none=True) for d in self.distributed],
            vehicle=[v.declaration() for v in self.vehicle],
            fill=None if self.fill is None else self.fill.model_dump(),
        )
        return pattern if load_x is None else pattern.moved(load_x)

    def path_settings(self) -> dict[str, Any]:
        """``lambda_step``, ``tolerance``, ``lambda_cap``: how the load path runs (None: anchored
        on the direct limit, :func:`tce.analysis.loadpath.load_path`); with
        ``critical_position``, also ``critical_position`` and ``positions`` (the search's
        starting positions, m)."""
        out: dict[str, Any] = {"lambda_step": self.lambda_step, "tolerance": self.tolerance, "lambda_cap": self.lambda_cap}
        if self.critical_position:
            out.update(critical_position=True, positions=list(self.positions or []))
        return out

    @field_validator("alpha")
    @classmethod
    def _some_alpha(cls, v: float | list[float]) -> float | list[float]:
        if isinstance(v, list):
            if not v:
                raise ValueError("an empty list; fix: give at least one direction")
            _distinct("alpha", v)
        return v

    @field_validator("positions")
    @classmethod
    def _positions_need_the_search(cls, v: list[float] | None, info: ValidationInfo) -> list[float] | None:
        if v is not None and not info.data.get("critical_position"):
            raise ValueError(
                "positions are the critical-position search's starting grid; fix: set critical_position = true "
                "or sweep the positions with [sweep] load_x"
            )
        return v

    @model_validator(mode="after")
    def _path_ends(self) -> LoadsSection:
        if self.lambda_step is None or self.lambda_cap is None:
            return self
        if self.lambda_step > self.lambda_cap:
            raise ValueError(
                f"lambda_step = {self.lambda_step!r} is larger than lambda_cap = {self.lambda_cap!r}: the path would "
                "try no multiplier but 0; fix: use a lambda_step below lambda_cap, or leave either out (both are "
                "then chosen from the direct limit)"
            )
        if not self.lambda_cap / self.lambda_step <= MAX_INCREMENTS:
            raise ValueError(
                f"lambda_cap / lambda_step = {self.lambda_cap / self.lambda_step:.3g} load increments, more than "
                f"MAX_INCREMENTS = {MAX_INCREMENTS}; fix: use a larger lambda_step or a smaller lambda_cap"
            )
        return self


def _distinct(key: str, values: list[float]) -> None:
    """Refuse a value listed twice (two scenarios would share one name and one answer)."""
    seen: set[float] = set()
    for v in values:
        if v in seen:
            raise ValueError(f"the value {v!r} is listed twice in {key}; fix: remove one of them")
        seen.add(v)


class SweepSection(_Strict):
    """``[sweep]``: lists of values; the study runs the cartesian product."""

    friction: list[Friction] | None = None
    cohesion: list[Stress] | None = None
    tensile_strength: list[Stress] | None = None
    compressive_strength: list[Strength] | None = None
    magnitude: list[_within(MAX_MULTIPLIER)] | None = None
    inner_radius: list[Length] | None = None
    thickness: list[Length] | None = None
    depth: list[Length] | None = None
    radius: list[Length] | None = None
    load_x: list[Coordinate] | None = None

    def items(self) -> list[tuple[str, list[float]]]:
        """``(parameter, values)`` of the parameters swept, in declaration order."""
        return [(k, list(v)) for k, v in self if v is not None]


#: limits solved to refine one minimum of a critical-position search (bounded Brent search to xtol)
SEARCH_REFINE_SOLVES = 50

class AssessmentSection(_Strict):
    """``[assessment]``: partial factors on the dead (every fixed load, self-weight
    included) and live loads; the results carry the adequacy factor
    (:func:`tce.analysis.assessment.adequacy_factor`) and ``tce show`` reads as an assessment.
    The dead load of an arch is favourable: ``dead_factor`` is the favourable factor, at most
    1 (:data:`tce.analysis.assessment.DEAD_FACTOR_RULE`)."""

    dead_factor: Factor = 1.0
    live_factor: Factor = 1.0

    @field_validator("dead_factor")
    @classmethod
    def _favourable(cls, v: float) -> float:
        from ..analysis.assessment import check_dead_factor

        check_dead_factor(v)
        return v


class SettlementPathSection(_Strict):
    """``[settlement_path]``: follow each scenario's settlement vectors times a growing
    magnitude, the geometry updated as the blocks move, to the settlement capacity
    (:func:`tce.analysis.settlement_path.settlement_path`, ``docs/settlements.md``), carrying
    the fixed loads; ``live_at``: the magnitudes at which the live loads' ``lambda_max`` is
    computed on the deformed structure (its critical position searched again with
    ``[loads] critical_position``; :mod:`tce.study.settlement`). ``contact_gap`` (m; default
    ``1e-3`` of the structure's size): on the deformed structure, for the live loads and for the
    lateral capacity (``lambda = true``), the contacts open by at most this much carry
    compression: a joint opened by less closes under a motion that the limit analysis neglects."""

    model_config = ConfigDict(populate_by_name=True)  # merged with _Strict's

    increment: Multiplier = 0.001
    s_max: Multiplier = 1.0
    tolerance: Multiplier | None = None
    lam: bool = Field(default=False, alias="lambda")
    live_at: list[Annotated[float, Field(ge=0.0, le=MAX_MULTIPLIER)]] | None = None
    contact_gap: Length | None = None

    @model_validator(mode="after")
    def _not_too_many_increments(self) -> SettlementPathSection:
        from ..analysis.settlement_path import MAX_STEPS

        if self.increment > self.s_max:
            raise ValueError(f"increment = {self.increment!r} is larger than s_max = {self.s_max!r}: the path would "
                             "take no step; fix: an increment below s_max")
        if self.s_max / self.increment > MAX_STEPS:
            raise ValueError(
                f"s_max / increment = {self.s_max / self.increment:.3g} increments, more than {MAX_STEPS}; "
                "fix: a larger increment or a smaller s_max"
            )
        if self.live_at is not None:
            if not self.live_at:
                raise ValueError("live_at is an empty list; fix: give the magnitudes (>= 0) or remove it")
            _distinct("settlement_path.live_at", self.live_at)
            if max(self.live_at) > self.s_max:
                raise ValueError(
                    f"live_at {max(self.live_at):g} is beyond s_max = {self.s_max:g}; fix: raise s_max or "
                    "lower the magnitude"
                )
        return self


class StudyFile(_Strict):
    """The whole study file."""

    study: StudySection
    structure: Structure
    material: MaterialSection = MaterialSection()
    ring_interface: RingInterfaceSection | None = None
    backing_interface: BackingInterfaceSection | None = None
    defects: DefectsSection | None = None
    loads: LoadsSection = LoadsSection()
    sweep: SweepSection = SweepSection()
    scenarios: Annotated[
        dict[Annotated[str, Field(min_length=1, max_length=100)], dict[str, Vector6]], Field(min_length=1)
    ] = Field(default_factory=lambda: {"none": {}})
    plots: PlotsSection = PlotsSection()
    assessment: AssessmentSection | None = None
    settlement_path: SettlementPathSection | None = None
    uncertainty: UncertaintySection | None = None

    @field_validator("scenarios")
    @classmethod
    def _case_names(cls, v: dict[str, dict[str, list[float]]]) -> dict[str, dict[str, list[float]]]:
        for name in v:  # a case name starts each scenario's name and its file names
            if "/" in name or "\\" in name or not name.strip("."):
                raise ValueError(f"the settlement case {name!r} holds a path separator or is only dots; fix: name it "
                                 "with letters, digits and '_'")
        return v

    @field_validator("sweep")
    @classmethod
    def _no_empty_list(cls, v: SweepSection) -> SweepSection:
        for key, values in v.items():
            if not values:
                raise ValueError(f"sweep.{key} is an empty list; fix: give at least one value or remove it")
            _distinct(f"sweep.{key}", values)
        return v


@dataclass(frozen=True)
class Scenario:
    """One load path to run: a settlement case in one direction with one parameter set.

    Attributes
    ----------
    name : str
        Unique name (the settlement case, then ``/key=value`` for each swept parameter
        that takes more than one value).
    settlement : str
        Name of the settlement case (``[scenarios.NAME]``).
    settlements : dict
        ``{support: [ux, uy, uz, rx, ry, rz]}`` (m, rad), already scaled by ``magnitude``.
    alpha : float
        Lateral direction (degrees).
    pattern : dict
        The scenario's load pattern (:meth:`tce.core.loads.LoadPattern.to_dict`: ``alpha``
        and ``load_x`` applied).
    params : dict
        Values of the swept parameters (and ``alpha``, ``magnitude``) for this scenario.
    structure, material : dict
        Validated ``[structure]`` and ``[material]`` sections with the swept values applied;
        the material holds the ``[ring_interface]`` and ``[backing_interface]`` keys given
        (under their names) when the study has those sections.
    loads : dict
        ``lambda_step``, ``tolerance``, ``lambda_cap`` (and ``critical_position``,
        ``positions`` when the study searches the critical position).
    assembly_digest : str
        SHA-256 of the built assembly (:func:`assembly_digest`): what the structure is,
        whatever file or generator it came from.
    draw : tuple of float
        Load multipliers the study's figures draw for this scenario (``[plots] steps``,
        empty unless ``[plots]`` selects the scenario): solved after the load path when
        they are not steps of it. Not part of :attr:`key`: figures do not change answers.
    uncertainty : str, optional
        Set on the jobs of ``[uncertainty]`` (:meth:`Study.jobs`), which solve the section
        (JSON, :meth:`UncertaintySection.spec`) instead of the load path (:mod:`tce.study.samples`).
    samples : (int, int), optional
        A job of samples: the samples ``lo`` to ``hi - 1``, named ``<scenario> samples lo-hi``;
        None for the scenario's job of FORM and subset simulation, ``<scenario> form+subset``.
    of : str, optional
        The name of the scenario a job of ``[uncertainty]`` belongs to.
    """

    name: str
    settlement: str
    settlements: dict[str, list[float]]
    alpha: float
    pattern: dict[str, Any]
    params: dict[str, float]
    structure: dict[str, Any]
    material: dict[str, Any]
    loads: dict[str, Any]
    assembly_digest: str
    draw: tuple[float, ...] = ()
    settlement_path: dict[str, Any] | None = None
    uncertainty: str | None = None
    samples: tuple[int, int] | None = None
    of: str | None = None

    @property
    def group(self) -> str:
        """Key of the analysis this scenario needs: scenarios with equal keys share one."""
        return json.dumps([self.assembly_digest, self.material], sort_keys=True)

    def __repr__(self) -> str:
        moved = ", ".join(self.settlements) or "no support motion"
        return display.call("Scenario", {"alpha": self.alpha}, head=f"{self.name!r}, {moved}")

    @property
    def key(self) -> str:
        """SHA-256 of everything that determines the answer (for resuming): the built
        assembly, the material, the support motions, the direction, the loads (when other
        than the lateral pattern alone), the load-path settings, the versions of tce and
        of the solver, how the runner narrows the limit, the solver's settings and a digest
        of the installed tce code (:mod:`tce.study.keys`)."""
        from ..core.solve import SOLVER_NAME
        from .keys import BRACKET, code_digest, solver_settings

        what = {
            "assembly": self.assembly_digest,
            "material": self.material,
            "settlements": self.settlements,
            "alpha": self.alpha,
            "loads": self.loads,
            "tce": __version__,
            "solver": SOLVER_NAME,
            "bracket": BRACKET,
            "solver_settings": solver_settings(),
            "code": code_digest(),
        }
        if not self.loads_pattern.default:
            what["pattern"] = self.pattern
        if self.settlement_path is not None:
            what["settlement_path"] = self.settlement_path
        if self.uncertainty is not None:
            section = UncertaintySection.model_validate_json(self.uncertainty)
            what["uncertainty"] = section.answer_spec(self.samples is not None)
            what["samples"] = None if self.samples is None else list(self.samples)
        return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()

    @property
    def loads_pattern(self) -> LoadPattern:
        """The scenario's :class:`tce.core.loads.LoadPattern`."""
        return LoadPattern.from_dict(self.pattern)

    @property
    def moves(self) -> bool:
        """Whether the scenario moves a support."""
        return any(any(u != 0 for u in v) for v in self.settlements.values())

    def capacity_kind(self, capacity: str) -> str:
        """What the samples of this scenario compute for ``[uncertainty] capacity``
        (:func:`tce.study.uncertainty.capacity_kind`)."""
        return capacity_kind(capacity, self.settlement_path is not None, self.moves, "dead_factor" in self.loads)

    def drawn(self, values: Mapping[str, float]) -> Drawn:
        """The scenario's sections with the sample ``values`` (study key -> value) set:
        ``material.<key>``, ``structure.<key>``, ``loads.alpha``, ``loads.fill.<key>``,
        ``loads.vehicle.<i>.x`` / ``.y``, ``assessment.<factor>``; ``settlement.magnitude``
        multiplies the settlement vectors (:func:`check_uncertainty` has checked the keys)."""
        structure, material, pattern = dict(self.structure), dict(self.material), copy.deepcopy(self.pattern)
        factors = {k: float(self.loads[k]) for k in ("dead_factor", "live_factor") if k in self.loads}
        scale = 1.0
        for key, v in values.items():
            head, _, rest = key.partition(".")
            if head == "material":
                material[rest] = v
            elif head == "structure":
                structure[rest] = v
            elif head == "assessment":
                factors[rest] = v
            elif key == "settlement.magnitude":
                scale = v
            elif key == "loads.alpha":
                pattern["alpha"] = v
            elif rest.startswith("fill."):
                pattern["fill"][rest[5:]] = v
            else:  # loads.vehicle.<i>.<x|y>
                _, i, coord = rest.split(".")
                pattern["vehicle"][int(i)][coord] = v
        settlements = {s: [scale * u for u in vec] for s, vec in self.settlements.items()}
        return Drawn(structure, material, pattern, factors, settlements)


@dataclass(frozen=True)
class Drawn:
    """A scenario's sections with one sample's values (plain data, as in :class:`Scenario`;
    ``factors``: the assessment's ``dead_factor`` and ``live_factor``)."""

    structure: dict[str, Any]
    material: dict[str, Any]
    pattern: dict[str, Any]
    factors: dict[str, float]
    settlements: dict[str, list[float]]


def assembly_digest(assembly: Assembly) -> str:
    """SHA-256 of an assembly's blocks and interfaces (names, exact coordinates, faces,
    unit weights, supports, stiffness multipliers; not its ``meta``)."""
    data = assembly.to_dict()
    data.pop("meta")
    return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()


@dataclass(frozen=True)
class Study:
    """A validated study file.

    Attributes
    ----------
    path : Path
        The file it was read from.
    text : str
        The file's TOML text (stored in the results so that a run can be repeated).
    spec : StudyFile
        The validated content.
    """

    path: Path
    text: str
    spec: StudyFile = field(repr=False)
    _assemblies: dict[str, Assembly] = field(default_factory=dict, repr=False, compare=False)
    _digests: dict[str, str] = field(default_factory=dict, repr=False, compare=False)

    @property
    def name(self) -> str:
        """The study's name (``[study] name``)."""
        return self.spec.study.name

    def __repr__(self) -> str:
        scenarios = self.scenarios()
        return display.call("Study", {}, head=f"{self.name!r}, {self.path}, {len(scenarios)} scenarios "
                            f"{display.names([sc.name for sc in scenarios], 3)}")

    def search_solves(self) -> int:
        """Most direct-limit solves of one critical-position search (0 without one): the
        positions it scans on the first structure, and :data:`SEARCH_REFINE_SOLVES` for each
        minimum it refines."""
        if not self.spec.loads.critical_position:
            return 0
        from ..analysis.critical import REFINED, scan_positions, search_bounds

        sc = next(self._expand())
        pattern, assembly = sc.loads_pattern, self.assembly(sc.structure)
        scanned = scan_positions(pattern, assembly, *search_bounds(pattern, assembly), sc.loads["positions"])
        return len(scanned) + REFINED * SEARCH_REFINE_SOLVES

    def work(self) -> str:
        """The most solves the study asks for, in words (:func:`tce.study.guards.work`)."""
        return f"{guards.work(self.spec, self.search_solves())[1]} (the study's cap: [study] max_solves = " \
               f"{self.spec.study.max_solves})"

    def assembly(self, structure: dict[str, Any]) -> Assembly:
        """The built assembly of a scenario's ``structure`` section: built once (when the
        study is validated), then the same object for the run, its workers and its results."""
        key = json.dumps(structure, sort_keys=True)
        if key not in self._assemblies:
            built = build_structure(structure)
            if self.spec.defects is not None:
                try:
                    built = self.spec.defects.apply(built)
                except AssemblyError as exc:
                    raise AssemblyError(f"defects: {exc}") from None
            self._assemblies[key] = built
        return self._assemblies[key]

    @cached_property
    def swept(self) -> list[tuple[str, list[float]]]:
        """Every parameter that varies across scenarios, with its values (alpha first)."""
        axes = [("alpha", self.spec.loads.alphas)] + self.spec.sweep.items()
        return [(k, v) for k, v in axes if len(v) > 1 or k != "alpha"]

    def scenarios(self) -> list[Scenario]:
        """The cartesian product of settlement cases, directions and sweeps, in file order."""
        out = list(self._expand())
        plots = self.spec.plots
        drawn = set(plots.select([sc.name for sc in out]))
        lams = tuple(plots.lambdas)
        return [replace(sc, draw=lams) if lams and sc.name in drawn else sc for sc in out]

    def jobs(self) -> list[Scenario]:
        """What a run solves: every scenario (:meth:`scenarios`) and, with ``[uncertainty]``,
        for each scenario ``ceil(samples / chunk)`` jobs of samples (:attr:`Scenario.samples`)
        and, with ``form`` or ``subset``, one job of FORM and subset simulation, in the
        scenarios' order."""
        scenarios = self.scenarios()
        section = self.spec.uncertainty
        if section is None:
            return scenarios
        spec, n = section.spec(), section.samples
        jobs = [
            replace(sc, name=f"{sc.name}{SAMPLES_SEPARATOR}{lo}-{min(lo + section.chunk, n)}", draw=(),
                    samples=(lo, min(lo + section.chunk, n)), uncertainty=spec, of=sc.name)
            for sc in scenarios for lo in range(0, n, section.chunk)
        ]
        if section.form or section.subset:
            jobs += [replace(sc, name=f"{sc.name}{ESTIMATORS_SUFFIX}", draw=(), uncertainty=spec, of=sc.name)
                     for sc in scenarios]
        return scenarios + jobs

    def _expand(self) -> Iterator[Scenario]:
        spec = self.spec
        axes = [("alpha", spec.loads.alphas)] + spec.sweep.items()
        names = [k for k, _ in axes]
        loads = spec.loads.path_settings()
        if spec.assessment is not None:
            loads.update(spec.assessment.model_dump())
        for case, motions in spec.scenarios.items():
            for values in itertools.product(*(v for _, v in axes)):
                p = dict(zip(names, (float(v) for v in values), strict=True))
                scale = p.get("magnitude", 1.0)
                label = "/".join(f"{k}={_fmt(p[k])}" for k, v in axes if len(v) > 1)
                structure = _with(spec.structure.model_dump(), p, GEOMETRY_SWEEPS)
                yield Scenario(
                    name=f"{case}/{label}" if label else case,
                    settlement=case,
                    settlements={s: [scale * u for u in vec] for s, vec in motions.items()},
                    alpha=p["alpha"],
                    pattern=spec.loads.pattern(p["alpha"], p.get("load_x")).to_dict(),
                    params=p,
                    structure=structure,
                    material=self.material(p),
                    loads=loads,
                    assembly_digest=self._digest(structure),
                    settlement_path=spec.settlement_path.model_dump() if spec.settlement_path else None,
                )

    def material(self, params: dict[str, float] | None = None) -> dict[str, Any]:
        """The ``[material]`` section with the swept values ``params`` applied, and the
        ``[ring_interface]`` and ``[backing_interface]`` keys given (under their names) when
        the study has those sections: what :func:`build_material` builds."""
        spec = self.spec
        out = _with(spec.material.model_dump(), params or {}, MATERIAL_SWEEPS)
        for key in ("ring_interface", "backing_interface"):
            if getattr(spec, key) is not None:
                out[key] = getattr(spec, key).model_dump(exclude_unset=True)
        if spec.defects is not None and spec.defects.joint_law:
            out["joint_law"] = [law.model_dump(exclude_unset=True, exclude={"joints"}) for law in spec.defects.joint_law]
        return out

    def _digest(self, structure: dict[str, Any]) -> str:
        key = json.dumps(structure, sort_keys=True)
        if key not in self._digests:
            self._digests[key] = assembly_digest(self.assembly(structure))
        return self._digests[key]


def _fmt(value: float) -> str:
    """Exact label of a swept value: the shortest text that reads back as the same float
    (``0.8000001`` stays ``0.8000001``), without a trailing ``.0``."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _with(section: dict[str, Any], params: dict[str, float], keys: tuple[str, ...]) -> dict[str, Any]:
    """``section`` with the swept values of ``keys`` applied."""
    return section | {k: params[k] for k in keys if k in params}


# ---------------------------------------------------------------------------- reading
_LISTS = (
    " ([ux, uy, uz, rx, ry, rz] in m and rad for a displacement, [x, y, z] for a point or a force, "
    "[x, y] for a plan point, [from, to] for a plan range)"
)
#: hints of a study file that replace :data:`tce.messages.HINTS`
_HINTS = {
    "too_short": "give exactly {min_length} numbers" + _LISTS,
    "too_long": "give exactly {max_length} numbers" + _LISTS,
    "string_pattern_mismatch": "use only letters, digits, '_', '.' and '-', not starting with '.' or '-'",
    "union_tag_invalid": "use one of the structure types {tags}",
    "union_tag_not_found": "add type = \"semicircular_arch\" (or another structure type)",
}


def parse_study(text: str, path: Path | str = "<study>") -> Study:
    """Validate study TOML ``text`` (see :func:`load_study`; ``path`` is for messages)."""
    path = Path(path)
    guards.check_text(path, text)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise StudyError(f"{path}: not valid TOML: {exc}; fix: correct the syntax") from None
    except RecursionError:
        raise StudyError(
            f"{path}: nested more than MAX_TOML_DEPTH = {guards.MAX_TOML_DEPTH} deep; fix: a study needs tables "
            "of values and lists, no deeper"
        ) from None
    guards.check_tree(path, data)
    try:
        spec = StudyFile.model_validate(data)
    except ValidationError as exc:
        raise StudyError("\n".join(describe(path, exc, StudyFile, "docs/studies.md", _HINTS, _SECTIONS))) from None
    guards.check_work(path, spec)
    if isinstance(spec.structure, FileStructure):
        where = (path.parent / spec.structure.path).resolve()
        spec = spec.model_copy(update={"structure": spec.structure.model_copy(update={"path": str(where)})})
    try:
        base = spec.loads.pattern(spec.loads.alphas[0])
    except LoadError as exc:
        raise StudyError(f"{path}: {exc.within('loads')}") from None
    if spec.sweep.load_x is not None:
        try:
            base.moved(0.0)
        except LoadError as exc:
            raise StudyError(f"{path}: sweep.load_x: {exc.problem} in [loads]; fix: {exc.fix}") from None
    if spec.loads.critical_position:
        if spec.sweep.load_x is not None:
            raise StudyError(
                f"{path}: loads.critical_position: the search finds the position itself, a load_x sweep samples it; "
                "fix: remove [sweep] load_x (give a starting grid as [loads] positions) or set critical_position = false"
            )
        if base.reference_x != base.reference_x:
            raise StudyError(
                f"{path}: loads.critical_position: nothing moves; fix: add a [[loads.vehicle]] or a [[loads.point]] "
                "with on_top and scaled = true"
            )
    study = Study(path, text, spec)
    _check_scenarios(study)
    guards.check_work(path, spec, drawn_scenarios=len(spec.plots.select([sc.name for sc in study._expand()])),
                      search_solves=study.search_solves())
    _check_plots(study)
    _check_settlement_path(study)
    _check_passive(study)
    check_uncertainty(study)
    return study


def _check_passive(study: Study) -> None:
    """The fill's passive restraint (``[loads.fill] kp`` > 0) with a non-associative material:
    the non-associative estimate does not carry it (:func:`tce.core.passive.refuse_passive`)."""
    fill = study.spec.loads.fill
    if fill is None or fill.kp == 0.0:
        return
    if any(build_material(sc.material).flow == "non-associative" for sc in study.scenarios()):
        raise StudyError(
            f"{study.path}: loads.fill.kp: {fill.kp:g} with a non-associative material: the non-associative "
            "estimate does not carry the passive restraint; fix: kp = 0, or flow = \"associative\""
        )


def load_study(path: Path | str) -> Study:
    """Read and validate a study file; build each distinct structure once to check it.

    Raises
    ------
    StudyError
        The file is missing or unreadable, is not TOML, breaks the schema, describes a
        structure that cannot be built, or moves a support the structure does not have.
    """
    path = Path(path)
    return parse_study(guards.read_study_text(path), path)


def build_structure(section: dict[str, Any]) -> Assembly:
    """The assembly of a validated ``[structure]`` section given as a plain dict."""
    return TypeAdapter(Structure).validate_python(section).build()


def build_material(section: dict[str, Any]) -> Material:
    """The material of a validated ``[material]`` section given as a plain dict
    (:meth:`Study.material`): with a ``"backing_interface"`` entry, the interfaces of kind
    ``"backing"`` get its law; with a ``"ring_interface"`` entry, the interfaces of kind
    ``"ring"`` get its law, and with ``"joint_law"`` entries the joints of kinds ``joints1``,
    ... theirs (:func:`joint_kind`), the keys they leave out taken from ``[material]``."""
    section = dict(section)
    given = {kind: section.pop(key, None) for key, kind in (("ring_interface", RING_KIND), ("backing_interface", BACKING))}
    joints = section.pop("joint_law", [])
    material = MaterialSection.model_validate(section).build()
    own = {k: getattr(material, k) for k in ("friction", "cohesion", "tensile_strength", "compressive_strength")}
    laws = {joint_kind(k): Material(**(own | {k_: v for k_, v in law.items() if v is not None}))
            for k, law in enumerate(joints)}
    for kind, law in given.items():
        if law is not None:
            law = RingInterfaceSection.model_validate(law)
            laws[kind] = Material(bonded=True) if law.bonded else \
                Material(**(own | law.model_dump(exclude_none=True, exclude={"bonded"})))
    return replace(material, interfaces=laws) if laws else material


def _check_scenarios(study: Study) -> None:
    """Build every distinct structure (kept for the run) and material; check the supports
    each scenario moves, that no two scenarios share a name, and apply each scenario's loads
    to its structure."""
    spec = study.spec
    fields = type(spec.structure).model_fields
    for key, _ in spec.sweep.items():
        if key in GEOMETRY_SWEEPS and key not in fields:
            usable = [k for k in GEOMETRY_SWEEPS if k in fields]
            raise StudyError(
                f"{study.path}: sweep.{key}: the structure type {spec.structure.type!r} has no parameter "
                f"{key!r}; fix: sweep one of {usable} or remove it"
            )
    geometry = [(k, v) for k, v in spec.sweep.items() if k in GEOMETRY_SWEEPS]
    for values in itertools.product(*(v for _, v in geometry)):
        swept = dict(zip((k for k, _ in geometry), (float(v) for v in values), strict=True))
        try:
            study.assembly(_with(spec.structure.model_dump(), swept, GEOMETRY_SWEEPS)).validate()
        except (ValueError, OSError) as exc:
            raise StudyError(
                f"{study.path}: structure: cannot build it{f' with {swept}' if swept else ''}: {exc}; "
                f"fix: {_build_fix(spec.structure, exc, swept)}"
            ) from None
    names: dict[str, str] = {}  # slug -> scenario name: each names its own files (tce export)
    for sc in study.scenarios():
        try:
            build_material(sc.material)
        except (ValueError, ValidationError) as exc:
            # Material's messages start with the parameter they are about
            name = str(exc).split(" ", 1)[0]
            key = f"material.{name}" if name in MaterialSection.model_fields else "material"
            swept = {k: v for k, v in sc.params.items() if k in MATERIAL_SWEEPS}
            raise StudyError(
                f"{study.path}: {key}: {exc}{f' (with {swept})' if swept else ''}; "
                f"fix: change the [material]{', [ring_interface]' if study.spec.ring_interface else ''} or [sweep] values"
            ) from None
        kinds = study.assembly(sc.structure).interface_table.kind
        if study.spec.ring_interface is not None and RING_KIND not in kinds:
            raise StudyError(
                f"{study.path}: ring_interface: the structure has no faces between rings, so the law would have no "
                "effect; fix: give the arch rings = 2 or more, or remove [ring_interface]"
            )
        if study.spec.backing_interface is not None and BACKING not in kinds:
            raise StudyError(
                f"{study.path}: backing_interface: the structure has no backing blocks, so the law would have no "
                "effect; fix: give the arch backing = {{ height = ..., model = \"blocks\" }} above its extrados' "
                "springing, or remove [backing_interface]"
            )
        supports = study.assembly(sc.structure).support_names
        unknown = sorted(set(sc.settlements) - set(supports))
        if unknown:
            raise StudyError(
                f"{study.path}: scenarios.{sc.settlement}.{unknown[0]}: the structure has no support "
                f"named {unknown[0]!r}; fix: use one of {list(supports)}{did_you_mean(unknown[0], supports)}"
            )
        if any(not math.isfinite(u) for v in sc.settlements.values() for u in v):
            raise StudyError(f"{study.path}: scenarios.{sc.settlement}: a displacement overflows; fix: smaller values")
        twin = names.setdefault(slug(sc.name), sc.name)
        if twin is not sc.name:
            same = (f"are named {sc.name!r}" if twin == sc.name
                    else f"{twin!r} and {sc.name!r} share the file name {slug(sc.name)!r}")
            raise StudyError(
                f"{study.path}: scenarios.{sc.settlement}: two scenarios {same}; fix: rename the settlement case"
            )
        _check_loads(study, sc, study.assembly(sc.structure))


def _check_loads(study: Study, sc: Scenario, assembly: Assembly) -> None:
    """Apply a scenario's loads to its structure; a load that cannot be applied is named."""
    pattern = sc.loads_pattern
    try:
        if sc.loads.get("critical_position"):
            from ..analysis.critical import check_on_deck, on_deck

            # the declared position need not have every moving vehicle on the deck: the search moves them
            at_declared = on_deck(pattern, assembly)
            if at_declared is not None:
                resolve(at_declared, assembly)
            _check_positions(study, sc, assembly)
            check_on_deck(pattern, assembly)
        else:
            resolve(pattern, assembly)
    except LoadError as exc:
        # name load_x only for a load it moved
        moved = [f"point[{k}]." for k, p in enumerate(pattern.point) if p.scaled and p.on_top is not None]
        keys = GEOMETRY_SWEEPS + (("load_x",) if any(exc.key.startswith(m) for m in moved) else ())
        swept = {k: v for k, v in sc.params.items() if k in keys}
        where = f" (with {', '.join(f'sweep.{k} = {v:g}' for k, v in swept.items())})" if swept else ""
        err = exc.within("loads")
        raise StudyError(f"{study.path}: {err.key}: {err.problem}{where}; fix: {err.fix}") from None


def _check_positions(study: Study, sc: Scenario, assembly: Assembly) -> None:
    """The starting positions of a critical-position search lie in its range."""
    from ..analysis.critical import search_bounds

    lo, hi = search_bounds(sc.loads_pattern, assembly)
    for k, x in enumerate(sc.loads["positions"]):
        if not lo <= x <= hi:
            raise StudyError(
                f"{study.path}: loads.positions[{k}]: {x:g} m is outside [{lo:.6g}, {hi:.6g}] m, the positions where a "
                "moving load is on the deck; fix: give positions inside it"
            )


def _build_fix(section: BaseModel, exc: Exception, swept: dict[str, float]) -> str:
    """The fix of a structure that cannot be built, for the kind of failure."""
    text = str(exc)
    if text.startswith("defects:"):
        return "name the blocks and joints of [defects] as the structure names them (a joint: 'A|B', its two blocks)"
    if not isinstance(section, FileStructure):
        return f"change the [sweep] values of {sorted(swept)}" if swept else "change the [structure] values"
    if isinstance(exc, FileNotFoundError):
        return "correct [structure] path (relative to the study file)"
    if isinstance(exc, InputLimitError):
        return "split the structure or simplify its blocks (limits: docs/assembly-format.md)"
    if "not a regular file" in text:
        return "point [structure] path at a block file (.json or .obj)"
    if "no support block" in text or "every block is a support" in text or "support block(s)" in text:
        return "name the support blocks with supports = [...] in [structure]"
    return "correct the block file named above"


def _check_plots(study: Study) -> None:
    """Every ``[plots] scenarios`` entry names (or matches) a scenario of the study."""
    names = [sc.name for sc in study._expand()]
    for entry in study.spec.plots.unmatched(names):
        k = (study.spec.plots.scenarios or []).index(entry)
        raise StudyError(
            f"{study.path}: plots.scenarios[{k}]: no scenario named {entry!r}; "
            f"fix: use one of {names[:8]}{' ...' if len(names) > 8 else ''} (or a pattern such as 'outward/*')"
            f"{did_you_mean(entry, names)}"
        )


def _check_settlement_path(study: Study) -> None:
    """``[settlement_path]`` follows assemblies of the rigid Heyman material; planar ones with
    in-plane motions and (with ``lambda = true``) an in-plane lateral direction."""
    section = study.spec.settlement_path
    if section is None:
        return
    from ..analysis.settlement_path import check_path_scene
    from ..core.model import find_plane

    for sc in study.scenarios():
        pattern = sc.loads_pattern
        if pattern.live_loads and not section.live_at:
            raise StudyError(
                f"{study.path}: settlement_path: the path carries the self-weight and the fixed loads; the live "
                f"loads ({', '.join(pattern.live_loads)}) are applied after it, on the deformed structure, at the "
                "magnitudes of live_at; fix: add live_at = [...] to [settlement_path] (multiples of the settlement "
                "vectors), or remove [settlement_path]"
            )
        if section.live_at and not pattern.live_loads:
            raise StudyError(
                f"{study.path}: settlement_path.live_at: no live load to apply (lambda multiplies the lateral "
                "pattern alone, which lambda = true follows along the path); fix: remove live_at or add a live load"
            )
        assembly = study.assembly(sc.structure)
        try:
            check_path_scene(assembly, build_material(sc.material), sc.settlements, sc.alpha if section.lam else None)
        except ValueError as exc:
            raise StudyError(
                f"{study.path}: settlement_path (scenario {sc.name!r}): {exc}; fix: remove [settlement_path] "
                "or give a Heyman material (no [material] keys) and, for a planar structure, in-plane motions"
            ) from None
        if section.live_at and find_plane(assembly) is None:
            raise StudyError(
                f"{study.path}: settlement_path.live_at: live loads on a deformed spatial structure are not "
                "supported: its no-sliding contacts, no longer parallel after the settlement, carry spurious "
                "tangential forces (a dome's crown load came out unbounded after 2 cm of spread; "
                "docs/settlements.md); fix: remove live_at, or use a planar structure"
            )


def _real(annotation: Any) -> bool:
    """Whether a field's annotation takes a real number (not a list of them)."""
    if annotation is float:
        return True
    if get_origin(annotation) in (list, tuple, dict):
        return False
    return any(_real(a) for a in get_args(annotation))


def _numeric(fields: Mapping[str, Any]) -> list[str]:
    """The fields of a section that take a real number."""
    return [k for k, f in fields.items() if _real(f.annotation)]


def _key_problem(study: Study, key: str) -> str | None:
    """Why ``key`` is not a variable of ``study`` (None when it is one)."""
    spec = study.spec
    head, _, rest = key.partition(".")
    sections = {"material": MaterialSection.model_fields, "structure": type(spec.structure).model_fields,
                "loads.fill": FillSection.model_fields, "assessment": AssessmentSection.model_fields}
    if head == "loads" and rest.startswith("fill."):
        head, rest = "loads.fill", rest[5:]
        if spec.loads.fill is None:
            return "the study has no [loads.fill]"
    if head in sections:
        if head == "assessment" and spec.assessment is None:
            return "the study has no [assessment]"
        if head == "structure" and spec.defects is not None:
            return ("a structure with [defects] is not rebuilt per sample; fix: remove the variable, or the "
                    "[defects] section")
        numeric = _numeric(sections[head])
        if rest in numeric:
            return None
        if rest in sections[head]:
            return f"{head}.{rest} is not a real number; use one of {[f'{head}.{k}' for k in numeric]}"
        return f"{head} has no key {rest!r}; use one of {[f'{head}.{k}' for k in numeric]}{did_you_mean(rest, numeric)}"
    if key in ("loads.alpha", "settlement.magnitude"):
        return None
    if head == "loads" and rest.startswith("vehicle."):
        _, i, coord = (rest.split(".") + ["", ""])[:3]
        n = len(spec.loads.vehicle)
        if not (i.isdigit() and int(i) < n and coord in ("x", "y") and rest.count(".") == 2):
            return f"use loads.vehicle.<i>.x or .y with i from 0 to {n - 1}" if n else "the study has no [[loads.vehicle]]"
        if coord == "x" and spec.loads.critical_position:
            return "the critical-position search sets the vehicles' x itself; fix: remove the variable"
        return None
    known = ["material.<key>", "structure.<key>", "loads.alpha", "loads.fill.<key>", "loads.vehicle.<i>.x",
             "loads.vehicle.<i>.y", "assessment.dead_factor", "assessment.live_factor", "settlement.magnitude"]
    return f"not a key a variable can set; use one of {known}"


def _reason(exc: Exception) -> str:
    """A refusal in a few words (the first two problems of a ValidationError)."""
    if isinstance(exc, ValidationError):
        return "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in exc.errors()[:2])
    return str(exc)


def _refused(study: Study, sc: Scenario, key: str, value: float) -> str | None:
    """Why the section of ``key`` refuses ``value`` in scenario ``sc`` (None when it takes it)."""
    d = sc.drawn({key: value})
    head = key.partition(".")[0]
    try:
        if head == "material":
            build_material(d.material)
        elif head == "structure":
            build_structure(d.structure).validate()
        elif head == "assessment":
            AssessmentSection.model_validate(d.factors)
        elif key == "settlement.magnitude":
            if not abs(value) <= MAX_MULTIPLIER:
                return f"beyond +-{MAX_MULTIPLIER:g}"
        elif key == "loads.alpha":
            if not abs(value) <= 360.0:
                return "an angle beyond +-360 degrees"
        else:
            if "fill" in d.pattern:
                FillSection.model_validate(d.pattern["fill"])
            pattern = LoadPattern.from_dict(d.pattern)
            if not sc.loads.get("critical_position"):
                resolve(pattern, study.assembly(sc.structure))
    except (ValueError, ValidationError, LoadError, OSError) as exc:
        return _reason(exc)
    return None


def check_uncertainty(study: Study) -> None:
    """Refuse an ``[uncertainty]`` section that cannot run on ``study``, naming the file and the
    key (:class:`StudyError`): a variable's key that the study does not have or that is not a
    real number, a capacity whose section is missing, the assessment's factors with another
    capacity, the material with a settlement capacity, and a variable whose smallest or largest
    drawn value its section refuses (a normal thickness drawn negative)."""
    section = study.spec.uncertainty
    if section is None:
        return
    path, spec = study.path, study.spec
    jobs = len(study.scenarios()) * math.ceil(section.samples / section.chunk)
    if jobs > MAX_JOBS:
        raise StudyError(f"{path}: uncertainty.chunk: {jobs} jobs of samples (scenarios x ceil(samples / chunk)), more "
                         f"than MAX_JOBS = {MAX_JOBS}, each a file; fix: a larger chunk")
    where = lambda key: f'{path}: uncertainty.variables."{key}"'  # noqa: E731
    for key in section.names:
        problem = _key_problem(study, key)
        if problem is not None:
            raise StudyError(f"{where(key)}: {problem}" + ("" if "fix:" in problem else "; fix: correct the key"))
    needs = {"adequacy_factor": ("assessment", spec.assessment), "settlement_capacity":
             ("settlement_path", spec.settlement_path)}
    if section.capacity in needs and needs[section.capacity][1] is None:
        name = needs[section.capacity][0]
        raise StudyError(f"{path}: uncertainty.capacity: {section.capacity} needs a [{name}] section; fix: add it or "
                         "capacity = \"auto\"")
    kinds = {sc.name: sc.capacity_kind(section.capacity) for sc in study.scenarios()}
    for sc in study.scenarios():
        if kinds[sc.name] == "settlement_capacity" and not sc.moves:
            raise StudyError(f"{path}: uncertainty.capacity: scenario {sc.name!r} moves no support: it has no settlement "
                             "capacity; fix: capacity = \"auto\"")
    for key in section.names:
        if key.startswith("assessment.") and any(k != "adequacy_factor" for k in kinds.values()):
            raise StudyError(f"{where(key)}: the assessment's factors enter the adequacy factor alone, and some "
                             "scenario computes another capacity; fix: capacity = \"adequacy_factor\" or remove the variable")
        if key.startswith("material.") and "settlement_capacity" in kinds.values():
            raise StudyError(f"{where(key)}: a settlement path follows the rigid Heyman material (no friction limit, "
                             "cohesion or strengths); fix: remove the variable, or capacity = \"lambda_max\"")
    _, x = draw(section)
    first = study.scenarios()[0]
    for j, key in enumerate(section.names):
        lo, hi = float(x[:, j].min()), float(x[:, j].max())
        for value in (lo, hi) if hi > lo else (lo,):
            problem = _refused(study, first, key, value)
            if problem is not None:
                raise StudyError(
                    f"{where(key)}: the {section.samples} drawn values span [{lo:.6g}, {hi:.6g}] and {value:.6g} is "
                    f"refused ({problem}); fix: a distribution within the key's range (truncnorm with bounds, "
                    "lognormal for a positive quantity) or a smaller spread"
                )
