"""Shared fixtures, and the hypothesis settings profile of the suite.

Hypothesis is derandomized by default (profile ``ci``): every run, CI included, draws the same
examples, so a failure is reproducible and a green run means the same thing twice. Set
``TCE_HYPOTHESIS=explore`` to draw new examples on each run when hunting for bugs.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly

settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", derandomize=False, print_blob=True)
settings.load_profile(os.environ.get("TCE_HYPOTHESIS", "ci"))


@pytest.fixture(scope="session")
def arch() -> Assembly:
    """The paper's arch: inner radius 1.00 m, thickness 0.20 m, depth 0.25 m, 14 voussoirs."""
    return semicircular_arch()
