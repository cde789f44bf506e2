"""The structure drawing of the calculation report: elevation, plan and end view to scale, with
the overall dimensions and the supports marked."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..plot import draw
from ..structures.assembly import Assembly

__all__ = ["structure_figure"]

#: (title, camera, screen axes as indices into x, y, z)
_VIEWS = (
    ("elevation (looking along +y)", draw.Camera.elevation(), (0, 2)),
    ("plan (from above)", draw.Camera.plan(), (0, 1)),
    ("end view (from +x)", draw.Camera(0.0, 0.0), (1, 2)),
)


def _dimension(ax: Axes, lo: float, hi: float, at: float, vertical: bool, text: str) -> None:
    """A dimension line from ``lo`` to ``hi`` (m) at ``at`` across, with its length."""
    xy = ((at, lo), (at, hi)) if vertical else ((lo, at), (hi, at))
    ax.annotate("", xy=xy[0], xytext=xy[1], arrowprops=dict(arrowstyle="<->", color="#333333", lw=0.8))
    mid = 0.5 * (lo + hi)
    ax.text(*((at, mid) if vertical else (mid, at)), text, fontsize=8, ha="center", va="center",
            rotation=90 if vertical else 0, bbox=dict(facecolor="white", edgecolor="none", pad=1.0))


def structure_figure(asm: Assembly) -> Figure:
    """Three orthographic views of ``asm`` (metres, equal scales), supports grey, with the
    overall dimensions (span x, depth y, height z) drawn as dimension lines.

    Returns
    -------
    Figure
        One row of three axes (gids ``"view:elevation"``, ``"view:plan"``, ``"view:end"``).
    """
    pts = np.vstack([b.shape.vertices for b in asm.blocks])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    ext = hi - lo
    size = float(ext.max()) or 1.0
    widths = [ext[i] + 0.4 * size for _, _, (i, _) in _VIEWS]
    fig = Figure(figsize=(11.0, 3.8), layout="constrained")
    axes = fig.subplots(1, 3, width_ratios=widths)
    for ax, (title, camera, (i, j)), gid in zip(axes, _VIEWS, ("elevation", "plan", "end")):
        draw.BlockArt.of(asm, camera).draw(ax)
        gap = 0.08 * size
        _dimension(ax, lo[i], hi[i], lo[j] - gap, False, f"{ext[i]:.3g} m")
        _dimension(ax, lo[j], hi[j], hi[i] + gap, True, f"{ext[j]:.3g} m")
        ax.set_xlim(lo[i] - 0.2 * size, hi[i] + 0.2 * size)
        ax.set_ylim(lo[j] - 0.18 * size, hi[j] + 0.1 * size)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel(f"{'xyz'[i]} (m)", fontsize=8)
        ax.set_ylabel(f"{'xyz'[j]} (m)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_gid(f"view:{gid}")
    return fig
