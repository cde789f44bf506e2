"""The shape every tce result shares (in the manner of :class:`scipy.optimize.OptimizeResult`).

Every answer tce computes, from one conic solve to a whole load path, is a frozen
dataclass deriving from :class:`Result`: it carries a ``status`` word, ``ok`` (whether the
numbers in it are an answer), a ``message`` saying what decided, the ``solver`` that ran,
and two times: ``solve_time`` (wall time inside the solver's solve calls) and
``wall_time`` (the whole call, from Python). Results hold arrays and plain values, never
the model or the assembly they came from.

Every result shows itself in one line (``repr``: the status and the class's :attr:`Result.HEADLINE`
numbers, under 400 characters), as a small table in a notebook (``_repr_html_``) and as a
labelled :class:`xarray.Dataset` (:meth:`Result.to_xarray`). Subclasses are declared with
``repr=False`` so that the dataclass does not replace that repr with one of every field.

Status words (``docs/conventions.md``): ``optimal`` (an answer that passed its residual
checks), ``infeasible`` (no admissible force state: the loads exceed the capacity),
``unbounded`` (the support motion is incompatible with the material, or no finite limit),
``numerical`` (the solver failed or its answer did not pass the checks). Analyses built on
solves use their own outcome words where the four do not fit (a load path ends in
``limit``, ``no_limit``, ...); each class says which.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from .. import display
from .clarabel_solver import SOLVER_NAME

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["DOFS", "STATUSES", "WRENCH_COMPONENTS", "XYZ", "Result"]

STATUSES = ("optimal", "infeasible", "unbounded", "numerical")
#: labels of a support wrench's components (kN, kN m) and of a rigid-body velocity's
WRENCH_COMPONENTS = ("Fx", "Fy", "Fz", "Mx", "My", "Mz")
DOFS = ("vx", "vy", "vz", "wx", "wy", "wz")
XYZ = ("x", "y", "z")

@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
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

    #: fields or properties that the repr, the HTML table and :meth:`to_xarray` show after the status
    HEADLINE: ClassVar[tuple[str, ...]] = ()

    def headline(self) -> dict[str, Any]:
        """The headline values ``{name: value}`` of :attr:`HEADLINE`."""
        return {k: getattr(self, k) for k in self.HEADLINE}

    def __repr__(self) -> str:
        fields = self.headline()
        if self.message and (not self.ok or not self.HEADLINE):  # a failure says why; a diagnosis is its message
            fields["message"] = self.message if len(self.message) <= 120 else self.message[:117] + "..."
        return display.call(type(self).__name__, fields, head=repr(self.status))

    def _repr_html_(self) -> str:
        rows = [*self.headline().items(), ("message", self.message), ("solver", self.solver),
                ("wall time", f"{self.wall_time:.3g} s")]
        return display.html_table(type(self).__name__, rows, status=self.status)

    def _arrays(self) -> tuple[dict[str, tuple], dict[str, Any]]:
        """Labelled arrays of :meth:`to_xarray` beyond the headline: ``(data_vars, coords)``."""
        return {}, {}

    def to_xarray(self) -> xr.Dataset:
        """The result as a labelled dataset.

        Returns
        -------
        xarray.Dataset
            The numeric :attr:`HEADLINE` values as 0-d variables, the subclass's labelled arrays
            (e.g. ``reaction`` with dims ``(support, component)``), and ``status``, ``ok``,
            ``message``, ``solver``, ``solve_time``, ``wall_time`` and the text headline
            values as attrs. Names, dims and units follow the study results (``docs/results.md``).
        """
        import xarray as xr

        data: dict[str, tuple] = {}
        attrs: dict[str, Any] = {"status": self.status, "ok": int(self.ok), "message": self.message,
                                 "solver": self.solver, "solve_time": self.solve_time, "wall_time": self.wall_time}
        for k, v in self.headline().items():
            if isinstance(v, (bool, np.bool_)) or v is None or isinstance(v, str):
                attrs[k] = "" if v is None else str(v) if isinstance(v, str) else int(v)
            elif isinstance(v, (int, float, np.number)):
                data[k] = ((), v)
        arrays, coords = self._arrays()
        data.update(arrays)
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @property
    def ok(self) -> bool:
        """True when the result's numbers are an answer (``status`` in ``OK``)."""
        return self.status in self.OK
