"""No finite limit, explained: which contacts carry the lateral load without limit, and why.

The references are built here: blocks between walls, where the load path of the lateral load
is known without tce (a block pushed against a wall; a row of blocks pushed into one), and the
two bundled samples whose limit is unbounded (type-b's wedge in a notch, the shelf's clamped
blocks)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from tce.analysis.diagnose import diagnose, explain_no_limit, no_limit_reason
from tce.analysis.loadpath import load_path
from tce.core.analysis import Analysis
from tce.core.limit import LimitSolver
from tce.core.material import Material
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import box
from tce.cli import main

from helpers import block_on_support
from structures.test_io import DATA, _load_sample


def _between_walls(n_boxes: int) -> Assembly:
    """A floor, a west and an east wall (supports), and ``n_boxes`` unit boxes in a row filling
    the gap between the walls exactly: every box touches the floor, its neighbours and, at the
    ends of the row, a wall."""
    w = float(n_boxes)
    blocks = [
        Block("floor", box([0, 0, -0.5], [w, 1, 0]), 20.0, True),
        Block("west", box([-0.5, 0, 0], [0, 1, 1]), 20.0, True),
        Block("east", box([w, 0, 0], [w + 0.5, 1, 1]), 20.0, True),
    ]
    blocks += [Block(f"b{k + 1}", box([k, 0, 0], [k + 1, 1, 1]), 20.0) for k in range(n_boxes)]

    def face_x(x):  # the square x = const, counter-clockwise about +x
        return np.array([[x, 0, 0], [x, 1, 0], [x, 1, 1], [x, 0, 1]], float)

    itfs = [Interface(0, 3 + k, np.array([[k, 0, 0], [k + 1, 0, 0], [k + 1, 1, 0], [k, 1, 0]], float), [0, 0, 1])
            for k in range(n_boxes)]
    itfs.append(Interface(1, 3, face_x(0.0), [1, 0, 0]))
    itfs.append(Interface(2, 2 + n_boxes, face_x(w)[::-1], [-1, 0, 0]))
    itfs += [Interface(3 + k, 4 + k, face_x(k + 1.0), [1, 0, 0]) for k in range(n_boxes - 1)]
    return Assembly(tuple(blocks), tuple(itfs))


@pytest.mark.parametrize("alpha, wall", [(0.0, "east|b1"), (180.0, "west|b1")])
def test_a_block_pushed_against_a_wall_goes_straight_into_it(alpha, wall):
    """With friction, the floor cannot take shear without a normal force, which the lateral load
    alone does not give: the least force that carries it is the wall's push, equal to the load."""
    an = Analysis(_between_walls(1), Material(friction=0.5), model="spatial")
    assert an.limit(alpha).status == "unbounded"
    why = explain_no_limit(an, alpha)
    assert why.reason == "into_support"
    assert why.interfaces == [wall] and why.blocks == ["b1"]
    assert f"straight into the support {wall.split('|')[0]}: block b1 bears on it through {wall}" in why.summary
    ray = LimitSolver(an.model("spatial"), an.material).lateral_ray(alpha)
    model = an.model("spatial")
    total = np.zeros(3)
    for c, k in enumerate(model.contact_interface):
        total += ray[c] @ model.assembly.interfaces[k].frame  # global force on block B
    # the wall's contacts push back the whole lateral load, W = 20 kN, normal to the wall
    wall_k = [k for k, i in enumerate(model.assembly.interfaces) if f"{model.assembly.names[i.a]}|{model.assembly.names[i.b]}" == wall]
    fn = ray[np.isin(model.contact_interface, wall_k), 0].sum()
    assert fn == pytest.approx(20.0, rel=1e-6)
    assert np.abs(ray[~np.isin(model.contact_interface, wall_k)]).max() <= 1e-6 * 20.0


def test_a_row_of_blocks_locks_against_the_far_wall():
    """Two boxes pushed east: the west box can only push on its neighbour (a wall does not pull),
    which passes both loads to the east wall: a free-free interface carries the certificate."""
    an = Analysis(_between_walls(2), Material(friction=0.5), model="spatial")
    why = explain_no_limit(an, 0.0)
    assert why.reason == "locked"
    assert why.interfaces == ["east|b2", "b1|b2"]  # most loaded first: 40 kN, then 20 kN
    assert why.blocks == ["b2"]
    assert "block b2 bears on the support east and block b1 is held between its neighbours" in why.summary


def test_a_block_clamped_between_walls_locks_along_them():
    """Along the walls the box is jammed: the two walls can squeeze it with any pair of equal
    and opposite normal forces, and their friction then carries any load along y."""
    an = Analysis(_between_walls(1), Material(friction=0.5), model="spatial")
    why = explain_no_limit(an, 90.0)
    assert why.reason == "into_support"
    assert {"east|b1", "west|b1"} <= set(why.interfaces)


def test_a_finite_limit_is_not_explained_away():
    an = Analysis(block_on_support(b=0.4, h=1.0), Material(friction=0.8))
    lim = an.limit(0.0)  # the block rocks at lambda = b / h
    assert lim.status == "optimal" and lim.lambda_max == pytest.approx(0.4, rel=1e-6)
    assert explain_no_limit(an, 0.0).reason == "finite"
    why = explain_no_limit(an, 0.0, reached=0.3)
    assert why.reason == "beyond_cap" and "raise [loads] lambda_cap" in why.summary
    lp = load_path(an, 0.0, step=0.1, atol=1e-3)
    assert lp.outcome == "limit" and no_limit_reason(an, lp) == ""


def test_type_b_wedge_goes_straight_into_its_supports():
    an = Analysis(_load_sample("type-b"), Material())  # Heyman, as in test_io.SAMPLES
    for alpha in (0.0, 90.0):
        why = explain_no_limit(an, alpha)
        assert why.reason == "into_support"
        assert sorted(why.interfaces) == ["0|2", "1|2"] and why.blocks == ["2"]
        assert "Heyman" in why.summary
    lp = load_path(an, 0.0, step=2.0, lam_cap=6.0)
    assert lp.outcome == "no_limit"
    assert no_limit_reason(an, lp) == explain_no_limit(an, 0.0, 6.0).summary


def test_shelf_blocks_lock():
    an = Analysis(_load_sample("shelf"), Material(friction=0.9))
    why = explain_no_limit(an, 90.0)
    assert why.reason == "locked"
    assert "blocks 3 and 7 are held between their neighbours" in why.summary
    assert {"1|3", "3|4", "3|5", "5|7", "7|8"} <= set(why.interfaces)  # 3 and 7 touch no support
    d = diagnose(an, 1000.0, 90.0)
    assert d.status == "optimal" and d.no_limit is not None and d.no_limit.reason == "locked"


STUDY = """
[study]
name = "typeb"
[structure]
type = "file"
path = "{path}"
supports = ["0", "1"]
[loads]
alpha = [0.0, 90.0]
lambda_step = 2.0
lambda_cap = 4.0
"""


def test_dataset_and_show_carry_the_reason(tmp_path, capsys):
    study = tmp_path / "typeb.toml"
    study.write_text(STUDY.format(path=(DATA / "type-b.json").as_posix()))
    assert main(["-q", "run", str(study), "--out", str(tmp_path), "--jobs", "1", "--no-plots"]) == 0
    ds = xr.load_dataset(tmp_path / "typeb" / "results.nc")
    assert list(ds["outcome"].values) == ["no_limit", "no_limit"]
    reasons = [str(r) for r in ds["no_limit_reason"].values]
    assert all("goes straight into the supports 0 and 1" in r for r in reasons)
    capsys.readouterr()
    assert main(["show", str(tmp_path / "typeb" / "results.nc")]) == 0
    out = capsys.readouterr().out
    for name, why in zip(ds["scenario"].values, reasons):
        assert f"{name}: no_limit: the direct limit is unbounded, the live loads are carried at any lambda; {why}" in out
