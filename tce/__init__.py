"""tce: Total Complementary Energy analysis of masonry as rigid blocks in unilateral, frictional contact.

The method is that of *3D exploration of internal stresses due to lateral loads and foundation
movements in a semicircular arch* (the paper; ``docs/conventions.md``). Data flow one way, and
the subpackages follow it:

``tce.structures``  geometry, blocks, interfaces, supports; generators and file readers
``tce.core``        operators built once (model), conic problems, the Clarabel solves, limit analysis
``tce.analysis``    load path, minimum thickness, diagnosis
``tce.study``       study files, the parallel runner, results datasets, the command line
``tce.plot``        figures of a results dataset
``tce.quality``     developer tools: benchmarks, the hard-case suite and its report

The names most scripts need are importable from ``tce`` itself (loaded on first use), e.g.
``from tce import semicircular_arch, Analysis, Material, load_path``. The module paths of
tce 0.1 (``tce.arch``, ``tce.material``, ``tce.loadpath``, ...) still import: they are the
modules of their new homes.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
from importlib.metadata import PackageNotFoundError, version
from types import ModuleType
from typing import Any

try:
    __version__ = version("tce")
except PackageNotFoundError:  # running from a source tree that is not installed
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
    "load_study": "tce.study.schema",
    "run_study": "tce.study.runner",
}

#: module paths of tce 0.1 -> where the module lives now
_MOVED = {
    "tce.arch": "tce.structures.arch",
    "tce.assembly": "tce.structures.assembly",
    "tce.contacts": "tce.structures.contacts",
    "tce.dome": "tce.structures.dome",
    "tce.geometry": "tce.structures.geometry",
    "tce.io": "tce.structures.io",
    "tce.material": "tce.core.material",
    "tce.model": "tce.core.model",
    "tce.solve": "tce.core.solve",
    "tce.limit": "tce.core.limit",
    "tce.loadpath": "tce.analysis.loadpath",
    "tce.thickness": "tce.analysis.thickness",
    "tce.diagnose": "tce.analysis.diagnose",
    "tce.runner": "tce.study.runner",
    "tce.results": "tce.study.results",
    "tce.cli": "tce.study.cli",
}

__all__ = ["__version__", *_PUBLIC]


def __getattr__(name: str) -> Any:
    """Load a public name's module on first use (``import tce`` stays light)."""
    if name in _PUBLIC:
        value = getattr(importlib.import_module(_PUBLIC[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tce' has no attribute {name!r}")


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Resolve a tce 0.1 module path to the module at its new home (the same module object)."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> Any:
        if fullname in _MOVED:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec: Any) -> ModuleType:
        return importlib.import_module(_MOVED[spec.name])

    def exec_module(self, module: ModuleType) -> None:
        """Nothing to run: the module was executed at its new home."""


if not any(isinstance(f, _MovedModules) for f in sys.meta_path):
    sys.meta_path.append(_MovedModules())
