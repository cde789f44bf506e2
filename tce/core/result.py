"""The shape every tce result shares (in the manner of :class:`scipy.optimize.OptimizeResult`).

Every answer tce computes, from one conic solve to a whole load path, is a frozen
dataclass deriving from :class:`Result`: it carries a ``status`` word, ``ok`` (whether the
numbers in it are an answer), a ``message`` saying what decided, the ``solver`` that ran,
and two honest times: ``solve_time`` (wall time inside the solver's solve calls) and
``wall_time`` (the whole call, from Python). Results hold arrays and plain values, never
the model or the assembly they came from.

Status words (``docs/conventions.md``): ``optimal`` (an answer that passed its residual
checks), ``infeasible`` (no admissible force state: the loads exceed the capacity),
``unbounded`` (the support motion is incompatible with the material, or no finite limit),
``numerical`` (the solver failed or its answer did not pass the checks). Analyses built on
solves use their own outcome words where the four do not fit (a load path ends in
``limit``, ``no_limit``, ...); each class says which.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from functools import cache
from typing import Any, ClassVar, TypeVar

from .clarabel_solver import SOLVER_NAME

__all__ = ["STATUSES", "Result"]

STATUSES = ("optimal", "infeasible", "unbounded", "numerical")

R = TypeVar("R", bound="Result")


@cache
def _field_names(cls: type) -> frozenset[str]:
    """The names of a result class's fields (computed once per class)."""
    return frozenset(f.name for f in fields(cls))


@dataclass(frozen=True, eq=False, kw_only=True)
class Result:
    """Fields every result has.

    Attributes
    ----------
    status : str
        What the computation established (see the subclass).
    message : str
        What decided the status (solver statuses, retries, notes).
    solver : str
        Solver name and version.
    solve_time : float
        Wall time spent in the solver's solve calls (s), summed over the solves made.
    wall_time : float
        Wall time of the whole call (s).
    """

    #: status words for which ``ok`` is True
    OK: ClassVar[tuple[str, ...]] = ("optimal",)

    status: str
    message: str = ""
    solver: str = SOLVER_NAME
    solve_time: float = 0.0
    wall_time: float = 0.0

    @property
    def ok(self) -> bool:
        """True when the result's numbers are an answer (``status`` in ``OK``)."""
        return self.status in self.OK

    @classmethod
    def of_fields(cls: type[R], values: dict[str, Any]) -> R:
        """The instance whose fields are ``values`` (every field named once, no defaults).

        The same object as ``cls(**values)`` without the frozen ``__init__``, which sets each
        field through ``object.__setattr__`` (about 8 us for a :class:`tce.core.solve.TCEResult`,
        a fifth of the load path's own time per solve).

        Raises
        ------
        TypeError
            When ``values`` does not name exactly the class's fields.
        """
        names = _field_names(cls)
        if values.keys() != names:
            raise TypeError(f"{cls.__name__}.of_fields: fields {sorted(names ^ values.keys())} missing or unknown")
        obj = object.__new__(cls)
        obj.__dict__.update(values)
        return obj
