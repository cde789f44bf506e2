"""Which wheels of a vehicle are kept (tce.core.vehicles.wheel_loads, through
tce.core.loads.resolve), against a hand list: a lorry of three axles and four wheels on
the two-span bridge, over free and over fixed piers, and the rule "on a free block's top,
inside the width" applied by hand at positions all along the bridge.

The bridge (arch_bridge(spans=2, voussoirs=3)): spans of 6 m with a rise of 1.5 m and a
0.4 m ring, centred on x = -+3.5 m, 3 m wide (y from -1.5 to 1.5). The intrados radius is
(3^2 + 1.5^2) / (2 x 1.5) = 3.75 m about a centre 2.25 m below the springings, the extrados
4.15 m; the joints are at -+53.13 deg (sin = 0.8) and -+17.71 deg from the vertical. The
deck is the extrados chords from x = -6.82 to -0.18 and 0.18 to 6.82 m, and the pier's top
between them (z = 0.24 m): free with free piers, a support with fixed piers.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from tce.core.loads import LoadPattern, resolve
from tce.structures.bridge import arch_bridge

LORRY = dict(axles=[[0.0, 10.0], [3.0, 20.0], [6.0, 30.0]], wheels=[-1.0, 1.0, 2.0, -3.0], name="lorry")
HALF_WIDTH = 1.5


def extrados_z(x: float) -> float:
    """Height of the extrados chord above x (m), from the segmental geometry by hand."""
    centre = -3.5 if x < 0 else 3.5
    theta = math.asin(0.8)
    angles = [-theta, -theta / 3, theta / 3, theta]
    pts = [(centre + 4.15 * math.sin(a), -2.25 + 4.15 * math.cos(a)) for a in angles]
    for (x0, z0), (x1, z1) in zip(pts[:-1], pts[1:]):
        if x0 <= x <= x1:
            return z0 + (z1 - z0) * (x - x0) / (x1 - x0)
    raise ValueError(f"x = {x} is not over a span")


@pytest.mark.parametrize("piers, kept, dropped", [
    # (axle, wheel, block, x, y, load) kept; the dropped wheels' words, in the note
    ("fixed",
     [(0, 0, "s1v01", -6.0, -1.0, 10 / 4), (0, 1, "s1v01", -6.0, 1.0, 10 / 4),
      (1, 0, "s1v02", -3.0, -1.0, 20 / 4), (1, 1, "s1v02", -3.0, 1.0, 20 / 4)],
     ["axle 1 wheel 3 (x = -6 m, y = 2 m) off the deck", "axle 1 wheel 4 (x = -6 m, y = -3 m) off the deck",
      "axle 2 wheel 3 (x = -3 m, y = 2 m) off the deck", "axle 2 wheel 4 (x = -3 m, y = -3 m) off the deck",
      "axle 3 wheel 1 (x = 0 m, y = -1 m) over support block 'pier1'",
      "axle 3 wheel 2 (x = 0 m, y = 1 m) over support block 'pier1'", "axle 3 wheel 3 (x = 0 m, y = 2 m) off the deck",
      "axle 3 wheel 4 (x = 0 m, y = -3 m) off the deck"]),
    ("free",
     [(0, 0, "s1v01", -6.0, -1.0, 10 / 4), (0, 1, "s1v01", -6.0, 1.0, 10 / 4),
      (1, 0, "s1v02", -3.0, -1.0, 20 / 4), (1, 1, "s1v02", -3.0, 1.0, 20 / 4),
      (2, 0, "pier1", 0.0, -1.0, 7.5), (2, 1, "pier1", 0.0, 1.0, 7.5)],
     ["axle 1 wheel 3 (x = -6 m, y = 2 m) off the deck", "axle 1 wheel 4 (x = -6 m, y = -3 m) off the deck",
      "axle 2 wheel 3 (x = -3 m, y = 2 m) off the deck", "axle 2 wheel 4 (x = -3 m, y = -3 m) off the deck",
      "axle 3 wheel 3 (x = 0 m, y = 2 m) off the deck",
      "axle 3 wheel 4 (x = 0 m, y = -3 m) off the deck"]),
])
def test_kept_wheels_of_a_lorry_on_two_spans_as_listed_by_hand(piers, kept, dropped):
    b = arch_bridge(spans=2, voussoirs=3, piers=piers)
    a = resolve(LoadPattern(lateral=False, vehicle=[dict(LORRY, x=-6.0)]), b)
    assert a.sources == tuple(f"vehicle[0].axle[{ax}].wheel[{w}]" for ax, w, *_ in kept)
    assert [b.names[i] for i in a.blocks] == [blk for _, _, blk, *_ in kept]
    assert a.points[:, :2] == pytest.approx(np.array([(x, y) for *_, x, y, _ in kept]), abs=1e-12)
    z = [0.24 if blk == "pier1" else extrados_z(x) for _, _, blk, x, _, _ in kept]
    assert a.points[:, 2] == pytest.approx(z, abs=2e-3)
    assert a.forces[:, 2] == pytest.approx([-load for *_, load in kept], rel=1e-12)
    assert np.allclose(a.forces[:, :2], 0.0)
    (note,) = a.notes
    assert f"{len(dropped)} of 12 wheels dropped" in note and "lorry" in note
    assert note.split(": ", 2)[2].split("; ") == dropped


def hand_kept(x_ref: float, piers: str) -> set[tuple[int, int]]:
    """(axle, wheel) on the deck: inside the width, over a span's extrados, or over the pier's
    top if the pier is free."""
    deck = [(-6.82, -0.18), (0.18, 6.82)] if piers == "fixed" else [(-6.82, 6.82)]
    out = set()
    for ax, (dx, _) in enumerate(LORRY["axles"]):
        for w, dy in enumerate(LORRY["wheels"]):
            if abs(dy) < HALF_WIDTH and any(lo < x_ref + dx < hi for lo, hi in deck):
                out.add((ax, w))
    return out


@pytest.mark.parametrize("piers", ["fixed", "free"])
def test_kept_wheels_all_along_the_bridge_follow_the_hand_rule(piers):
    b = arch_bridge(spans=2, voussoirs=3, piers=piers)
    p = LoadPattern(lateral=False, vehicle=[LORRY])
    # every 0.25 m from the first axle on the deck to the last one leaving it, clear of the
    # deck's edges (-+6.8200, -+0.1800 to 4 digits)
    seen = 0
    for x in np.arange(-12.75, 6.8, 0.25) + 0.01:
        want = hand_kept(float(x), piers)
        if not want:
            continue
        seen += 1
        a = resolve(p.moved(float(x)), b)
        wheels = [tuple(int(v) for v in re.fullmatch(r"vehicle\[0\]\.axle\[(\d)\]\.wheel\[(\d)\]", s).groups())
                  for s in a.sources]
        assert set(wheels) == want and len(wheels) == len(want), x
        # each wheel carries its axle's load shared by the four wheels
        assert a.forces[:, 2] == pytest.approx([-LORRY["axles"][ax][1] / 4 for ax, _ in wheels])
    assert seen > 60
