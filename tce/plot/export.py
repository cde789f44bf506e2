"""ParaView files of a results dataset (VTK XML through meshio).

:func:`export_vtk` writes, under ``<out>/``:

``blocks.vtu``
    The blocks as triangles (faces fan-triangulated); cell data ``block`` (index in the
    dataset's ``block`` order) and ``support`` (1 for supports). A geometry sweep adds
    ``blocks_<k>.vtu`` for structure k.
``<scenario>/forces_<k>.vtu``
    Step ``k`` (an optimal step, in lambda order): every interface vertex as a VTK vertex
    with point data ``force`` (kN, on block B, global frame) and ``fn`` (its component
    along the interface normal, kN).
``<scenario>/resultants_<k>.vtu``
    The pressure points of the interfaces that carry load, with point data
    ``resultant`` (kN, on block B, global frame), ``torque`` (kN m, about the normal) and
    ``interface`` (index in the dataset's ``interface`` order).
``<scenario>/mechanism.vtu``
    The blocks with point data ``displacement``: the collapse mechanism at lambda_max
    (unit amplitude, m; "Warp By Vector" shows it), when the scenario has one.
``<scenario>.pvd``
    A ParaView collection of the scenario's steps (vertex forces, resultants, its blocks)
    with ``timestep`` = lambda: the time slider walks the load path.

Units as in the dataset (m, kN, kN m). ``<scenario>`` is the scenario name made safe for
a file name.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from ..files import atomic_write
from ..structures.assembly import Assembly
from ..study.names import slug
from .data import assembly, geometry, optimal_steps, scenarios

__all__ = ["export_vtk"]


def _triangles(asm: Assembly, ds: xr.Dataset, displaced: Sequence[NDArray[np.float64]] | None = None):
    """Points, triangles and per-triangle block index of the blocks (optionally displaced)."""
    order = [str(b) for b in ds["block"].values] if "block" in ds.coords else list(asm.names)
    points, tris, block = [], [], []
    base = 0
    for k, b in enumerate(asm.blocks):
        v = np.asarray(b.shape.vertices if displaced is None else displaced[k], float)
        points.append(v)
        for face in b.shape.faces:
            for m in range(1, len(face) - 1):
                tris.append((base + face[0], base + face[m], base + face[m + 1]))
                block.append(order.index(b.name))
        base += len(v)
    return np.vstack(points), np.array(tris, dtype=np.int64), np.array(block, dtype=np.int64)


def _write(path: Path, points: NDArray, cells: list, point_data: dict | None = None,
           cell_data: dict | None = None) -> Path:
    import meshio

    with atomic_write(path) as tmp:
        meshio.write(tmp, meshio.Mesh(points, cells, point_data=point_data or {}, cell_data=cell_data or {}),
                     file_format="vtu")
    return path


def _vertices(n: int) -> list:
    return [("vertex", np.arange(n, dtype=np.int64)[:, None])]


def export_vtk(ds: xr.Dataset, out: Path | str, names: Sequence[str] | None = None) -> list[Path]:
    """Write the VTK files described in the module docstring.

    Parameters
    ----------
    ds : xarray.Dataset
        Results dataset with ``vertex_force`` and ``vertex_point``.
    out : path
        Folder (created).
    names : sequence of str, optional
        Scenarios to export (default: all).

    Returns the files written.

    Raises
    ------
    ValueError
        The dataset has no vertex forces (written by an older tce: run the study again).
    """
    missing = [v for v in ("vertex_force", "vertex_point", "vertex_interface") if v not in ds]
    if missing:
        raise ValueError(f"the dataset has no {missing[0]!r} (written by an older tce): run the study again")
    out = Path(out)
    written = []
    blocks: dict[int, tuple] = {}  # geometry -> (file name, points, triangles, block of each triangle)

    def blocks_of(s: str) -> tuple:
        g = geometry(ds, s)
        if g not in blocks:
            asm = assembly(ds, s)
            points, tris, block = _triangles(asm, ds)
            support = np.array([int(asm.blocks[asm.index[str(ds["block"].values[b])]].support) for b in block])
            name = "blocks.vtu" if g == 0 else f"blocks_{g}.vtu"
            written.append(_write(out / name, points, [("triangle", tris)],
                                  cell_data={"block": [block], "support": [support]}))
            blocks[g] = (name, points, tris, block)
        return blocks[g]

    for s in names or scenarios(ds):
        asm = assembly(ds, s)
        blocks_file, points, tris, block = blocks_of(s)
        sub = ds.sel(scenario=s)
        folder = out / slug(s)
        vp = np.asarray(sub["vertex_point"].transpose("vertex", "xyz").values, float)
        normal_of = {f"{asm.names[i.a]}|{asm.names[i.b]}": i.normal for i in asm.interfaces}
        vnormal = np.array([normal_of[str(n)] for n in ds["vertex_interface"].values]).reshape(-1, 3)
        vf = np.asarray(sub["vertex_force"].transpose("step", "vertex", "xyz").values, float)
        pp = np.asarray(sub["pressure_point"].transpose("step", "interface", "xyz").values, float)
        res = np.asarray(sub["resultant"].transpose("step", "interface", "xyz").values, float)
        tq = np.asarray(sub["torque"].transpose("step", "interface").values, float)
        lam = np.asarray(sub["lam"].values, float)
        entries = []
        for n, k in enumerate(optimal_steps(ds, s)):
            written.append(_write(folder / f"forces_{n:03d}.vtu", vp, _vertices(len(vp)),
                                  point_data={"force": vf[k], "fn": np.einsum("ij,ij->i", vf[k], vnormal)}))
            ok = np.flatnonzero(np.all(np.isfinite(pp[k]), axis=1) & np.all(np.isfinite(res[k]), axis=1))
            written.append(_write(folder / f"resultants_{n:03d}.vtu", pp[k][ok], _vertices(len(ok)),
                                  point_data={"resultant": res[k][ok], "torque": tq[k][ok],
                                              "interface": ok.astype(np.int64)}))
            entries += [(lam[k], 0, f"{slug(s)}/forces_{n:03d}.vtu"), (lam[k], 1, f"{slug(s)}/resultants_{n:03d}.vtu"),
                        (lam[k], 2, blocks_file)]
        if "mechanism" in ds:
            vel = np.asarray(sub["mechanism"].sel(block=list(asm.names)).transpose("block", "dof").values, float)
            if np.all(np.isfinite(vel)) and np.any(vel):
                cen = asm.centroids
                disp = [vel[k, :3] + np.cross(vel[k, 3:], np.asarray(b.shape.vertices) - cen[k])
                        for k, b in enumerate(asm.blocks)]
                written.append(_write(folder / "mechanism.vtu", points, [("triangle", tris)],
                                      point_data={"displacement": np.vstack(disp)}, cell_data={"block": [block]}))
        rows = "\n".join(f'    <DataSet timestep="{t:.12g}" part="{part}" file={quoteattr(f)}/>'
                         for t, part, f in entries)
        pvd = out / f"{slug(s)}.pvd"
        with atomic_write(pvd) as tmp:
            tmp.write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
                           f"{rows}\n  </Collection>\n</VTKFile>\n", encoding="utf-8")
        written.append(pvd)
    return written
