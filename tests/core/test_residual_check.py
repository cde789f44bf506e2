"""An answer that leaves the friction cone is never ``optimal``, whatever Clarabel says.

Clarabel is replaced by a wrapper that adds to every answer a self-stress of purely tangential
contact forces: every equilibrium row still holds, but the contacts leave their friction cones.
The residual check (equilibrium and contact law, docs/conventions.md) must then refuse the
answer: ``solve`` reports no optimal state and ``limit`` no lambda_max.

The hook is ``clarabel.DefaultSolver`` (the module attribute tce calls): if tce stops calling
it, ``test_the_hook_is_used`` says so.
"""

from __future__ import annotations

import clarabel
import numpy as np
import pytest
import scipy.linalg
from helpers import block_on_support

from tce.analysis import Analysis
from tce.core.conic import cone_violation
from tce.core.material import Material

MU = 0.3


@pytest.fixture
def scene():
    an = Analysis(block_on_support(0.4, 1.0, 0.3), Material(MU), model="spatial")
    model = an.model("spatial")
    # self-stresses with fn = 0 at every contact: tangential forces that cancel each other
    fn_rows = np.eye(model.n_vars)[0 :: model.dim]
    null = scipy.linalg.null_space(np.vstack([model.A_eq.toarray(), fn_rows]))
    assert null.shape[1] > 0
    d = null[:, 0] / np.abs(null[:, 0]).max()
    return an, model, d


class ConeBreaker:
    """Stands in for ``clarabel.DefaultSolver``: solves with the real one, then adds
    ``amplitude * d`` to the first ``len(d)`` entries (the contact forces) of the answer."""

    calls = 0
    direction: np.ndarray = np.zeros(0)
    amplitude = 100.0
    real = clarabel.DefaultSolver

    def __init__(self, *args, **kwargs):
        self._solver = self.real(*args, **kwargs)

    def update(self, *args, **kwargs):
        return self._solver.update(*args, **kwargs)

    def solve(self):
        sol = self._solver.solve()
        n = len(self.direction)
        x = np.array(sol.x)
        if len(x) >= n:
            type(self).calls += 1
            x[:n] += self.amplitude * self.direction

        class Answer:
            def __getattr__(self, name):
                return getattr(sol, name)

        answer = Answer()
        answer.x = x
        return answer


@pytest.fixture
def breaker(scene, monkeypatch):
    _, _, d = scene
    monkeypatch.setattr(ConeBreaker, "direction", d)
    monkeypatch.setattr(ConeBreaker, "calls", 0)
    monkeypatch.setattr(clarabel, "DefaultSolver", ConeBreaker)
    return ConeBreaker


def test_the_perturbation_keeps_equilibrium_and_leaves_the_cone(scene):
    an, model, d = scene
    W = an.assembly.total_weight
    r = an.solve(0.2)
    assert r.status == "optimal"
    F = r.forces.ravel() + ConeBreaker.amplitude * W * d
    assert np.abs(model.A_eq @ (ConeBreaker.amplitude * W * d)).max() < 1e-10 * W
    assert cone_violation(model, MU, F) > W


def test_the_hook_is_used(scene, breaker):
    an, _, _ = scene
    an.solve(0.2)
    assert breaker.calls > 0, "tce no longer calls clarabel.DefaultSolver: move this test's hook"


def test_a_cone_violating_answer_is_not_optimal(scene, breaker):
    an, _, _ = scene
    r = an.solve(0.2)
    assert r.status != "optimal"
    assert np.all(np.isnan(r.forces))


def test_a_cone_violating_limit_is_not_optimal(scene, breaker):
    an, _, _ = scene
    lim = an.limit(0.0)
    assert lim.status != "optimal"
    assert not np.isfinite(lim.lambda_max)
