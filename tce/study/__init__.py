"""Studies: TOML files (``schema``), the parallel runner (``runner``) and results datasets
(``results``). Nothing here draws: the command line (:mod:`tce.cli`) composes running and drawing.

The schema's public names are re-exported here, imported on first use (so that the ``tce``
program handles Ctrl-C before numpy and pydantic are imported); the runner is imported from
:mod:`tce.study.runner`.
"""

from typing import Any

__all__ = ["Scenario", "Study", "StudyError", "build_material", "build_structure", "load_study", "parse_study"]


def __getattr__(name: str) -> Any:
    if name in __all__:
        from . import schema

        return getattr(schema, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
