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


@pytest.fixture(autouse=True)
def _signals_left_as_found():
    """Every test leaves the process's signal dispositions as it found them: an ignored Ctrl-C
    left behind (by a stop, or a handler not restored) is inherited by every process a later test
    starts, which then cannot be interrupted (the Ctrl-C fault tests ended 0 instead of 130)."""
    import signal

    sigs = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
    before = {s: signal.getsignal(s) for s in sigs}
    yield
    after = {s: signal.getsignal(s) for s in sigs}
    for s in sigs:
        signal.signal(s, before[s])
    changed = {signal.Signals(s).name: (before[s], after[s]) for s in sigs if after[s] != before[s]}
    assert not changed, f"the test left signal handlers changed: {changed}"
