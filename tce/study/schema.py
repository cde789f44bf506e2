"""Study files: a TOML description of a structure, its material, its loads and its scenarios.

A study is read and validated as a whole before anything runs (:func:`load_study`): the
schema (pydantic, unknown keys forbidden, NaN and infinities refused), then the structure
is built once per distinct geometry and every scenario's support names are checked
against it. Every problem is reported as a :class:`StudyError` whose message names the
file, the key and the fix. The format is documented in ``docs/studies.md``.

A valid study expands (:meth:`Study.scenarios`) into the cartesian product of its
settlement cases, its lateral directions (``[loads] alpha``) and its ``[sweep]`` lists,
in that order, each expanded :class:`Scenario` carrying everything a worker needs.
"""

from __future__ import annotations

import fnmatch
import itertools
import json
import math
import tomllib
from collections.abc import Iterator
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError, field_validator

from ..structures.assembly import Assembly
from ..core.material import Material

__all__ = [
    "PlotsSection",
    "Scenario",
    "Study",
    "StudyError",
    "build_material",
    "build_structure",
    "load_study",
    "parse_study",
]

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


class LoadsSection(_Strict):
    """``[loads]``: lateral directions (degrees), load-path step and bisection tolerance."""

    alpha: float | list[float] = 0.0
    lambda_step: Positive = 0.02
    tolerance: Positive = 1e-6
    lambda_cap: Positive = 100.0

    @property
    def alphas(self) -> list[float]:
        """The directions as a list."""
        return [float(a) for a in (self.alpha if isinstance(self.alpha, list) else [self.alpha])]

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

    def items(self) -> list[tuple[str, list[float]]]:
        """``(parameter, values)`` of the parameters swept, in declaration order."""
        return [(k, list(v)) for k, v in self if v is not None]


#: figure kinds of ``[plots] kinds`` (docs/studies.md, "Figures")
PLOT_KINDS = ("thrust", "states", "thrust_lines", "base", "mechanism", "summary", "view")
#: studies with more scenarios draw per-scenario figures only for those ``[plots] scenarios`` names
MAX_DRAWN_SCENARIOS = 12


class PlotsSection(_Strict):
    """``[plots]``: the states, scenarios and figure kinds a study draws (docs/studies.md).

    Attributes
    ----------
    steps : list
        Load multipliers to draw (numbers >= 0) and ``"max"`` (lambda_max). A number that
        is not a step of the load path is solved, never interpolated.
    scenarios : list of str, optional
        Scenario names or shell patterns (``"outward/*"``) drawn in the per-scenario figures,
        the thrust curves and the interactive view. Default: every scenario when the study
        has at most :data:`MAX_DRAWN_SCENARIOS`, none otherwise (summary figures only).
    kinds : list of str, optional
        Figure kinds among :data:`PLOT_KINDS`; default: every kind that applies except
        ``"base"``.
    """

    steps: list[Any] = Field(default_factory=lambda: [0.0, "max"])
    scenarios: list[str] | None = None
    kinds: list[Literal[PLOT_KINDS]] | None = None  # type: ignore[valid-type]

    @field_validator("steps")
    @classmethod
    def _steps(cls, v: list[Any]) -> list[Any]:
        if not v:
            raise ValueError('give at least one load multiplier, e.g. [0.0, "max"]')
        out: list[Any] = []
        for item in v:
            ok = item == "max" or (
                isinstance(item, int | float) and not isinstance(item, bool) and math.isfinite(item) and item >= 0
            )
            if not ok:
                raise ValueError(f'{item!r} is neither a load multiplier >= 0 nor "max"')
            value = "max" if item == "max" else float(item)
            if value not in out:
                out.append(value)
        return out

    @field_validator("scenarios", "kinds")
    @classmethod
    def _not_empty(cls, v: list[str] | None) -> list[str] | None:
        if v is not None and not v:
            raise ValueError("give at least one entry or remove the key")
        return v

    @property
    def lambdas(self) -> list[float]:
        """The numeric load multipliers of :attr:`steps`."""
        return [s for s in self.steps if s != "max"]

    def unmatched(self, names: list[str]) -> list[str]:
        """Entries of :attr:`scenarios` that match none of ``names``."""
        return [p for p in self.scenarios or [] if not any(fnmatch.fnmatchcase(n, p) for n in names)]

    def select(self, names: list[str]) -> list[str]:
        """The scenarios of ``names`` (in that order) drawn per scenario (see :attr:`scenarios`)."""
        if self.scenarios is None:
            return list(names) if len(names) <= MAX_DRAWN_SCENARIOS else []
        return [n for n in names if any(fnmatch.fnmatchcase(n, p) for p in self.scenarios)]


class StudyFile(_Strict):
    """The whole study file."""

    study: StudySection
    structure: Structure
    material: MaterialSection = MaterialSection()
    loads: LoadsSection = LoadsSection()
    sweep: SweepSection = SweepSection()
    scenarios: dict[str, dict[str, Vector6]] = Field(default_factory=lambda: {"none": {}})
    plots: PlotsSection = PlotsSection()

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
    params : dict
        Values of the swept parameters (and ``alpha``, ``magnitude``) for this scenario.
    structure, material : dict
        Validated ``[structure]`` and ``[material]`` sections with the swept values applied.
    loads : dict
        ``lambda_step``, ``tolerance``, ``lambda_cap``.
    draw : tuple of float
        Load multipliers the study's figures draw for this scenario (``[plots] steps``,
        empty unless ``[plots]`` selects the scenario): solved after the load path when
        they are not steps of it. Not part of :attr:`key`: figures do not change answers.
    """

    name: str
    settlement: str
    settlements: dict[str, list[float]]
    alpha: float
    params: dict[str, float]
    structure: dict[str, Any]
    material: dict[str, Any]
    loads: dict[str, float]
    draw: tuple[float, ...] = ()

    @property
    def group(self) -> str:
        """Key of the analysis this scenario needs: scenarios with equal keys share one."""
        return json.dumps([self.structure, self.material], sort_keys=True)

    @property
    def key(self) -> str:
        """Everything that determines the answer, as canonical JSON (for resuming)."""
        return json.dumps(
            [self.group, self.settlements, self.alpha, self.loads], sort_keys=True
        )


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
        out = list(self._expand())
        plots = self.spec.plots
        drawn = set(plots.select([sc.name for sc in out]))
        lams = tuple(plots.lambdas)
        return [replace(sc, draw=lams) if lams and sc.name in drawn else sc for sc in out]

    def _expand(self) -> Iterator[Scenario]:
        spec = self.spec
        axes = [("alpha", spec.loads.alphas)] + spec.sweep.items()
        names = [k for k, _ in axes]
        loads = spec.loads.model_dump(exclude={"alpha"})
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
                    params=p,
                    structure=_with(spec.structure.model_dump(), p, GEOMETRY_SWEEPS),
                    material=_with(spec.material.model_dump(), p, ("friction",)),
                    loads=loads,
                )


def _fmt(value: float) -> str:
    """Short, exact-enough label of a swept value."""
    return f"{value:g}"


def _with(section: dict[str, Any], params: dict[str, float], keys: tuple[str, ...]) -> dict[str, Any]:
    """``section`` with the swept values of ``keys`` applied."""
    out = dict(section)
    out.update({k: params[k] for k in keys if k in params})
    return out


# ---------------------------------------------------------------------------- reading
_HINTS = {
    "extra_forbidden": "remove it or correct its spelling (keys: docs/studies.md)",
    "missing": "add it",
    "greater_than": "use a value > {gt}",
    "greater_than_equal": "use a value >= {ge}",
    "less_than": "use a value < {lt}",
    "finite_number": "use a finite number (NaN and inf are not allowed)",
    "too_short": "give exactly 6 numbers [ux, uy, uz, rx, ry, rz] (m, rad)",
    "too_long": "give exactly 6 numbers [ux, uy, uz, rx, ry, rz] (m, rad)",
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
    study = Study(path, text, spec)
    _check_scenarios(study)
    _check_plots(study)
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
    """Build every distinct structure and material; check the supports each scenario moves."""
    checked: dict[str, tuple[str, ...]] = {}
    for sc in study.scenarios():
        skey = json.dumps(sc.structure, sort_keys=True)
        if skey not in checked:
            try:
                checked[skey] = build_structure(sc.structure).validate().support_names
            except (ValueError, OSError) as exc:
                swept = {k: v for k, v in sc.params.items() if k in GEOMETRY_SWEEPS}
                raise StudyError(
                    f"{study.path}: structure: cannot build it{f' with {swept}' if swept else ''}: {exc}; "
                    "fix: change the [structure] or [sweep] values"
                ) from None
        try:
            build_material(sc.material)
        except (ValueError, ValidationError) as exc:
            raise StudyError(f"{study.path}: material: {exc}; fix: change the [material] values") from None
        unknown = sorted(set(sc.settlements) - set(checked[skey]))
        if unknown:
            raise StudyError(
                f"{study.path}: scenarios.{sc.settlement}.{unknown[0]}: the structure has no support "
                f"named {unknown[0]!r}; fix: use one of {list(checked[skey])}"
            )
        if any(not math.isfinite(u) for v in sc.settlements.values() for u in v):
            raise StudyError(f"{study.path}: scenarios.{sc.settlement}: a displacement overflows; fix: smaller values")


def _check_plots(study: Study) -> None:
    """Every ``[plots] scenarios`` entry names (or matches) a scenario of the study."""
    names = [sc.name for sc in study._expand()]
    for entry in study.spec.plots.unmatched(names):
        k = (study.spec.plots.scenarios or []).index(entry)
        raise StudyError(
            f"{study.path}: plots.scenarios[{k}]: no scenario named {entry!r}; "
            f"fix: use one of {names[:8]}{' ...' if len(names) > 8 else ''} (or a pattern such as 'outward/*')"
        )
