"""Run a study file and read its results dataset.

A study (TOML, docs/studies.md) lists a structure, a material, load directions and settlement
scenarios; ``run_study`` solves every scenario's load path and writes one labelled xarray
dataset (docs/results.md). Run: ``python examples/04_study_file.py [study.toml] [out]``
(default: ``examples/04_study.toml`` into ``results/``); the same as ``tce run``.
"""

import sys
from pathlib import Path

import xarray as xr

from tce import load_study, run_study

study_file = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).with_name("04_study.toml")
out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path("results")
report = run_study(load_study(study_file), out, jobs=1, plots=False)
print(f"{len(report.solved)} scenarios solved, {len(report.reused)} reused: {report.results}")

with xr.open_dataset(report.results) as ds:
    print(ds[["lambda_max", "lambda_direct", "outcome", "model"]].to_dataframe().to_string())
    right = ds["reaction"].sel(support="right", component="Fx").isel(step=0)
    print("thrust of the right support at lambda = 0 (kN):")
    print(right.to_series().to_string())
