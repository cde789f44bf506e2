"""Interface resultants from vertex forces: resultant force, pressure point, torque about the normal.

Conventions (``docs/conventions.md``): forces act on block B of each interface (the block the normal
points into); the pressure point is where the resultant of the normal vertex forces meets
the interface plane, ``p = sum(fn_j x_j) / sum(fn_j)``; the torque is the moment of all
vertex forces about the pressure point, component along the normal (kN m).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .model import InterfaceMap, Model

__all__ = ["interface_resultants", "global_vertex_forces"]


def _map(model: Model | InterfaceMap) -> InterfaceMap:
    return model.interface_map if isinstance(model, Model) else model


def global_vertex_forces(model: Model | InterfaceMap, vertex_forces: NDArray[np.float64]) -> NDArray[np.float64]:
    """Vertex forces ``(nv, 3)`` from interface frames ``(fn, ft1, ft2)`` to the global frame (kN)."""
    return np.einsum("kij,ki->kj", _map(model).vertex_frames, vertex_forces)


def interface_resultants(
    model: Model | InterfaceMap, vertex_forces: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Resultants of the model's interfaces (``model.interfaces`` order).

    Parameters
    ----------
    model : Model or InterfaceMap
    vertex_forces : (nv, 3) ndarray
        ``(fn, ft1, ft2)`` at every interface vertex, interface frame (kN).

    Returns
    -------
    resultant : (ni, 3) ndarray
        Sum of the vertex forces, global frame (kN), acting on block B.
    pressure_point : (ni, 3) ndarray
        Pressure point (m); NaN where the interface carries no normal force.
    torque : (ni,) ndarray
        Moment about the normal through the pressure point (kN m); NaN with it.
    """
    imap = _map(model)
    ni = len(imap.interfaces)
    pos = imap.vertex_slot  # interface slot (0..ni-1) of each vertex
    g = global_vertex_forces(imap, vertex_forces)
    x = imap.vertex_points
    fn = vertex_forces[:, 0]

    def per_interface(v: NDArray[np.float64]) -> NDArray[np.float64]:
        if v.ndim == 1:
            return np.bincount(pos, weights=v, minlength=ni)
        return np.column_stack([np.bincount(pos, weights=v[:, k], minlength=ni) for k in range(v.shape[1])])

    resultant = per_interface(g)
    fn_sum = per_interface(fn)
    scale = np.abs(fn).max(initial=0.0)
    carries = fn_sum > 1e-12 * max(scale, 1e-300)
    with np.errstate(invalid="ignore", divide="ignore"):
        pp = np.where(carries[:, None], per_interface(fn[:, None] * x) / fn_sum[:, None], np.nan)
    normals = imap.normals
    moment = per_interface(np.cross(x, g)) - np.cross(pp, resultant)
    torque = np.where(carries, np.einsum("ij,ij->i", moment, normals), np.nan)
    return resultant, pp, torque
