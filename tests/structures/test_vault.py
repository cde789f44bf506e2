"""Barrel and groin vaults: exact planar blocks, interfaces by construction, closed-form volumes,
the stack-bond vault against the arch, and lambda_max under the vaults' symmetries."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.structures.arch import semicircular_arch
from tce.structures.contacts import check_overlaps, detect_interfaces
from tce.structures.vault import barrel_vault, groin_vault

VAULTS = {
    "barrel-stack": lambda: barrel_vault(1.0, 0.2, 1.5, 12, 6),
    "barrel-running": lambda: barrel_vault(1.0, 0.2, 1.25, 9, 5, bond="running"),
    "barrel-course-supports": lambda: barrel_vault(1.0, 0.2, 0.9, 6, 3, supports="courses"),
    "groin-square": lambda: groin_vault(2.0, thickness=0.2, voussoirs=8),
    "groin-rectangle": lambda: groin_vault(2.0, 3.0, 0.25, 6),
    "groin-springings": lambda: groin_vault(2.0, 2.5, 0.2, 6, supports="springings"),
}


def _free_volume(asm):
    return sum(b.volume for b in asm.blocks if not b.support)


@pytest.mark.parametrize("name", sorted(VAULTS))
def test_blocks_are_exact_planar_polyhedra_that_do_not_overlap(name):
    asm = VAULTS[name]().validate()
    for b in asm.blocks:
        b.shape.validate(b.name, tol=1e-12)  # every face planar to round-off
    check_overlaps(asm)


@pytest.mark.parametrize("name", sorted(VAULTS))
def test_interfaces_by_construction_are_those_detected(name):
    """Every interface built with the blocks is found by contact detection, with the same
    polygon (area, centroid) and normal; detection finds nothing else except contacts between
    two supports (which carry no unknowns)."""
    asm = VAULTS[name]()
    sup = set(asm.support_indices)

    def table(itfs):
        out = {}
        for i in itfs:
            if i.a in sup and i.b in sup:
                continue
            out.setdefault((i.a, i.b), []).append(i)
        return out

    mine, found = table(asm.interfaces), table(detect_interfaces(asm))
    assert set(mine) == set(found)
    for key, items in mine.items():
        assert len(items) == 1 and len(found[key]) == 1, key
        a, b = items[0], found[key][0]
        assert a.area == pytest.approx(b.area, rel=1e-9)
        assert np.allclose(a.centroid, b.centroid, atol=1e-9)
        assert np.allclose(a.normal, b.normal, atol=1e-9)
        # the normal points from A into B, and A has the lower index
        assert a.a < a.b
        assert a.normal @ (asm.blocks[a.b].centroid - asm.blocks[a.a].centroid) > 0


def _chord_ring_area(ri, ro, angles):
    """Area of a ring of chord-faced voussoirs between radial joints at ``angles`` (rad):
    each is a triangle from the centre on the extrados chord minus one on the intrados chord."""
    d = np.abs(np.diff(angles))
    return float(np.sum(0.5 * np.sin(d)) * (ro**2 - ri**2))


@pytest.mark.parametrize("bond", ["stack", "running"])
def test_barrel_vault_volume_closed_form(bond):
    ri, t, depth, n, nc = 1.1, 0.25, 2.0, 10, 5
    asm = barrel_vault(ri, t, depth, n, nc, bond=bond)
    full = np.linspace(np.pi, 0, n + 1)
    half = np.concatenate([[np.pi], np.pi - np.pi / n * (np.arange(n) + 0.5), [0.0]])
    per_course = [full if bond == "stack" or c % 2 == 0 else half for c in range(nc)]
    exact = sum(_chord_ring_area(ri, ri + t, a) for a in per_course) * depth / nc
    assert _free_volume(asm) == pytest.approx(exact, rel=1e-12)
    # the supports: two walls under the springings, the whole depth long
    assert asm.support_names == ("left", "right")
    for s in asm.support_names:
        assert asm.blocks[asm.index[s]].volume == pytest.approx(t * t * depth, rel=1e-12)


def _groin_volume(span_x, span_y, t, n):
    """Volume of the facetted groin vault, derived independently of tce.

    A web (say the north one, of the barrel spanning x) is the set of points (x, y, z) with
    (x, z) in the chord-faced section Q of the ring (intrados radius Ri = span_x / 2, extrados
    Ro = Ri + t) and |x| <= y <= Ro. Its volume is the integral over Q of (Ro - |x|):
    Ro * area(Q_i) - |first moment of Q_i about x = 0| summed over the voussoir sections Q_i
    (each on one side of x = 0). Q_i is the triangle (O, Ro e_i, Ro e_i+1) minus the triangle
    (O, Ri e_i, Ri e_i+1); a triangle with a vertex at O has area 1/2 r^2 sin(d) and first
    moment area * (x_1 + x_2) / 3. The four webs are the north one turned by quarter turns,
    and stretching y by k = span_y / span_x multiplies every volume by k.
    """
    ri = span_x / 2.0
    ro = ri + t
    th = np.linspace(np.pi, 0.0, n + 1)
    d = np.pi / n
    area = 0.5 * math.sin(d) * (ro**2 - ri**2)
    moment = 0.5 * math.sin(d) * (ro**3 - ri**3) * np.abs(np.cos(th[:-1]) + np.cos(th[1:])) / 3.0
    web = float(np.sum(ro * area - moment))
    return 4.0 * web * span_y / span_x


def _groin_volume_continuous(span_x, span_y, t):
    """The same with the exact (circular) section: integral of (Ro - |x|) over the half ring."""
    ri = span_x / 2.0
    ro = ri + t
    web = ro * math.pi / 2.0 * (ro**2 - ri**2) - 2.0 / 3.0 * (ro**3 - ri**3)
    return 4.0 * web * span_y / span_x


@pytest.mark.parametrize("span_y", [2.0, 3.1])
@pytest.mark.parametrize("n", [2, 6, 12])
def test_groin_vault_volume_closed_form(span_y, n):
    asm = groin_vault(2.0, span_y, 0.3, n)
    assert _free_volume(asm) == pytest.approx(_groin_volume(2.0, span_y, 0.3, n), rel=1e-12)


def test_groin_vault_volume_converges_to_the_continuous_vault():
    exact = _groin_volume_continuous(2.0, 2.6, 0.2)
    errs = [abs(_free_volume(groin_vault(2.0, 2.6, 0.2, n)) / exact - 1.0) for n in (4, 8, 16, 32)]
    assert errs[0] > errs[1] > errs[2] > errs[3]
    assert 3.5 < errs[1] / errs[2] < 4.5  # inscribed chords: second order
    assert errs[-1] < 2e-3


def test_groin_vault_names_and_supports():
    asm = groin_vault(2.0, voussoirs=4)
    assert asm.support_names == ("ne", "nw", "sw", "se")
    assert asm.names[4:] == tuple(f"{w}{i:02d}" for w in "nwse" for i in range(1, 5))
    # each pier is the corner square under the two springing triangles that rest on it
    for s in asm.support_names:
        k = asm.index[s]
        on = [i for i in asm.interfaces if k in (i.a, i.b)]
        assert len(on) == 2
        assert sum(i.area for i in on) == pytest.approx(0.2**2, rel=1e-12)
    split = groin_vault(2.0, 3.0, voussoirs=4, supports="springings")
    assert split.support_names == ("ne_n", "ne_e", "nw_w", "nw_n", "sw_s", "sw_w", "se_e", "se_s")
    # the supports of one corner share nothing but a diagonal: each carries one springing
    for s in split.support_names:
        k = split.index[s]
        (itf,) = [i for i in split.interfaces if k in (i.a, i.b)]
        web = split.names[itf.b if itf.a == k else itf.a]
        assert web[0] == s[-1]


def test_barrel_vault_supports_per_course():
    asm = barrel_vault(1.0, 0.2, 0.9, 6, 3, supports="courses")
    assert asm.support_names == ("left01", "left02", "left03", "right01", "right02", "right03")
    for c in (1, 2, 3):
        for side in ("left", "right"):
            k = asm.index[f"{side}{c:02d}"]
            (itf,) = [i for i in asm.interfaces if k in (i.a, i.b)]
            assert asm.names[itf.b].startswith(f"c{c:02d}")


@pytest.mark.parametrize(
    "call, key",
    [
        (lambda: barrel_vault(thickness=-0.1), "thickness"),
        (lambda: barrel_vault(courses=0), "courses"),
        (lambda: barrel_vault(bond="english"), "bond"),
        (lambda: barrel_vault(supports="piers"), "supports"),
        (lambda: groin_vault(voussoirs=7), "even"),
        (lambda: groin_vault(span_y=float("nan")), "span_y"),
        (lambda: groin_vault(supports="walls"), "supports"),
        (lambda: groin_vault(support_height=0.0), "support_height"),
    ],
)
def test_bad_parameters_are_named(call, key):
    with pytest.raises(ValueError, match=key):
        call()


# ---------------------------------------------------------------- the stack bond is the arch
def test_stack_bond_barrel_vault_is_the_arch_times_the_courses():
    """In stack bond no joint crosses the courses: every course is the arch of the course's
    depth, and the vault carries exactly what its courses carry side by side. Its lambda_max
    in the arch's plane is the arch's (a course's mechanism is the vault's, and the arch's
    limit state repeated in every course is the vault's), and with compliant joints (a unique
    answer) every wall carries the courses' reactions added up: the arch's times the courses
    (the courses' moment arms along y cancel about the wall's centroid)."""
    courses, depth = 5, 1.25
    vault = barrel_vault(1.0, 0.2, depth, 10, courses)
    arch = semicircular_arch(1.0, 0.2, depth / courses, 10)
    rigid = Material(friction=0.8)
    lv, la = Analysis(vault, rigid).limit(0.0), Analysis(arch, rigid).limit(0.0)
    assert lv.status == la.status == "optimal"
    assert lv.model == "spatial" and la.model == "planar"  # two different conic programs
    assert lv.lambda_max == pytest.approx(la.lambda_max, rel=1e-7)
    soft = Material(friction=0.8, normal_stiffness=1e6)
    sett = {"right": [0.0005, 0.0, -0.0002, 0.0, 0.0, 0.0]}
    rv = Analysis(vault, soft).solve(0.1, 0.0, sett)
    ra = Analysis(arch, soft).solve(0.1, 0.0, sett)
    assert rv.status == ra.status == "optimal"
    assert np.allclose(rv.support_wrenches, courses * ra.support_wrenches, atol=1e-7 * vault.total_weight)


# ---------------------------------------------------------------- symmetry of the limit
@lru_cache(maxsize=None)
def _analysis(name):
    return Analysis(VAULTS[name](), Material(friction=0.8))


def _lam(name, alpha):
    lim = _analysis(name).limit(alpha)
    assert lim.status == "optimal" and lim.certificate_gap < 1e-6
    return lim.lambda_max


@pytest.mark.parametrize("name", ["barrel-stack", "barrel-running"])
def test_barrel_vault_limit_is_symmetric(name):
    """Both barrel vaults are symmetric about the planes x = 0 and y = 0 (the running bond
    with an odd number of courses maps course c onto course C-1-c, of the same parity): the
    load in direction alpha meets the mirror image of the vault under alpha + 180 and -alpha."""
    for alpha in (0.0, 35.0, 90.0):
        ref = _lam(name, alpha)
        assert _lam(name, alpha + 180.0) == pytest.approx(ref, rel=1e-6)
        assert _lam(name, -alpha) == pytest.approx(ref, rel=1e-6)


def test_square_groin_vault_limit_has_the_symmetry_of_the_square():
    """The square groin vault maps onto itself under the quarter turns and the mirrors about
    the axes and the diagonals: lambda_max is the same for alpha, alpha + 90, -alpha, 90 - alpha."""
    ref = _lam("groin-square", 20.0)
    for alpha in (110.0, 200.0, 290.0, -20.0, 70.0):
        assert _lam("groin-square", alpha) == pytest.approx(ref, rel=1e-6)
    assert _lam("groin-square", 0.0) == pytest.approx(_lam("groin-square", 90.0), rel=1e-6)


def test_rectangular_groin_vault_limit_has_the_symmetry_of_the_rectangle():
    for alpha in (0.0, 30.0, 90.0):
        ref = _lam("groin-rectangle", alpha)
        for image in (alpha + 180.0, -alpha, 180.0 - alpha):
            assert _lam("groin-rectangle", image) == pytest.approx(ref, rel=1e-6)
    # no quarter-turn symmetry: the long and the short direction differ
    assert abs(_lam("groin-rectangle", 0.0) / _lam("groin-rectangle", 90.0) - 1.0) > 1e-3
