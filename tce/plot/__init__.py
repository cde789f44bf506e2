"""Figures of a results dataset (:mod:`tce.plot.figures`)."""

from .figures import assembly_view, figure_sheet, mechanism_view, thrust_curves, thrust_line, write_figures

__all__ = ["assembly_view", "figure_sheet", "mechanism_view", "thrust_curves", "thrust_line", "write_figures"]
