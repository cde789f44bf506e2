"""Study files: a TOML description of a structure, its material, its loads and its scenarios.

A study is read and validated as a whole before anything runs (:func:`load_study`): the
schema (pydantic, unknown keys forbidden, NaN and infinities refused), then the structure
is built once per distinct geometry and every scenario's support names are checked
against it. Every problem is reported as a :class:`StudyError` whose message names the
file, the key and the fix. The format is documented in ``docs/studies.md``.

A valid study expands (:meth:`Study.scenarios`) into the cartesian product of its
settlement cases, its lateral directions (``[loads] alpha``) and its ``[sweep]`` lists,
in that order, each expanded :class:`Scenario` carrying everything a worker needs. The
loads (``[loads]``, its ``[[loads.point]]`` and ``[[loads.distributed]]`` tables) are a
:class:`tce.core.loads.LoadPattern`; they are resolved against every structure before
anything runs, and ``[sweep] load_x`` moves every scaled ``on_top`` point load.
"""

from __future__ import annotations

import itertools
import json
import math
import tomllib
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError, field_validator

from ..core.loads import LoadError, LoadPattern, resolve
from ..core.material import Material
from ..structures.assembly import Assembly

__all__ = ["Scenario", "Study", "StudyError", "build_material", "build_structure", "load_study", "parse_study"]

COMPONENTS = ("ux", "uy", "uz", "rx", "ry", "rz")
#: swept parameters that change the structure (the others change material or settlement)
GEOMETRY_SWEEPS = ("inner_radius", "thickness", "depth", "radius")


class StudyError(ValueError):
    """A study file that cannot be run; the message says where and how to fix it."""


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, frozen=True)


Positive = Annotated[float, Field(gt=0)]
NonNegative = Annotated[float, Field(ge=0)]
Vector6 = Annotated[list[float], Field(min_length=6, max_length=6)]
Vector3 = Annotated[list[float], Field(min_length=3, max_length=3)]
Vector2 = Annotated[list[float], Field(min_length=2, max_length=2)]


class StudySection(_Strict):
    """``[study]``: the study's name (also its results folder) and an optional description."""

    name: str = Field(min_length=1, pattern=r"^[A-Za-z0-9_.-]+$")
    description: str = ""


class ArchStructure(_Strict):
    """``[structure] type = "semicircular_arch"``: :func:`tce.arch.semicircular_arch`."""

    type: Literal["semicircular_arch"]
    inner_radius: Positive = 1.0
    thickness: Positive = 0.2
    depth: Positive = 0.25
    voussoirs: Annotated[int, Field(ge=1)] = 14
    unit_weight: Positive = 20.0
    support_height: Positive | None = None

    def build(self) -> Assembly:
        """The assembly this section describes."""
        from ..structures.arch import semicircular_arch

        return semicircular_arch(**self.model_dump(exclude={"type"}))


class DomeStructure(_Strict):
    """``[structure] type = "dome"``: :func:`tce.dome.hemispherical_dome`."""

    type: Literal["dome"]
    radius: Positive = 5.0
    thickness: Positive = 0.3
    sectors: Annotated[int, Field(ge=3)] = 16
    courses: Annotated[int, Field(ge=1)] = 8
    oculus: Annotated[float, Field(ge=0, lt=90)] = 0.0
    unit_weight: Positive = 20.0
    support_height: Positive | None = None

    def build(self) -> Assembly:
        """The assembly this section describes."""
        from ..structures.dome import hemispherical_dome

        return hemispherical_dome(**self.model_dump(exclude={"type"}))


class FileStructure(_Strict):
    """``[structure] type = "file"``: blocks read by :func:`tce.io.load_assembly`.

    ``path`` is relative to the study file (made absolute when the study is read);
    ``supports`` names the support blocks (default: the flags in the file).
    """

    type: Literal["file"]
    path: str = Field(min_length=1)
    supports: list[str] | None = None
    unit_weight: Positive | None = None

    def build(self) -> Assembly:
        """The assembly this section describes."""
        from ..structures.io import load_assembly

        return load_assembly(self.path, supports=self.supports, unit_weight=self.unit_weight)


Structure = Annotated[ArchStructure | DomeStructure | FileStructure, Field(discriminator="type")]


class MaterialSection(_Strict):
    """``[material]``: friction (absent: Heyman, unlimited) and optional stiffnesses."""

    friction: NonNegative | None = None
    normal_stiffness: Positive | None = None
    shear_stiffness: Positive | None = None

    def build(self) -> Material:
        """The :class:`tce.material.Material` of this section."""
        return Material(**self.model_dump())


class PointLoadSection(_Strict):
    """``[[loads.point]]``: a force (kN) on a free block (``block``, ``at``) or on the top
    surface above a plan point (``on_top``); :class:`tce.core.loads.PointLoad`."""

    block: str | None = None
    at: Vector3 | None = None
    on_top: Vector2 | None = None
    force: Vector3
    scaled: bool = True


class DistributedLoadSection(_Strict):
    """``[[loads.distributed]]``: a pressure (kN/m^2 of plan area, downwards) over a plan
    rectangle; :class:`tce.core.loads.DistributedLoad`."""

    x: Vector2
    y: Vector2 | None = None
    pressure: float
    scaled: bool = True


class LoadsSection(_Strict):
    """``[loads]``: the load pattern (lateral directions in degrees, whether lambda multiplies
    the lateral pattern, point and distributed loads), load-path step and bisection tolerance."""

    alpha: float | list[float] = 0.0
    lateral: bool = True
    point: list[PointLoadSection] = Field(default_factory=list)
    distributed: list[DistributedLoadSection] = Field(default_factory=list)
    lambda_step: Positive = 0.02
    tolerance: Positive = 1e-6
    lambda_cap: Positive = 100.0

    @property
    def alphas(self) -> list[float]:
        """The directions as a list."""
        return [float(a) for a in (self.alpha if isinstance(self.alpha, list) else [self.alpha])]

    def pattern(self, alpha: float) -> LoadPattern:
        """The load pattern in direction ``alpha`` (raises :class:`tce.core.loads.LoadError`)."""
        return LoadPattern(
            alpha=alpha,
            lateral=self.lateral,
            point=[p.model_dump(exclude_none=True) for p in self.point],
            distributed=[d.model_dump(exclude_none=True) for d in self.distributed],
        )

    def path_settings(self) -> dict[str, float]:
        """``lambda_step``, ``tolerance``, ``lambda_cap``: how the load path runs."""
        return {"lambda_step": self.lambda_step, "tolerance": self.tolerance, "lambda_cap": self.lambda_cap}

    @field_validator("alpha")
    @classmethod
    def _some_alpha(cls, v: float | list[float]) -> float | list[float]:
        if isinstance(v, list) and not v:
            raise ValueError("give at least one direction")
        return v


class SweepSection(_Strict):
    """``[sweep]``: lists of values; the study runs the cartesian product."""

    friction: list[NonNegative] | None = None
    magnitude: list[float] | None = None
    inner_radius: list[Positive] | None = None
    thickness: list[Positive] | None = None
    depth: list[Positive] | None = None
    radius: list[Positive] | None = None
    load_x: list[float] | None = None

    def items(self) -> list[tuple[str, list[float]]]:
        """``(parameter, values)`` of the parameters swept, in declaration order."""
        return [(k, list(v)) for k, v in self if v is not None]


class StudyFile(_Strict):
    """The whole study file."""

    study: StudySection
    structure: Structure
    material: MaterialSection = MaterialSection()
    loads: LoadsSection = LoadsSection()
    sweep: SweepSection = SweepSection()
    scenarios: dict[str, dict[str, Vector6]] = Field(default_factory=lambda: {"none": {}})

    @field_validator("sweep")
    @classmethod
    def _no_empty_list(cls, v: SweepSection) -> SweepSection:
        for key, values in v.items():
            if not values:
                raise ValueError(f"sweep.{key} is an empty list: give at least one value or remove it")
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
        Validated ``[structure]`` and ``[material]`` sections with the swept values applied.
    loads : dict
        ``lambda_step``, ``tolerance``, ``lambda_cap``.
    """

    name: str
    settlement: str
    settlements: dict[str, list[float]]
    alpha: float
    pattern: dict[str, Any]
    params: dict[str, float]
    structure: dict[str, Any]
    material: dict[str, Any]
    loads: dict[str, float]

    @property
    def group(self) -> str:
        """Key of the analysis this scenario needs: scenarios with equal keys share one."""
        return json.dumps([self.structure, self.material], sort_keys=True)

    @property
    def key(self) -> str:
        """Everything that determines the answer, as canonical JSON (for resuming)."""
        key = [self.group, self.settlements, self.alpha, self.loads]
        if not self.loads_pattern.default:  # the paper's pattern keeps the keys of tce 0.1
            key.append(self.pattern)
        return json.dumps(key, sort_keys=True)

    @property
    def loads_pattern(self) -> LoadPattern:
        """The scenario's :class:`tce.core.loads.LoadPattern`."""
        return LoadPattern.from_dict(self.pattern)


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

    @property
    def name(self) -> str:
        """The study's name (``[study] name``)."""
        return self.spec.study.name

    @cached_property
    def swept(self) -> list[tuple[str, list[float]]]:
        """Every parameter that varies across scenarios, with its values (alpha first)."""
        axes = [("alpha", self.spec.loads.alphas)] + self.spec.sweep.items()
        return [(k, v) for k, v in axes if len(v) > 1 or k != "alpha"]

    def scenarios(self) -> list[Scenario]:
        """The cartesian product of settlement cases, directions and sweeps, in file order."""
        return list(self._expand())

    def _expand(self) -> Iterator[Scenario]:
        spec = self.spec
        axes = [("alpha", spec.loads.alphas)] + spec.sweep.items()
        names = [k for k, _ in axes]
        loads = spec.loads.path_settings()
        for case, motions in spec.scenarios.items():
            for values in itertools.product(*(v for _, v in axes)):
                p = dict(zip(names, (float(v) for v in values), strict=True))
                scale = p.get("magnitude", 1.0)
                label = "/".join(f"{k}={_fmt(p[k])}" for k, v in axes if len(v) > 1)
                yield Scenario(
                    name=f"{case}/{label}" if label else case,
                    settlement=case,
                    settlements={s: [scale * u for u in vec] for s, vec in motions.items()},
                    alpha=p["alpha"],
                    pattern=_pattern(spec.loads, p).to_dict(),
                    params=p,
                    structure=_with(spec.structure.model_dump(), p, GEOMETRY_SWEEPS),
                    material=_with(spec.material.model_dump(), p, ("friction",)),
                    loads=loads,
                )


def _pattern(section: LoadsSection, params: dict[str, float]) -> LoadPattern:
    """The load pattern of a scenario: direction ``alpha``, moved to ``load_x`` when swept."""
    pattern = section.pattern(params["alpha"])
    return pattern.moved(params["load_x"]) if "load_x" in params else pattern


def _fmt(value: float) -> str:
    """Short, exact-enough label of a swept value."""
    return f"{value:g}"


def _with(section: dict[str, Any], params: dict[str, float], keys: tuple[str, ...]) -> dict[str, Any]:
    """``section`` with the swept values of ``keys`` applied."""
    out = dict(section)
    out.update({k: params[k] for k in keys if k in params})
    return out


# ---------------------------------------------------------------------------- reading
_LISTS = (
    " ([ux, uy, uz, rx, ry, rz] in m and rad for a displacement, [x, y, z] for a point or a force, "
    "[x, y] for a plan point, [from, to] for a plan range)"
)
_HINTS = {
    "extra_forbidden": "remove it or correct its spelling (keys: docs/studies.md)",
    "missing": "add it",
    "greater_than": "use a value > {gt}",
    "greater_than_equal": "use a value >= {ge}",
    "less_than": "use a value < {lt}",
    "finite_number": "use a finite number (NaN and inf are not allowed)",
    "too_short": "give exactly {min_length} numbers" + _LISTS,
    "too_long": "give exactly {max_length} numbers" + _LISTS,
    "float_type": "write a number",
    "float_parsing": "write a number",
    "int_type": "write a whole number",
    "int_from_float": "write a whole number",
    "int_parsing": "write a whole number",
    "list_type": "write a list, e.g. [1, 2]",
    "dict_type": "write a table",
    "model_type": "write a table",
    "string_type": "write a quoted string",
    "string_pattern_mismatch": "use only letters, digits, '_', '.' and '-'",
    "string_too_short": "give a non-empty value",
    "union_tag_invalid": "use one of the structure types listed",
    "union_tag_not_found": "add type = \"semicircular_arch\" (or another structure type)",
    "literal_error": "use one of the values listed",
}


def _key(loc: tuple[Any, ...]) -> str:
    """Dotted TOML key of a pydantic location (drops the union tags pydantic inserts)."""
    parts: list[str] = []
    for item in loc:
        if isinstance(item, int):
            parts[-1] = f"{parts[-1]}[{item}]" if parts else f"[{item}]"
        elif item in ("float", "list[float]", "semicircular_arch", "dome", "file") or "[" in str(item):
            continue
        else:
            parts.append(str(item))
    return ".".join(parts) or "(top level)"


def _describe(path: Path, exc: ValidationError) -> str:
    """One line per problem: file, key, what is wrong, how to fix it."""
    lines, seen = [], set()
    for err in exc.errors():
        key = _key(err["loc"])
        if key in seen:  # a union reports each alternative: keep the first
            continue
        seen.add(key)
        hint = _HINTS.get(err["type"], "see docs/studies.md").format(**err.get("ctx", {}))
        got = "" if err["type"] in ("missing",) else f" (got {err.get('input')!r})"
        lines.append(f"{path}: {key}: {err['msg']}{got}; fix: {hint}")
    return "\n".join(lines)


def parse_study(text: str, path: Path | str = "<study>") -> Study:
    """Validate study TOML ``text`` (see :func:`load_study`; ``path`` is for messages)."""
    path = Path(path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise StudyError(f"{path}: not valid TOML: {exc}; fix: correct the syntax") from None
    try:
        spec = StudyFile.model_validate(data)
    except ValidationError as exc:
        raise StudyError(_describe(path, exc)) from None
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
    study = Study(path, text, spec)
    _check_scenarios(study)
    return study


def load_study(path: Path | str) -> Study:
    """Read and validate a study file; build each distinct structure once to check it.

    Raises
    ------
    StudyError
        The file is missing or unreadable, is not TOML, breaks the schema, describes a
        structure that cannot be built, or moves a support the structure does not have.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise StudyError(f"{path}: cannot read the study file ({exc}); fix: give a readable TOML file") from None
    return parse_study(text, path)


def build_structure(section: dict[str, Any]) -> Assembly:
    """The assembly of a validated ``[structure]`` section given as a plain dict."""
    return TypeAdapter(Structure).validate_python(section).build()


def build_material(section: dict[str, Any]) -> Material:
    """The material of a validated ``[material]`` section given as a plain dict."""
    return MaterialSection.model_validate(section).build()


def _check_scenarios(study: Study) -> None:
    """Build every distinct structure and material; check the supports each scenario moves
    and apply its loads to its structure."""
    checked: dict[str, Assembly] = {}
    for sc in study.scenarios():
        skey = json.dumps(sc.structure, sort_keys=True)
        if skey not in checked:
            try:
                checked[skey] = build_structure(sc.structure).validate()
            except (ValueError, OSError) as exc:
                swept = {k: v for k, v in sc.params.items() if k in GEOMETRY_SWEEPS}
                raise StudyError(
                    f"{study.path}: structure: cannot build it{f' with {swept}' if swept else ''}: {exc}; "
                    "fix: change the [structure] or [sweep] values"
                ) from None
        _check_loads(study, sc, checked[skey])
        try:
            build_material(sc.material)
        except (ValueError, ValidationError) as exc:
            raise StudyError(f"{study.path}: material: {exc}; fix: change the [material] values") from None
        supports = checked[skey].support_names
        unknown = sorted(set(sc.settlements) - set(supports))
        if unknown:
            raise StudyError(
                f"{study.path}: scenarios.{sc.settlement}.{unknown[0]}: the structure has no support "
                f"named {unknown[0]!r}; fix: use one of {list(supports)}"
            )
        if any(not math.isfinite(u) for v in sc.settlements.values() for u in v):
            raise StudyError(f"{study.path}: scenarios.{sc.settlement}: a displacement overflows; fix: smaller values")


def _check_loads(study: Study, sc: Scenario, assembly: Assembly) -> None:
    """Apply a scenario's loads to its structure; a load that cannot be applied is named."""
    pattern = sc.loads_pattern
    try:
        resolve(pattern, assembly)
    except LoadError as exc:
        # name load_x only for a load it moved
        moved = [f"point[{k}]." for k, p in enumerate(pattern.point) if p.scaled and p.on_top is not None]
        keys = GEOMETRY_SWEEPS + (("load_x",) if any(exc.key.startswith(m) for m in moved) else ())
        swept = {k: v for k, v in sc.params.items() if k in keys}
        where = f" (with {', '.join(f'sweep.{k} = {v:g}' for k, v in swept.items())})" if swept else ""
        err = exc.within("loads")
        raise StudyError(f"{study.path}: {err.key}: {err.problem}{where}; fix: {err.fix}") from None
