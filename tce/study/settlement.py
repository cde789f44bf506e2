"""The finite-settlement variables of a scenario's dataset (``[settlement_path]``, ``docs/results.md``).

:func:`settlement_vars` runs :func:`tce.analysis.settlement_path.settlement_path` on a
scenario's settlement vectors and returns its variables on a ``settlement_step`` dimension,
whose ``settlement_magnitude`` coordinate holds the magnitudes (multiples of the scenario's
settlement vectors), merged into the scenario's load-path dataset by the runner.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..analysis.settlement_path import SettlementPathResult, settlement_path
from ..core.material import Material
from ..core.model import EZ
from ..structures.assembly import Assembly
from .schema import Scenario

__all__ = ["NO_MOTION", "settlement_vars"]

#: outcome of a scenario that moves no support (nothing to follow)
NO_MOTION = "no_motion"


def _wrenches(r: SettlementPathResult) -> np.ndarray:
    """Reactions ``(k, n_supports, 6)`` in the global frame from the path's in-plane ones."""
    e, m = r.plane.e, r.plane.m
    rx, rz, mo = r.reactions[..., 0], r.reactions[..., 1], r.reactions[..., 2]
    force = rx[..., None] * e + rz[..., None] * EZ
    return np.concatenate([force, -mo[..., None] * m], axis=-1)


def _displacements(r: SettlementPathResult) -> np.ndarray:
    """Block displacements ``(k, n_blocks, 6)``: ``(ux, uy, uz)`` of the centroid and the
    rotation vector ``(rx, ry, rz)``, from the reference placement."""
    e, m = r.plane.e, r.plane.m
    p = r.placements
    return np.concatenate([p[..., :1] * e + p[..., 1:2] * EZ, -p[..., 2:3] * m], axis=-1)


def _sequence(r: SettlementPathResult, assembly: Assembly) -> str:
    names = assembly.names
    return "; ".join(
        f"s={s:.6g}: {names[assembly.interfaces[k].a]}|{names[assembly.interfaces[k].b]} {event}"
        for s, k, event in r.hinge_sequence
    )


def settlement_vars(sc: Scenario, assembly: Assembly, material: Material) -> xr.Dataset:
    """The ``settlement_*`` variables of scenario ``sc`` (its ``settlement_path`` settings)."""
    opts = sc.settlement_path or {}
    moves = any(any(u != 0 for u in v) for v in sc.settlements.values())
    if not moves:
        scalars = {"settlement_capacity": np.nan, "settlement_upper": np.nan, "settlement_n_solves": 0}
        text = {"settlement_outcome": NO_MOTION, "settlement_message": "the scenario moves no support",
                "settlement_hinge_sequence": ""}
        data = {k: (("scenario",), np.asarray([v])) for k, v in scalars.items()}
        data |= {k: (("scenario",), np.asarray([v], dtype=object)) for k, v in text.items()}
        return xr.Dataset(data)
    r = settlement_path(
        assembly,
        sc.settlements,
        material,
        increment=opts["increment"],
        s_max=opts["s_max"],
        atol=opts.get("tolerance"),
        lam=bool(opts.get("lam")),
        alpha=sc.alpha,
    )
    itf = len(assembly.interfaces)
    rotating = np.zeros((len(r.magnitudes), itf))  # float: padded with NaN when merged
    for i, h in enumerate(r.hinges):
        rotating[i, h] = 1
    k = np.arange(len(r.magnitudes))
    dims = ("scenario", "settlement_step")
    data = {
        "settlement_capacity": (("scenario",), [r.capacity]),
        "settlement_upper": (("scenario",), [r.upper]),
        "settlement_outcome": (("scenario",), np.asarray([r.status], dtype=object)),
        "settlement_message": (("scenario",), np.asarray([r.message], dtype=object)),
        "settlement_hinge_sequence": (("scenario",), np.asarray([_sequence(r, assembly)], dtype=object)),
        "settlement_n_solves": (("scenario",), [r.n_solves]),
        "settlement_reaction": (dims + ("support", "component"), _wrenches(r)[None]),
        "settlement_lambda_max": (dims, r.lambda_max[None]),
        "settlement_hinge": (dims + ("interface",), rotating[None]),
        "settlement_open": (dims + ("interface",), r.open_ends.sum(axis=2)[None].astype(float)),
        "settlement_displacement": (dims + ("block", "dof"), _displacements(r)[None]),
    }
    coords = {"settlement_step": k, "settlement_magnitude": (dims, r.magnitudes[None])}
    return xr.Dataset(data, coords=coords)
