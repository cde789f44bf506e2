"""Studies: TOML files (``schema``), the parallel runner (``runner``) and results datasets
(``results``). Nothing here draws: the command line (:mod:`tce.cli`) composes running and drawing.

The schema's public names are re-exported here (the runner, which needs xarray and joblib,
is imported from :mod:`tce.study.runner`).
"""

from . import jobs as _jobs  # noqa: F401  (first: honours TCE_NO_DASK before anything imports xarray)
from .schema import Scenario, Study, StudyError, build_material, build_structure, load_study, parse_study

__all__ = ["Scenario", "Study", "StudyError", "build_material", "build_structure", "load_study", "parse_study"]
