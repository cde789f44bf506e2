"""Argument checks shared by the structure generators and the analyses that build structures.

Each raises :class:`ValueError` naming the parameter, so that a study file's error can point
at the key (``docs/studies.md``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

__all__ = ["MAX_BLOCKS", "check_blocks", "check_choice", "check_positive", "check_whole"]

#: Most blocks in an assembly: a block file's (:mod:`tce.structures.io`) and every generator's.
MAX_BLOCKS = 50_000


def check_blocks(count: int, how: str) -> None:
    """Raise ``ValueError`` when a generator would make more than :data:`MAX_BLOCKS` blocks.

    Called before anything is built, so that no parameter makes a generator run out of
    memory or time. ``how`` says how ``count`` follows from the parameters
    (``"voussoirs + 2 = 10000002"``, naming them for a study file's message).
    """
    if count > MAX_BLOCKS:
        raise ValueError(f"{how} = {count} blocks, more than MAX_BLOCKS = {MAX_BLOCKS}")


def check_positive(**params: float) -> None:
    """Raise ``ValueError`` naming the first parameter that is not a finite number > 0."""
    for name, value in params.items():
        try:
            ok = math.isfinite(float(value)) and float(value) > 0
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")


def check_whole(value: int, name: str, minimum: int = 1) -> int:
    """``value`` as an int; ``ValueError`` naming ``name`` unless it is a whole number >= ``minimum``."""
    try:
        ok = not isinstance(value, bool) and int(value) == value and value >= minimum
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok:
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {value!r}")
    return int(value)


def check_choice(value: str, name: str, options: Sequence[str]) -> str:
    """``value``; ``ValueError`` naming ``name`` and the options unless it is one of ``options``."""
    if value not in options:
        raise ValueError(f"{name} must be one of {list(options)}, got {value!r}")
    return value

