"""Figures and axes made before they are needed (issue 24): a figure drawer makes them while it
waits for the run's results, and the figure functions take them instead of making their own.

Making the axes of a figure and the ticks they draw is about a third of the CPU of drawing
Fig. 9's files with matplotlib 3.11 (an axes makes four ticks as it is created, 14 ms of
matplotlib's Python for a panel with both axes, and the ticks it draws are made at draw time,
each with three lines and two texts). None of it depends on the results: :func:`make` makes
an axes whose ticks exist, in a spare figure (added to the figure, then taken off it), and
:func:`figure` and :func:`axes` hand them out: the figure resized, each axes put back at its
place. The files are the same, byte for byte (``tests/faults/test_drawers.py``). Where
nothing was made (the run's own process, ``tce plot``), they make a new figure and axes, as
``Figure(figsize=...)`` and ``fig.add_axes(rect)`` do.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["AXES", "TICKS", "axes", "figure", "make", "ready"]

#: axes made with each spare figure (Fig. 9's thrust curves draw four panels)
AXES = 4
#: ticks made on each axis of a spare axes (the paper's panels draw 4-7 major ticks)
TICKS = 7

_FIGURES: list[Figure] = []
_AXES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # spare figure -> its spare axes


def make() -> None:
    """Make one spare axes, with :data:`TICKS` major ticks on each axis, in the last spare
    figure, or in a new one when it has :data:`AXES` already (one step: 10-15 ms)."""
    from matplotlib.figure import Figure

    if not _FIGURES or len(_AXES[_FIGURES[-1]]) >= AXES:
        fig = Figure()
        _FIGURES.append(fig)
        _AXES[fig] = []
    fig = _FIGURES[-1]
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    for axis in (ax.xaxis, ax.yaxis):
        axis.get_major_ticks(TICKS)
    fig.delaxes(ax)  # kept, with its ticks, until axes() puts it back
    _AXES[fig].append(ax)


def ready() -> int:
    """Spare axes left (in every spare figure)."""
    return sum(len(_AXES[fig]) for fig in _FIGURES)


def figure(figsize: Sequence[float]) -> Figure:
    """A figure of ``figsize`` inches: a spare one resized, or a new one."""
    if not _FIGURES:
        from matplotlib.figure import Figure

        return Figure(figsize=tuple(figsize))
    fig = _FIGURES.pop()
    fig.set_size_inches(*figsize)
    return fig


def axes(fig: Figure, rect: Sequence[float]) -> Axes:
    """An axes of ``fig`` at ``rect`` (figure fraction): a spare one of ``fig`` put back, or a new one."""
    spare = _AXES.get(fig)
    if not spare:
        return fig.add_axes(tuple(rect))
    ax = spare.pop(0)
    fig.add_axes(ax)
    ax.set_position(tuple(rect))
    ax.set_in_layout(True)  # set_position takes it out of layouts; fig.add_axes(rect) leaves it in
    return ax
