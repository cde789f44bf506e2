"""Assembly files: tce JSON, OBJ, COMPAS JSON (the bundled compas_cra samples), errors, and the samples' statics."""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

import tce
from tce.structures.arch import semicircular_arch
from tce.structures.assembly import AssemblyError
from tce.structures.geometry import GeometryError, box, polygon_area
from tce.structures.io import load_assembly, save_assembly_json
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.solve import TCESolver

DATA = Path(tce.__file__).parent / "data" / "assemblies"
CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]


def _cube(lo, hi):
    return box(lo, hi).vertices.tolist()


def _doc(*blocks, **extra):
    return dict(blocks=list(blocks), **extra)


def _block(name, lo, hi, faces=None, **kw):
    return dict(name=name, vertices=_cube(lo, hi), faces=faces or [list(f) for f in box(lo, hi).faces], **kw)


def _write(tmp_path, doc, name="a.json"):
    p = tmp_path / name
    p.write_text(json.dumps(doc))
    return p


def test_tce_json_stack_of_two(tmp_path):
    p = _write(tmp_path, _doc(
        _block("base", [0, 0, -1], [1, 1, 0], support=True),
        _block("top", [0.2, 0, 0], [1.2, 1, 1], unit_weight=25.0),
        unit_weight=18.0,
    ))
    asm = load_assembly(p)
    assert asm.names == ("base", "top") and asm.support_names == ("base",)
    assert [b.unit_weight for b in asm.blocks] == [18.0, 25.0]
    (itf,) = asm.interfaces
    assert (itf.a, itf.b) == (0, 1) and np.allclose(itf.normal, [0, 0, 1]) and itf.area == pytest.approx(0.8)
    assert asm.meta["format"] == "tce-json" and asm.meta["interfaces"] == "detected"
    # overrides
    asm2 = load_assembly(p, supports=["top"], unit_weight=10.0)
    assert asm2.support_names == ("top",) and [b.unit_weight for b in asm2.blocks] == [10.0, 25.0]
    asm3 = load_assembly(p, unit_weight={"base": 1.0})
    assert [b.unit_weight for b in asm3.blocks] == [1.0, 25.0]


def test_units_are_converted(tmp_path):
    p = _write(tmp_path, _doc(
        _block("base", [0, 0, -1000], [1000, 1000, 0], support=True),
        _block("top", [0, 0, 0], [1000, 1000, 1000]),
        units={"length": "mm", "force": "N"}, unit_weight=20000.0 * 1e-9,  # N/mm^3
    ))
    asm = load_assembly(p)
    assert asm.blocks[1].volume == pytest.approx(1.0)
    assert asm.blocks[1].unit_weight == pytest.approx(20.0)


def test_round_trip_of_a_generated_arch(tmp_path):
    arch = semicircular_arch()
    p = save_assembly_json(arch, tmp_path / "sub" / "arch.json")
    back = load_assembly(p)
    assert back.meta["interfaces"] == "from file" and back.meta["generator"] == "semicircular_arch"
    assert back.names == arch.names and back.support_names == arch.support_names
    assert np.allclose(back.weights, arch.weights, rtol=1e-14)
    for i, j in zip(back.interfaces, arch.interfaces):
        assert (i.a, i.b) == (j.a, j.b) and np.allclose(i.points, j.points) and np.allclose(i.normal, j.normal)
    detected = load_assembly(p, detect=True)
    assert [(i.a, i.b) for i in detected.interfaces] == [(i.a, i.b) for i in arch.interfaces]


def test_obj(tmp_path):
    lines = []
    base = 0
    for name, lo, hi in (("ground", [0, 0, -1], [2, 1, 0]), ("brick", [0.5, 0, 0], [1.5, 1, 0.5])):
        lines.append(f"o {name}")
        lines += [f"v {x} {y} {z}" for x, y, z in _cube(lo, hi)]
        lines += ["f " + " ".join(f"{i + 1 + base}/1/1" for i in f) for f in CUBE_FACES]
        base += 8
    p = tmp_path / "two.obj"
    p.write_text("# two boxes\n" + "\n".join(lines) + "\n")
    asm = load_assembly(p, supports=["ground"])
    assert asm.names == ("ground", "brick") and len(asm.interfaces) == 1
    assert asm.interfaces[0].area == pytest.approx(1.0)
    with pytest.raises(AssemblyError, match="no support"):
        load_assembly(p)
    with pytest.raises(AssemblyError, match="not found"):
        load_assembly(p, supports=["nope"])


@pytest.mark.parametrize(
    "mutate, exc, words",
    [
        (lambda b: b["faces"].pop(), GeometryError, ["broken", "not closed"]),
        (lambda b: b.update(faces=[f[::-1] for f in b["faces"]]), GeometryError, ["broken", "inverted"]),
        (lambda b: b["vertices"][6].__setitem__(2, 2.3), GeometryError, ["broken", "not planar"]),
        (lambda b: b.update(faces=[[0, 1, 99]]), AssemblyError, ["broken", "faces[0][2]", "from 0 to 7"]),
    ],
    ids=["open", "inverted", "non-planar", "bad-index"],
)
def test_broken_block_is_named(tmp_path, mutate, exc, words):
    broken = _block("broken", [0, 0, 1], [1, 1, 2])
    mutate(broken)
    p = _write(tmp_path, _doc(_block("base", [0, 0, 0], [1, 1, 1], support=True), broken))
    with pytest.raises(exc) as info:
        load_assembly(p)
    for w in words + ["a.json"]:
        assert w in str(info.value)


def test_assembly_level_errors_name_file_and_blocks(tmp_path):
    base = _block("base", [0, 0, 0], [1, 1, 1], support=True)
    with pytest.raises(AssemblyError, match=r"a\.json.*'base' and 'intruder'"):
        load_assembly(_write(tmp_path, _doc(base, _block("intruder", [0.5, 0.5, 0.5], [1.5, 1.5, 1.5]))))
    with pytest.raises(AssemblyError, match=r"'floating'.*touch nothing"):
        load_assembly(_write(tmp_path, _doc(base, _block("top", [0, 0, 1], [1, 1, 2]),
                                            _block("floating", [5, 5, 5], [6, 6, 6]))))
    with pytest.raises(AssemblyError, match="no support"):
        load_assembly(_write(tmp_path, _doc(dict(base, support=False), _block("top", [0, 0, 1], [1, 1, 2]))))
    with pytest.raises(AssemblyError, match="duplicate"):
        load_assembly(_write(tmp_path, _doc(base, dict(base))))
    with pytest.raises(AssemblyError, match="unknown file type"):
        load_assembly(tmp_path / "x.stl")
    bad = tmp_path / "bad.json"
    bad.write_text("{nope")
    with pytest.raises(AssemblyError, match="bad.json"):
        load_assembly(bad)


# ---------------------------------------------------------------- the compas_cra samples
# README table: supports by node key, friction and unit weight from the sample scripts
# (Heyman, mu = None, when the script gives none; unit weight 20 kN/m^3 when none is given).
# Every sample loads with the loader's default options: only the supports (not in the files)
# and the unit weights are given.
SAMPLES = {
    "cubes": dict(supports=[0], mu=0.84, uw=None, pairs={("0", "1"), ("1", "2")}, n=2),
    "type-b": dict(supports=[0, 1], mu=None, uw=None, pairs={("0", "1"), ("0", "2"), ("1", "2")}, n=3),
    "shelf": dict(supports=[0], mu=0.9, uw=1.0, n=19),
    "bridge": dict(supports=[0, 1], mu=0.9, uw={**{str(k): 3.51 for k in range(11, 16)},
                                                **{str(k): 1.0 for k in range(11)}}, n=37),
    "curve-3-blocks": dict(supports=[0], mu=None, uw=1.0, pairs={("0", "1"), ("1", "2")}, n=40),
}


@lru_cache(maxsize=None)
def _load_sample(name):
    c = SAMPLES[name]
    uw = c["uw"]
    return load_assembly(DATA / f"{name}.json", supports=c["supports"], unit_weight=uw)


@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_sample_loads_and_stands(name):
    c = SAMPLES[name]
    asm = _load_sample(name)
    assert asm.meta["format"] == "compas-json"
    assert asm.meta["interfaces"] == ("from file" if name == "curve-3-blocks" else "detected")
    pairs = {(asm.names[i.a], asm.names[i.b]) for i in asm.interfaces}
    if "pairs" in c:
        assert pairs == c["pairs"]
    assert len(asm.interfaces) == c["n"]
    res = TCESolver(build_model(asm, "spatial"), Material(friction=c["mu"])).solve(0.0)
    assert res.status == "optimal"
    assert res.support_wrenches[:, 2].sum() == pytest.approx(asm.total_weight, rel=1e-7)


def _stored_interfaces(raw):
    """The curved sample's stored interfaces: (u, v, points, frame z axis), read here directly."""
    out = []
    for u, row in raw["data"]["graph"]["data"]["edge"].items():
        for v, data in row.items():
            for item in data["interfaces"]:
                fr = item["data"]["frame"]["data"]
                out.append((u, v, np.array(item["data"]["points"]), np.cross(fr["xaxis"], fr["yaxis"])))
    return out


def test_curved_sample_uses_its_stored_interfaces():
    """The 40 stored strips (20 per curved contact) become the interfaces, unchanged, with the
    normal from the block of lower index into the other one (the frames' z axes point from
    edge key u into v, here from the upper block into the lower one)."""
    asm = _load_sample("curve-3-blocks")
    stored = _stored_interfaces(json.loads((DATA / "curve-3-blocks.json").read_text()))
    assert len(asm.interfaces) == len(stored) == 40
    for itf, (u, v, pts, z) in zip(asm.interfaces, stored):
        assert (asm.names[itf.a], asm.names[itf.b]) == tuple(sorted((u, v)))
        assert np.allclose(itf.points, pts[::-1] if u > v else pts, atol=1e-12)
        assert np.allclose(itf.normal, (-z if u > v else z) / np.linalg.norm(z), atol=1e-12)
        assert itf.normal @ (asm.blocks[itf.b].centroid - asm.blocks[itf.a].centroid) > 0


def test_curved_sample_detection_fallback_matches_the_stored_contact_area():
    """Detection is still there: with loose tolerances it finds the curved contacts between the
    differently meshed facets, over the stored interfaces' area within 3 %."""
    asm = load_assembly(DATA / "curve-3-blocks.json", supports=[0], detect=True, tol=1e-2, angle_tol=0.2,
                        min_area=1e-6, check_overlap=False)
    assert asm.meta["interfaces"] == "detected"
    stored = _stored_interfaces(json.loads((DATA / "curve-3-blocks.json").read_text()))
    for key in {tuple(sorted((u, v))) for u, v, _, _ in stored}:
        area = sum(polygon_area(p) for u, v, p, _ in stored if tuple(sorted((u, v))) == key)
        found = sum(i.area for i in asm.interfaces if (asm.names[i.a], asm.names[i.b]) == key)
        assert found == pytest.approx(area, rel=0.03)


def test_curved_sample_faces_are_non_planar():
    """Its quads are warped (COMPAS meshes): split into triangles by default for COMPAS files,
    reported when asked to."""
    assert _load_sample("curve-3-blocks").meta["faces_triangulated"] > 0
    with pytest.raises(GeometryError, match=r"curve-3-blocks.json: block '0'.*not planar"):
        load_assembly(DATA / "curve-3-blocks.json", supports=[0], nonplanar="error")


def _compas_doc(edge_interfaces):
    """A COMPAS assembly of two unit cubes (node 0 under node 1) with stored interfaces on edge 1 -> 0."""
    def mesh(lo, hi):
        b = box(lo, hi)
        return {"dtype": "compas.datastructures/Mesh", "data": {
            "vertex": {str(k): dict(zip("xyz", v)) for k, v in enumerate(b.vertices.tolist())},
            "face": {str(k): list(f) for k, f in enumerate(b.faces)}}}
    nodes = {"0": {"block": mesh([0, 0, 0], [1, 1, 1])}, "1": {"block": mesh([0, 0, 1], [1, 1, 2])}}
    edges = {"0": {}, "1": {"0": {"interfaces": edge_interfaces}}}
    return {"dtype": "compas_assembly.datastructures/Assembly",
            "data": {"graph": {"dtype": "compas.datastructures/Graph", "data": {"node": nodes, "edge": edges}}}}


def _stored(points, zaxis=(0.0, 0.0, -1.0)):
    x = np.cross(zaxis, [0.0, 1.0, 0.0]) if abs(zaxis[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    y = np.cross(zaxis, x)
    frame = {"dtype": "compas.geometry/Frame", "data": {"point": points[0], "xaxis": x.tolist(), "yaxis": y.tolist()}}
    return {"dtype": "compas_assembly.datastructures/Interface", "data": {"points": points, "frame": frame}}


SQUARE = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]]


def test_compas_stored_interface_is_used(tmp_path):
    half = [[0.0, 0.0, 1.0], [0.5, 0.0, 1.0], [0.5, 1.0, 1.0], [0.0, 1.0, 1.0]]
    asm = load_assembly(_write(tmp_path, _compas_doc([_stored(half)])), supports=[0])
    (itf,) = asm.interfaces
    assert (itf.a, itf.b) == (0, 1) and np.allclose(itf.normal, [0, 0, 1])
    assert itf.area == pytest.approx(0.5)  # the stored polygon, not the detected full square
    assert asm.meta["interfaces"] == "from file"
    assert len(load_assembly(_write(tmp_path, _compas_doc([_stored(half)])), supports=[0], detect=True).interfaces) == 1
    assert load_assembly(_write(tmp_path, _compas_doc([_stored(half)])), supports=[0], detect=True).interfaces[0].area == 1.0


@pytest.mark.parametrize(
    "item, words",
    [
        (_stored([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.02], [0.0, 1.0, 1.0]]), "not planar"),
        (_stored([[p[0], p[1], 0.0] for p in SQUARE]), "does not lie on block '1'"),
        (_stored([[p[0] + 3.0, p[1], 1.0] for p in SQUARE]), "does not lie on block '0'"),
        (_stored(SQUARE, zaxis=(0.0, 0.6, -0.8)), "plane of its frame"),
        (_stored(SQUARE[:2]), "at least 3"),
        ({"data": {"frame": None}}, "no 'points'"),
    ],
)
def test_compas_stored_interface_errors_name_the_interface(tmp_path, item, words):
    with pytest.raises(AssemblyError, match=rf"a.json: .*interface 0 of edge 1-0.*{words}"):
        load_assembly(_write(tmp_path, _compas_doc([item])), supports=[0])


def test_bundled_data_has_licence_and_readme():
    assert "MIT" in (DATA / "LICENSE-compas_cra.txt").read_text()
    assert "compas_cra" in (DATA / "README.md").read_text()
