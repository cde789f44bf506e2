"""Shared fixtures."""

from __future__ import annotations

import pytest

from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly


@pytest.fixture(scope="session")
def arch() -> Assembly:
    """The paper's arch: inner radius 1.00 m, thickness 0.20 m, depth 0.25 m, 14 voussoirs."""
    return semicircular_arch()
