"""The sections of a study file that need none of the structures or solvers: the strict base
of every section and ``[plots]`` (docs/studies.md), importable by ``tce plot`` without
:mod:`tce.study.schema` (which builds the structures and loads)."""

from __future__ import annotations

import fnmatch
import math
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from .names import PLOT_KINDS

__all__ = ["MAX_DRAWN_SCENARIOS", "PlotsSection"]


class _Strict(BaseModel):
    # strict: a number must be written as a number (an int is accepted for a float), never
    # as a boolean or a string
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, frozen=True, strict=True)


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
        Figure kinds among :data:`tce.study.names.PLOT_KINDS`; default: every kind that applies except
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
