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
from ..structures.assembly import Assembly
from .schema import Scenario

__all__ = ["NO_MOTION", "settlement_vars"]

#: outcome of a scenario that moves no support (nothing to follow)
NO_MOTION = "no_motion"


def _sequence(r: SettlementPathResult, assembly: Assembly) -> str:
    names = assembly.names
    return "; ".join(
        f"s={s:.6g}: {names[assembly.interfaces[k].a]}|{names[assembly.interfaces[k].b]} {event}"
        for s, k, event in r.hinge_sequence
    )


def settlement_vars(sc: Scenario, assembly: Assembly, material: Material) -> xr.Dataset:
    """The ``settlement_*`` variables of scenario ``sc`` (its ``settlement_path`` settings)."""
    opts = sc.settlement_path or {}
    nb, ni, ns = len(assembly.blocks), len(assembly.interfaces), len(assembly.support_names)
    if not any(any(u != 0 for u in v) for v in sc.settlements.values()):
        # nothing to follow: one step of NaN, so that the scenario merges with the others
        scalars = dict(capacity=np.nan, upper=np.nan, n_solves=0, outcome=NO_MOTION,
                       message="the scenario moves no support", hinge_sequence="")
        per_step = dict(magnitudes=np.full(1, np.nan), reaction=np.full((1, ns, 6), np.nan),
                        lambda_max=np.full(1, np.nan), hinge=np.full((1, ni), np.nan),
                        open=np.full((1, ni), np.nan), displacement=np.full((1, nb, 6), np.nan),
                        hinge_point=np.full((1, ni, 3), np.nan))
    else:
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
        rotating = np.zeros((len(r.magnitudes), ni))  # float: padded with NaN when merged
        for i, h in enumerate(r.hinges):
            rotating[i, h] = 1
        scalars = dict(capacity=r.capacity, upper=r.upper, n_solves=r.n_solves, outcome=r.status,
                       message=r.message, hinge_sequence=_sequence(r, assembly))
        per_step = dict(magnitudes=r.magnitudes, reaction=r.wrenches(), lambda_max=r.lambda_max,
                        hinge=rotating, open=r.open_ends.sum(axis=2).astype(float),
                        displacement=r.displacements(), hinge_point=r.hinge_points)
    dims = ("scenario", "settlement_step")
    data = {
        f"settlement_{k}": (("scenario",), np.asarray([v], dtype=object if isinstance(v, str) else None))
        for k, v in scalars.items()
    }
    data |= {
        "settlement_reaction": (dims + ("support", "component"), per_step["reaction"][None]),
        "settlement_lambda_max": (dims, per_step["lambda_max"][None]),
        "settlement_hinge": (dims + ("interface",), per_step["hinge"][None]),
        "settlement_open": (dims + ("interface",), per_step["open"][None]),
        "settlement_displacement": (dims + ("block", "dof"), per_step["displacement"][None]),
        "settlement_hinge_point": (dims + ("interface", "xyz"), per_step["hinge_point"][None]),
    }
    mags = per_step["magnitudes"]
    coords = {"settlement_step": np.arange(len(mags)), "settlement_magnitude": (dims, mags[None])}
    return xr.Dataset(data, coords=coords)
