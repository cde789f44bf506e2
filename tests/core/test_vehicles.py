"""Vehicles (tce.core.vehicles): axle groups that move as one rigid pattern, wheels off the
deck dropped with a note and never merged, the standard vehicles' figures; and the moving
point loads of a load_x sweep that keep their offsets (issue 21, problem 3)."""

from __future__ import annotations

import numpy as np
import pytest

from tce.core.loads import LoadError, LoadPattern, resolve
from tce.core.vehicles import (
    STANDARD,
    Vehicle,
    aashto_hl93_truck,
    deck_edges,
    deck_range,
    eurocode_lm1_tandem,
    eurocode_lm2_axle,
    standard_vehicle,
    tandem,
    tridem,
)
from tce.structures.arch import segmental_arch, semicircular_arch

ARCH = semicircular_arch()


def test_moved_point_loads_keep_their_offsets():
    # issue 21 problem 3: two axles 1.2 m apart moved by load_x stayed two loads 1.2 m apart
    p = LoadPattern(lateral=False, point=[
        dict(on_top=[-0.6, 0.0], force=[0, 0, -1.0]), dict(on_top=[0.6, 0.0], force=[0, 0, -1.0]),
        dict(on_top=[0.3, 0.0], force=[0, 0, -2.0], scaled=False),
    ])
    q = p.moved(-0.5)
    assert [pt.on_top[0] for pt in q.point] == pytest.approx([-0.5, 0.7, 0.3])
    applied = resolve(q, ARCH)
    assert len(applied.blocks) == 3 and np.ptp(applied.points[:2, 0]) == pytest.approx(1.2)


def test_vehicle_moves_as_one_and_its_reference_is_the_position():
    p = LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0], [0.4, 2.0]])])
    a = resolve(p.moved(-0.3), ARCH)
    assert a.points[:, 0] == pytest.approx([-0.3, 0.1])
    assert a.forces[:, 2] == pytest.approx([-1.0, -2.0])
    assert a.sources == ("vehicle[0].axle[0].wheel[0]", "vehicle[0].axle[1].wheel[0]")
    assert a.notes == ()
    # a point load and a vehicle move together: the vehicle is the reference
    both = LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0]], x=0.2)],
                       point=[dict(on_top=[0.5, 0.0], force=[0, 0, -1.0])]).moved(-0.1)
    assert both.vehicle[0].x == pytest.approx(-0.1) and both.point[0].on_top[0] == pytest.approx(0.2)


def test_wheels_off_the_deck_are_dropped_with_a_note_never_merged():
    p = LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0], [0.4, 1.0], [0.8, 1.0]], name="truck")])
    a = resolve(p.moved(0.7), ARCH)  # the deck ends at x = 1.2: the third axle (1.5) is off
    assert len(a.blocks) == 2 and a.points[:, 0] == pytest.approx([0.7, 1.1])
    assert len(a.notes) == 1 and "axle 3" in a.notes[0] and "truck" in a.notes[0] and "dropped" in a.notes[0]
    # wheels across the depth: only those over the 0.25 m deep arch stay
    w = resolve(LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 2.0]], wheels=[-1.0, 0.0])]), ARCH)
    assert len(w.blocks) == 1 and w.forces[0, 2] == pytest.approx(-1.0) and len(w.notes) == 1


def test_dropped_wheels_are_one_note_per_vehicle():
    """Issue 37 item 2: every dropped wheel of a vehicle in one line, not one line per wheel."""
    p = LoadPattern(vehicle=[dict(axles=[[0.0, 1.0], [0.4, 1.0], [0.8, 1.0]], wheels=[-1.0, 0.0, 1.0], name="truck")])
    a = resolve(p, ARCH)  # the 0.25 m deep arch: only the wheels on the line (y = 0) stay
    assert len(a.blocks) == 3
    assert len(a.notes) == 1 and "6 of 9 wheels" in a.notes[0] and a.notes[0].count("off the deck") == 6


@pytest.mark.parametrize("vehicle", [
    dict(axles=[[0.0, 1.0]], wheels=[-3.0, 3.0]),  # wheels 6 m apart on a 0.25 m deep arch
    dict(axles=[[0.0, 1.0]], wheels=[-900.0, 900.0]),  # offsets written in mm
    dict(axles=[[0.0, 1.0]], x=9.0),  # beyond the deck's end
])
def test_a_vehicle_with_no_wheel_on_the_deck_is_an_error_naming_the_deck(vehicle):
    """Issue 37 item 2 (fails on main: the loads resolved to nothing, and the limit was 'unbounded')."""
    from tce.core.analysis import Analysis

    pattern = LoadPattern(vehicle=[vehicle])
    deck = r"the deck, which spans x = \[-1\.2, 1\.2\] m, y = \[-0\.125, 0\.125\] m"
    with pytest.raises(ValueError, match=rf"vehicle\[0\]: no wheel of 'vehicle' .* {deck}"):
        resolve(pattern, ARCH)
    with pytest.raises(ValueError, match="no wheel"):
        Analysis(ARCH).limit(loads=pattern)


def test_patch_pressure_sums_to_the_wheel_load_and_its_part_off_the_deck_is_noted():
    bridge = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=4.0, voussoirs=12)
    v = dict(axles=[[0.0, 100.0]], wheels=[-1.0, 1.0], patch=[0.4, 0.4])
    a = resolve(LoadPattern(lateral=False, vehicle=[v]), bridge)
    assert a.forces[:, 2].sum() == pytest.approx(-100.0)
    assert set(a.sources) == {"vehicle[0].axle[0].wheel[0]", "vehicle[0].axle[0].wheel[1]"}
    lo, hi = deck_range(bridge)
    edge = LoadPattern(lateral=False, vehicle=[dict(v, x=hi + 0.1)])  # patch from hi - 0.1 to hi + 0.3: 25% on
    b = resolve(edge, bridge)
    assert b.forces[:, 2].sum() == pytest.approx(-25.0)
    # one note for the vehicle, naming both wheels
    assert len(b.notes) == 1 and b.notes[0].count("75% of its contact patch") == 2 and "2 of 2 wheels" in b.notes[0]


def test_symmetric_wheels_keep_the_planar_model():
    from tce.core.analysis import Analysis

    bridge = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=4.0, voussoirs=12)
    an = Analysis(bridge)
    sym = LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0]], wheels=[-1.0, 1.0])])
    off = LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0]], wheels=[-1.0, 1.0], y=0.5)])
    assert an.model_kind(loads=sym) == "planar"
    assert an.model_kind(loads=off) == "spatial"


@pytest.mark.parametrize(
    "kwargs, key",
    [
        (dict(axles=[]), "axles"),
        (dict(axles=[[0.0, 0.0]]), "axles[0]"),
        (dict(axles=[[0.0, 1.0], [0.0, 2.0]]), "axles"),
        (dict(axles=[[0.0, float("nan")]]), "axles[0]"),
        (dict(axles=[[0.0, 1.0]], wheels=[1.0, 1.0]), "wheels"),
        (dict(axles=[[0.0, 1.0]], patch=[0.4, 0.0]), "patch"),
        (dict(axles=[[0.0, 1.0]], scaled="yes"), "scaled"),
    ],
)
def test_bad_vehicles_name_their_key(kwargs, key):
    with pytest.raises(LoadError) as err:
        LoadPattern(lateral=False, vehicle=[kwargs])
    assert err.value.key == f"vehicle[0].{key}"


def test_pattern_round_trip_and_old_patterns_read_the_same():
    p = LoadPattern(lateral=False, vehicle=[eurocode_lm1_tandem(1)])
    assert LoadPattern.from_dict(p.to_dict()) == p
    assert "vehicle" not in LoadPattern(lateral=True).to_dict()


def test_standard_vehicles_figures():
    # EN 1991-2:2003 4.3.2, Figure 4.2a and Table 4.2
    ts = eurocode_lm1_tandem(1)
    assert ts.axles == ((0.0, 300.0), (1.2, 300.0)) and ts.wheels == (-1.0, 1.0) and ts.patch == (0.4, 0.4)
    assert eurocode_lm1_tandem(2).total == 400.0 and eurocode_lm1_tandem(3, alpha_q=0.8).total == pytest.approx(160.0)
    # EN 1991-2:2003 4.3.3, Figure 4.3
    lm2 = eurocode_lm2_axle()
    assert lm2.axles == ((0.0, 400.0),) and lm2.wheels == (-1.0, 1.0) and lm2.patch == (0.35, 0.6)
    # AASHTO LRFD 3.6.1.2.2 (SI)
    hl = aashto_hl93_truck()
    assert [a[1] for a in hl.axles] == [35.0, 145.0, 145.0] and hl.offsets == pytest.approx([0.0, 4.3, 8.6])
    assert np.ptp(hl.wheels) == pytest.approx(1.8)
    with pytest.raises(LoadError):
        aashto_hl93_truck(10.0)
    assert tandem(100.0, 1.3).offsets == pytest.approx([0.0, 1.3])
    assert tridem(80.0, 1.3).total == 240.0
    assert set(STANDARD) >= {"en1991_lm1_tandem_lane1", "en1991_lm2_axle", "aashto_hl93_truck"}
    assert standard_vehicle("en1991_lm1_tandem_lane1", x=2.0).x == 2.0
    with pytest.raises(LoadError, match="unknown vehicle"):
        standard_vehicle("lm9")


def test_deck_edges_are_the_extrados_joints():
    edges = deck_edges(ARCH)
    a = np.pi * (1.0 - np.arange(15) / 14)
    assert edges == pytest.approx(np.sort(1.2 * np.cos(a)), abs=1e-12)
    assert deck_range(ARCH) == pytest.approx((-1.2, 1.2))
    assert isinstance(Vehicle(axles=[[0.0, 1.0]]).label, str)


# ---------------------------------------------------------------------------- fill
def _extrados(span=6.0, rise=1.5, t=0.4, n=12):
    """Extrados joint ends (x, z) of the segmental arch, from its definition (independent)."""
    R = (span**2 / 4 + rise**2) / (2 * rise)
    zc = rise - R
    half = np.arctan2(span / 2, -zc)
    ang = np.linspace(np.pi / 2 + half, np.pi / 2 - half, n + 1)
    return np.column_stack([(R + t) * np.cos(ang), zc + (R + t) * np.sin(ang)])


def test_fill_weight_is_the_column_above_each_voussoir():
    from tce.core.fill import Fill

    bridge = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12)
    je = _extrados()
    road = je[:, 1].max() + 0.3
    a = resolve(LoadPattern(lateral=False, fill=Fill(depth=0.3, unit_weight=18.0),
                            vehicle=[dict(axles=[[0.0, 1.0]])]), bridge)
    fill = np.array([s.startswith("fill") for s in a.sources])
    # column over voussoir k: trapezoid between road and the extrados chord, 3 m deep
    h = road - je[:, 1]
    area = 0.5 * (h[:-1] + h[1:]) * np.diff(je[:, 0])
    xc = (np.diff(je[:, 0]) / 3.0) * (h[:-1] + 2 * h[1:]) / (h[:-1] + h[1:]) + je[:-1, 0]
    np.testing.assert_allclose(-a.forces[fill, 2], 18.0 * 3.0 * area, rtol=1e-12)
    np.testing.assert_allclose(a.points[fill, 0], xc, rtol=1e-12, atol=1e-12)
    assert not a.scaled[fill].any()
    # at rest: -k0 n_x / n_z of the weight, towards the crown, at the same point
    k = resolve(LoadPattern(lateral=False, fill=Fill(depth=0.3, unit_weight=18.0, k0=0.5, weight=False),
                            vehicle=[dict(axles=[[0.0, 1.0]])]), bridge)
    kf = np.array([s.startswith("fill") for s in k.sources])
    slope = np.diff(je[:, 1]) / np.diff(je[:, 0])  # dz/dx of each chord: n_x / n_z = -slope
    np.testing.assert_allclose(k.forces[kf, 0], 0.5 * slope * 18.0 * 3.0 * area, rtol=1e-10, atol=1e-9)
    assert (k.forces[kf, 0][:6] > 0).all() and (k.forces[kf, 0][6:] < 0).all() and not k.forces[kf, 2].any()
    off = resolve(LoadPattern(lateral=False, fill=Fill(depth=0.3, unit_weight=18.0, weight=False),
                              vehicle=[dict(axles=[[0.0, 1.0]])]), bridge)
    assert not any(s.startswith("fill") for s in off.sources)


def test_wheel_load_dispersed_2_to_1_through_the_fill():
    from tce.core.fill import DISPERSION_2_TO_1, Fill

    assert np.tan(np.radians(DISPERSION_2_TO_1)) == pytest.approx(0.5)
    bridge = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12)
    je = _extrados()
    x0 = 0.1  # over voussoir 7, near the crown joint at x = 0
    z0 = np.interp(x0, je[:, 0], je[:, 1])
    h = je[:, 1].max() + 0.5 - z0
    L = 2 * h * 0.5  # 2:1: the spread length on each side is h / 2
    a = resolve(LoadPattern(lateral=False, fill=Fill(depth=0.5, unit_weight=18.0, weight=False),
                            vehicle=[dict(axles=[[0.0, 10.0]], x=x0)]), bridge)
    live = a.scaled
    assert a.forces[live, 2].sum() == pytest.approx(-10.0)
    right = a.points[live, 0] > 0.0
    assert -a.forces[live][right, 2].sum() == pytest.approx(10.0 * (x0 + L / 2) / L, rel=1e-9)
    none = resolve(LoadPattern(lateral=False, fill=Fill(depth=0.5, unit_weight=18.0, weight=False, dispersion=0.0),
                               vehicle=[dict(axles=[[0.0, 10.0]], x=x0)]), bridge)
    assert none.points[none.scaled, 0] == pytest.approx([x0])


@pytest.mark.parametrize("kwargs, key", [(dict(depth=-1.0, unit_weight=18.0), "depth"),
                                         (dict(depth=0.3, unit_weight=0.0), "unit_weight"),
                                         (dict(depth=0.3, unit_weight=18.0, dispersion=75.0), "dispersion"),
                                         (dict(depth=0.3, unit_weight=18.0, k0=1.5), "k0")])
def test_bad_fill_names_its_key(kwargs, key):
    with pytest.raises(LoadError) as err:
        LoadPattern(fill=kwargs)
    assert err.value.key == f"fill.{key}"


# ---------------------------------------------------------------------------- invariants
def test_vehicle_invariants_units_mirrors():
    from tce.core.analysis import Analysis

    bridge = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12)
    an = Analysis(bridge)

    def lam(**v):
        return an.limit(loads=LoadPattern(lateral=False, vehicle=[v])).lambda_max

    base = lam(axles=[[0.0, 1.0], [1.2, 2.0]], wheels=[-0.9, 0.9], x=-2.0)
    # kN -> 1000 x the load: lambda / 1000 (the live load is multiplied by lambda)
    assert lam(axles=[[0.0, 1000.0], [1.2, 2000.0]], wheels=[-0.9, 0.9], x=-2.0) == pytest.approx(base / 1000, rel=1e-7)
    # the vehicle mirrored about x = 0 (offsets negated, position negated)
    assert lam(axles=[[0.0, 1.0], [-1.2, 2.0]], wheels=[-0.9, 0.9], x=2.0) == pytest.approx(base, rel=1e-7)
    # wheels given in another order, the reference on the other axle
    assert lam(axles=[[1.2, 2.0], [0.0, 1.0]], wheels=[0.9, -0.9], x=-2.0) == pytest.approx(base, rel=1e-9)
    assert lam(axles=[[-1.2, 1.0], [0.0, 2.0]], wheels=[-0.9, 0.9], x=-0.8) == pytest.approx(base, rel=1e-9)
    # off the plane of symmetry (spatial model): mirrored in y
    off = lam(axles=[[0.0, 1.0]], wheels=[-0.5, 0.7], y=0.3, x=-1.5)
    assert an.model_kind(loads=LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0]], wheels=[-0.5, 0.7], y=0.3,
                                                                       x=-1.5)])) == "spatial"
    assert lam(axles=[[0.0, 1.0]], wheels=[0.5, -0.7], y=-0.3, x=-1.5) == pytest.approx(off, rel=1e-6)


def test_cs454_axles_and_bogies_as_the_table_prints_them():
    # CS 454 Revision 0, Table 7.3.1a (normal traffic) and Table 7.3.1b (axle lift-off);
    # tonnes times standard gravity
    from tce.core.vehicles import STANDARD_GRAVITY, cs454_double_bogie, cs454_single_axle

    g = STANDARD_GRAVITY
    assert cs454_single_axle().axles == ((0.0, 11.5 * g),)
    for s, t in ((1.00, 8.0), (1.29, 8.0), (1.30, 9.5), (1.79, 9.5), (1.80, 10.0), (2.5, 10.0)):
        assert cs454_double_bogie(s).axles == ((0.0, t * g), (s, t * g))
    assert cs454_double_bogie(1.5, lift_off=True).axles == ((0.0, 1.5 * 9.5 * g), (1.5, 0.5 * 9.5 * g))
    assert standard_vehicle("cs454_double_bogie_s130").axles == ((0.0, 9.5 * g), (1.3, 9.5 * g))
    with pytest.raises(LoadError, match="spacing"):
        cs454_double_bogie(0.9)
