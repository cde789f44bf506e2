"""Studies of the battery: a scene written as a study file, run by tce's runner.

:func:`study_text` writes the TOML of a study (a generator type, or a block file written
beside it for a transformed structure), :func:`run` runs it and returns the results
dataset without what differs between runs (timings, the creation date).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.structures.assembly import Assembly
from tce.structures.io import save_assembly_json
from tce.study import runner
from tce.study.results import TIMING
from tce.study.schema import parse_study

#: the [structure] section of each structure of ``cases.BUILDERS`` (the same parameters)
SECTIONS: dict[str, dict[str, Any]] = {
    "semicircular_arch": {"type": "semicircular_arch", "voussoirs": 8},
    "ring_arch": {"type": "semicircular_arch", "thickness": 0.3, "voussoirs": 5, "rings": 2, "stagger": True},
    "pointed_arch": {"type": "pointed_arch", "voussoirs": 8},
    "segmental_arch": {"type": "segmental_arch", "voussoirs": 6},
    "arch_on_piers": {"type": "arch_on_piers", "voussoirs": 8, "pier_height": 0.6},
    "barrel_vault": {"type": "barrel_vault", "voussoirs": 6, "courses": 2, "depth": 0.5, "bond": "running"},
    "groin_vault": {"type": "groin_vault", "voussoirs": 4},
    "dome": {"type": "dome", "radius": 2.0, "thickness": 0.3, "sectors": 6, "courses": 3},
}


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        assert math.isfinite(v)
        return repr(float(v) + 0.0)  # -0.0 -> 0.0
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):  # an inline table
        return "{ " + ", ".join(f"{k} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(v)


def _table(name: str, items: dict[str, Any]) -> str:
    return f"[{name}]\n" + "".join(f"{k} = {_value(v)}\n" for k, v in items.items()) + "\n"


def material_section(m: Material) -> dict[str, Any]:
    """``[material]`` of a material (its keys that are not the defaults)."""
    out: dict[str, Any] = {}
    for key, default in (("friction", None), ("normal_stiffness", None), ("shear_stiffness", None), ("cohesion", 0.0),
                         ("tensile_strength", 0.0), ("compressive_strength", None), ("flow", "associative")):
        v = getattr(m, key)
        if v != default:
            out[key] = v
    return out


def study_text(
    name: str,
    structure: dict[str, Any],
    material: Material,
    pattern: LoadPattern,
    scenarios: dict[str, dict[str, list[float]]],
    loads: dict[str, Any] | None = None,
    sweep: dict[str, list[float]] | None = None,
    alphas: list[float] | None = None,
) -> str:
    """The TOML text of a study. ``loads`` adds load-path settings to ``[loads]``;
    ``alphas`` replaces the pattern's single direction."""
    text = _table("study", {"name": name}) + _table("structure", structure) + _table("material", material_section(material))
    head = {"alpha": alphas if alphas is not None else pattern.alpha, "lateral": pattern.lateral, **(loads or {})}
    text += _table("loads", head)
    for p in pattern.point:
        text += _table("[loads.point]", p.to_dict())
    for d in pattern.distributed:
        text += _table("[loads.distributed]", d.to_dict())
    if sweep:
        text += _table("sweep", sweep)
    for case, motions in scenarios.items():
        text += _table(f"scenarios.{case}", motions)
    return text


def file_section(asm: Assembly, folder: Path, name: str) -> dict[str, Any]:
    """``[structure]`` of a block file holding ``asm`` (written into ``folder``; its
    absolute path, so that studies in other folders can use it)."""
    path = save_assembly_json(asm, folder / f"{name}.json").resolve()
    return {"type": "file", "path": str(path), "supports": list(asm.support_names)}


def run(text: str, folder: Path, **options: Any) -> xr.Dataset:
    """Run the study ``text`` (written to ``folder/<study name>.toml``, results under
    ``folder/results``; in-process and without figures unless ``options`` say otherwise)
    and return its dataset without the timings and the creation date."""
    study = parse_study(text, folder / "study.toml")
    options = {"jobs": 1, "plots": False, **options}
    report = runner.run_study(study, folder / "results", **options)
    ds = xr.load_dataset(report.results).drop_vars(list(TIMING))
    ds.attrs.pop("created")
    return ds


def runners_agree(text: str, folder: Path) -> xr.Dataset:
    """Run the study ``text`` in-process, with 2 workers, and again after one of its scenario
    files is removed (resumed); assert the three datasets identical and return the first."""
    reference = run(text, folder / "in_process")
    xr.testing.assert_identical(run(text, folder / "jobs2", jobs=2), reference)
    out = folder / "resumed"
    run(text, out)
    name = parse_study(text, out / "study.toml").name
    (first, *_) = sorted((out / "results" / name / "scenarios").glob("*.nc"))
    first.unlink()
    xr.testing.assert_identical(run(text, out), reference)
    return reference


def total_reaction(ds: xr.Dataset, about: np.ndarray) -> np.ndarray:
    """Sum of the reactions per scenario and step, moments about ``about``: (scenario, step, 6)."""
    r = ds["reaction"].values  # scenario, step, support, component
    c = ds["block_centroid"].sel(block=ds["support"].values).values - about  # support, xyz
    moments = r[..., 3:] + np.cross(c, r[..., :3])
    return np.concatenate([r[..., :3].sum(-2), moments.sum(-2)], axis=-1)
