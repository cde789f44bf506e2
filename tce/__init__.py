"""tce: Total Complementary Energy analysis of masonry as rigid blocks in unilateral, frictional contact.

The method is that of *3D exploration of internal stresses due to lateral loads and foundation
movements in a semicircular arch* (the paper; ``docs/conventions.md``). Data flow one way, and
the subpackages follow it:

``tce.structures``  geometry, blocks, interfaces, supports; generators and file readers
``tce.core``        operators built once (model), conic problems, the Clarabel solves, limit analysis
``tce.analysis``    load path, minimum thickness, diagnosis
``tce.study``       study files, the parallel runner, results datasets
``tce.plot``        figures, interactive view and VTK export of a results dataset
``tce.report``      the calculation report (HTML and its PDF) of a results dataset
``tce.cli``         the ``tce`` command line: composes the layers above
``tce.quality``     developer tools beside the command line: benchmarks, the hard-case suite

The names most scripts need are importable from ``tce`` itself (loaded on first use, listed in
``__all__``), e.g. ``from tce import semicircular_arch, Analysis, Material, load_path``.
"""

from __future__ import annotations

from importlib import import_module as _import_module
from importlib.metadata import PackageNotFoundError as _PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("tce")
except _PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"

#: public name -> module that defines it
_PUBLIC = {
    "Analysis": "tce.core.analysis",
    "Material": "tce.core.material",
    "SolverOptions": "tce.core.solve",
    "LoadPattern": "tce.core.loads",
    "PointLoad": "tce.core.loads",
    "DistributedLoad": "tce.core.loads",
    "Vehicle": "tce.core.vehicles",
    "Fill": "tce.core.fill",
    "critical_position": "tce.analysis.critical",
    "adequacy_factor": "tce.analysis.assessment",
    "arch_bridge": "tce.structures.bridge",
    "build_model": "tce.core.model",
    "load_path": "tce.analysis.loadpath",
    "minimum_thickness": "tce.analysis.thickness",
    "arch_minimum_thickness": "tce.analysis.thickness",
    "diagnose": "tce.analysis.diagnose",
    "nonassociative_limit": "tce.analysis.nonassoc",
    "Assembly": "tce.structures.assembly",
    "AssemblyError": "tce.structures.assembly",
    "Block": "tce.structures.assembly",
    "Interface": "tce.structures.assembly",
    "semicircular_arch": "tce.structures.arch",
    "pointed_arch": "tce.structures.arch",
    "segmental_arch": "tce.structures.arch",
    "semicircular_arch_on_piers": "tce.structures.arch",
    "barrel_vault": "tce.structures.vault",
    "groin_vault": "tce.structures.vault",
    "hemispherical_dome": "tce.structures.dome",
    "load_assembly": "tce.structures.io",
    "save_assembly_json": "tce.structures.io",
    "Study": "tce.study.schema",
    "StudyError": "tce.study.schema",
    "load_study": "tce.study.schema",
    "run_study": "tce.study.runner",
}

__all__ = ["__version__", *_PUBLIC]

#: the subpackages (``dir(tce)`` lists them beside the public names)
_SUBPACKAGES = ("analysis", "cli", "core", "plot", "quality", "report", "structures", "study")


def __getattr__(name: str) -> object:
    """Load a public name's module on first use (``import tce`` stays light)."""
    if name in _PUBLIC:
        value = getattr(_import_module(_PUBLIC[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tce' has no attribute {name!r}")


def __dir__() -> list[str]:
    """The public names and the subpackages (not the module's own helpers)."""
    return sorted({*__all__, *_SUBPACKAGES})
