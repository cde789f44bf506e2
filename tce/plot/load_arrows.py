"""Arrows of the declared point and distributed loads of a scenario (``load_point``,
``load_force``, ``load_scaled`` of a results dataset, ``docs/results.md``).

The figures (:mod:`tce.plot.figures`) and the view (:mod:`tce.plot.view`) draw each arrow
ending at its point of application (it pushes on the block), to the resultants' scale and
with the force of the drawn step (a live load times lambda).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from .data import value

__all__ = ["LOAD_COLOUR", "declared_loads"]

LOAD_COLOUR = "#009E73"  # Okabe-Ito bluish green: apart from resultants (red) and hinges (blue)


def declared_loads(ds: xr.Dataset, scenario: str) -> tuple[NDArray, NDArray, NDArray] | None:
    """Points (k, 3) m, forces (k, 3) kN at lambda = 1 and live flags (k,) of a scenario's
    loads (padding dropped); None when the dataset has none."""
    if "load_point" not in ds:
        return None
    p = np.asarray(value(ds, "load_point", scenario, ["load", "xyz"]), dtype=float)
    f = np.asarray(value(ds, "load_force", scenario, ["load", "xyz"]), dtype=float)
    live = np.asarray(value(ds, "load_scaled", scenario), dtype=float)
    ok = np.all(np.isfinite(p), axis=1) & np.all(np.isfinite(f), axis=1)
    return (p[ok], f[ok], live[ok] > 0.5) if ok.any() else None
