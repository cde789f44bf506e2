"""COMPAS 2 block files as the peers write them today (``tests/data/compas2/README.md``): a
compas_cra 0.8 assembly saved with its contacts (points as serialised ``Point`` objects) and
a compas_dem 0.6 ``BlockModel`` with its ``FrictionContact`` objects. The stored contacts
must be the ones tce detects from the geometry on its own (an independent check of the
reading: same block pairs, areas and normals)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tce.structures.assembly import AssemblyError
from tce.structures.io import load_assembly

DATA = Path(__file__).resolve().parents[1] / "data" / "compas2"


def _by_pair(asm):
    return {(asm.names[i.a], asm.names[i.b]): i for i in asm.interfaces}


@pytest.mark.parametrize(
    "name, blocks, supports, contacts",
    [("cra_cubes_contacts.json", 3, ("0",), 2), ("dem_arch_blockmodel.json", 6, ("0", "5"), 5)],
)
def test_stored_contacts_are_the_detected_ones(name: str, blocks: int, supports: tuple, contacts: int) -> None:
    stored = load_assembly(DATA / name)
    detected = load_assembly(DATA / name, detect=True)
    assert stored.meta["interfaces"] == "from file" and detected.meta["interfaces"] == "detected"
    assert len(stored.blocks) == blocks and stored.support_names == supports
    a, b = _by_pair(stored), _by_pair(detected)
    assert sorted(a) == sorted(b) and len(a) == contacts
    for pair, it in a.items():
        assert it.area == pytest.approx(b[pair].area, rel=1e-6)
        np.testing.assert_allclose(it.normal, b[pair].normal, atol=1e-7)


def test_block_model_transformations_are_applied(tmp_path: Path) -> None:
    """A compas_dem element's ``transformation`` moves its mesh (here 1 m up, every block)."""
    doc = json.loads((DATA / "dem_arch_blockmodel.json").read_text())
    lift = {"dtype": "compas.geometry/Transformation",
            "data": {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1.0], [0, 0, 0, 1]]}}
    for element in doc["data"]["elements"].values():
        element["data"]["transformation"] = lift
    doc["data"]["graph"]["edge"] = {}
    (tmp_path / "up.json").write_text(json.dumps(doc))
    moved, here = load_assembly(tmp_path / "up.json"), load_assembly(DATA / "dem_arch_blockmodel.json")
    for b, c in zip(moved.blocks, here.blocks, strict=True):
        np.testing.assert_allclose(b.shape.vertices, c.shape.vertices + [0.0, 0.0, 1.0], atol=1e-12)
    doc["data"]["elements"][next(iter(doc["data"]["elements"]))]["data"]["transformation"]["data"]["matrix"][3] = [1, 0, 0, 1]
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    with pytest.raises(AssemblyError, match=r"transformation.matrix: a projective"):
        load_assembly(tmp_path / "bad.json")


def test_a_point_of_another_type_is_named(tmp_path: Path) -> None:
    doc = json.loads((DATA / "cra_cubes_contacts.json").read_text())
    item = doc["data"]["graph"]["data"]["edge"]["1"]["0"]["interfaces"][0]["data"]
    item["points"][0]["dtype"] = "compas.geometry/Line"
    (tmp_path / "x.json").write_text(json.dumps(doc))
    with pytest.raises(AssemblyError, match=r"x\.json: interface 0 of edge 1-0: points\[0\]: must be a point, got a 'compas.geometry/Line'"):
        load_assembly(tmp_path / "x.json")
