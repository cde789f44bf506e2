"""Figures, interactive view and VTK export of a results dataset.

:func:`write_figures` writes what a study's ``[plots]`` table asks for (:mod:`tce.plot.output`);
the figure functions are in :mod:`tce.plot.figures` (matplotlib), the HTML view in
:mod:`tce.plot.view` (plotly.js), the ParaView files in :mod:`tce.plot.export` (meshio). Names
load their module on first use, so the view and the export do not import matplotlib.
"""

from __future__ import annotations

import importlib
from typing import Any

#: public name -> module that defines it
_PUBLIC = {
    "PlotSpec": "tce.plot.data",
    "plot_spec": "tce.plot.data",
    "base_figure": "tce.plot.figures",
    "mechanism_view": "tce.plot.figures",
    "states_figure": "tce.plot.figures",
    "summary_figure": "tce.plot.figures",
    "thrust_curves": "tce.plot.figures",
    "thrust_lines": "tce.plot.figures",
    "write_figures": "tce.plot.output",
    "view_html": "tce.plot.view",
    "export_vtk": "tce.plot.export",
}

__all__ = sorted(_PUBLIC)


def __getattr__(name: str) -> Any:
    """Load a public name's module on first use."""
    if name in _PUBLIC:
        value = getattr(importlib.import_module(_PUBLIC[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tce.plot' has no attribute {name!r}")
