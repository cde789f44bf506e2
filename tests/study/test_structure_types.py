"""Every generator is a study [structure] type: validated, built with its own support names,
swept where it has the swept key, refused by name where it has not."""

from __future__ import annotations

import numpy as np
import pytest

from tce.structures.bridge import arch_bridge
from tce.structures.arch import pointed_arch, segmental_arch, semicircular_arch, semicircular_arch_on_piers
from tce.structures.dome import hemispherical_dome
from tce.structures.vault import barrel_vault, groin_vault
from tce.study.schema import STRUCTURE_TYPES, StudyError, build_structure, parse_study

# type -> (keys given in the study, the generator called directly with the same values, supports)
TYPES = {
    "semicircular_arch": ("voussoirs = 6", lambda: semicircular_arch(voussoirs=6), ("left", "right")),
    "pointed_arch": ("span = 3.0\nrise = 2.0\nvoussoirs = 8", lambda: pointed_arch(3.0, rise=2.0, voussoirs=8),
                     ("left", "right")),
    "segmental_arch": ("span = 3.0\nrise = 0.8\nvoussoirs = 7", lambda: segmental_arch(3.0, 0.8, voussoirs=7),
                       ("left", "right")),
    "arch_on_piers": ("voussoirs = 6\npier_height = 2.0", lambda: semicircular_arch_on_piers(voussoirs=6, pier_height=2.0),
                      ("left", "right")),
    "barrel_vault": ("voussoirs = 6\ncourses = 3\nbond = \"running\"\nsupports = \"courses\"",
                     lambda: barrel_vault(voussoirs=6, courses=3, bond="running", supports="courses"),
                     ("left01", "left02", "left03", "right01", "right02", "right03")),
    "groin_vault": ("span_y = 3.0\nvoussoirs = 4", lambda: groin_vault(span_y=3.0, voussoirs=4), ("ne", "nw", "sw", "se")),
    "dome": ("sectors = 4\ncourses = 2", lambda: hemispherical_dome(sectors=4, courses=2), ("s01", "s02", "s03", "s04")),
    "arch_bridge": ("spans = 2\nvoussoirs = 6", lambda: arch_bridge(spans=2, voussoirs=6),
                    ("abutment_left", "abutment_right", "foundation1")),
}


def _study(kind: str, keys: str, extra: str = "") -> str:
    return f'[study]\nname = "t"\n\n[structure]\ntype = "{kind}"\n{keys}\n{extra}'


def test_every_generator_is_a_type():
    assert set(TYPES) | {"file"} == set(STRUCTURE_TYPES)


@pytest.mark.parametrize("kind", sorted(TYPES))
def test_type_builds_the_generators_assembly(kind):
    keys, direct, supports = TYPES[kind]
    (sc,) = parse_study(_study(kind, keys)).scenarios()
    asm, ref = build_structure(sc.structure), direct()
    assert asm.names == ref.names and asm.support_names == supports
    assert np.allclose(asm.centroids, ref.centroids, atol=1e-12)
    assert asm.meta == ref.meta


@pytest.mark.parametrize("kind", sorted(TYPES))
def test_settling_an_unknown_support_names_the_supports(kind):
    keys, _, supports = TYPES[kind]
    with pytest.raises(StudyError, match=rf"scenarios.s.nowhere: .* no support named 'nowhere'; fix: use one of \[{supports[0]!r}"):
        parse_study(_study(kind, keys, "[scenarios.s]\nnowhere = [0, 0, 0, 0, 0, 0]\n"))


def test_thickness_sweep_builds_each_vault():
    study = parse_study(_study("barrel_vault", "voussoirs = 4\ncourses = 3", "[sweep]\nthickness = [0.15, 0.25]\n"))
    weights = [build_structure(sc.structure).total_weight for sc in study.scenarios()]
    assert weights[1] > weights[0]
    study = parse_study(_study("groin_vault", "voussoirs = 4", "[sweep]\nthickness = [0.15, 0.25]\n"))
    assert [build_structure(sc.structure).meta["thickness"] for sc in study.scenarios()] == [0.15, 0.25]


@pytest.mark.parametrize(
    "kind, keys, sweep",
    [("groin_vault", "voussoirs = 4", "inner_radius"), ("pointed_arch", "", "radius"), ("dome", "", "depth")],
)
def test_sweeping_a_key_the_type_has_not_is_refused(kind, keys, sweep):
    with pytest.raises(StudyError, match=rf"sweep.{sweep}: the structure type '{kind}' has no parameter '{sweep}'"):
        parse_study(_study(kind, keys, f"[sweep]\n{sweep} = [1.0, 2.0]\n"))


@pytest.mark.parametrize(
    "kind, keys, where",
    [
        ("groin_vault", "voussoirs = 7", "structure.voussoirs: .* multiple of 2"),
        ("barrel_vault", 'bond = "english"', "structure.bond"),
        ("barrel_vault", 'supports = "piers"', "structure.supports"),
        ("pointed_arch", "rise = 0.5", "cannot build it: rise must be >= span / 2"),
        ("segmental_arch", "rise = 2.0", "cannot build it: rise must be <= span / 2"),
        ("arch_on_piers", "pier_height = -1.0", "structure.pier_height"),
    ],
)
def test_bad_structure_keys_are_named(kind, keys, where):
    with pytest.raises(StudyError, match=where):
        parse_study(_study(kind, keys))
