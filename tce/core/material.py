"""Interface material: friction and optional stiffness."""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Material"]


def _finite(name: str, value: float | None, lower: float, strict: bool) -> None:
    if value is None:
        return
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < lower or (strict and v == lower):
        bound = f"> {lower}" if strict else f">= {lower}"
        raise ValueError(f"{name} must be a finite number {bound}, got {value!r}")


@dataclass(frozen=True)
class Material:
    """Contact law of the interfaces.

    Parameters
    ----------
    friction : float or None
        Coulomb friction coefficient mu >= 0 (``||ft|| <= mu fn`` per contact vertex);
        ``None`` is a Heyman material with unlimited friction (only ``fn >= 0``).
    normal_stiffness : float or None
        Normal stiffness per unit area (kN/m^3). ``None`` is the rigid case (``D = 0``).
    shear_stiffness : float or None
        Tangential stiffness per unit area (kN/m^3); defaults to ``normal_stiffness``.
        Only meaningful with a normal stiffness.
    """

    friction: float | None = None
    normal_stiffness: float | None = None
    shear_stiffness: float | None = None

    def __post_init__(self) -> None:
        _finite("friction", self.friction, 0.0, strict=False)
        _finite("normal_stiffness", self.normal_stiffness, 0.0, strict=True)
        _finite("shear_stiffness", self.shear_stiffness, 0.0, strict=True)
        if self.shear_stiffness is not None and self.normal_stiffness is None:
            raise ValueError("shear_stiffness needs a normal_stiffness (the rigid case has neither)")
        if self.normal_stiffness is not None and self.shear_stiffness is None:
            object.__setattr__(self, "shear_stiffness", self.normal_stiffness)

    @property
    def rigid(self) -> bool:
        """True when the contacts are rigid (no compliance term)."""
        return self.normal_stiffness is None

    @property
    def heyman(self) -> bool:
        """True when friction is unlimited."""
        return self.friction is None
