"""Object generators: valid part trees, labels, sizes, no interpenetration closed or across joint ranges."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from scenes.errors import SceneSpecError
from scenes.generators import CABINET_LAYOUTS, FRIDGE_LAYOUTS, GENERATORS, make_cabinet, make_refrigerator
from scenes.description import mass_properties
from scenes.description import Shape
from scenes.model import JointType
from scenes.overlap import part_overlaps
from scenes.description import pose
from scenes.validate import validate_object

SEEDS = range(6)


@pytest.mark.parametrize("category", sorted(GENERATORS))
def test_objects_are_valid_and_do_not_interpenetrate_across_their_ranges(category):
    for seed in SEEDS:
        obj = GENERATORS[category](np.random.default_rng(seed))
        validate_object(obj)
        assert part_overlaps(obj) == [], f"{category} seed {seed} closed"
        for j in obj.joints:
            if j.movable:
                for q in np.linspace(j.lower, j.upper, 5)[1:]:
                    assert part_overlaps(obj, {j.child: q}) == [], f"{category} seed {seed} joint {j.child} at {q}"


@pytest.mark.parametrize("layout", CABINET_LAYOUTS)
def test_cabinet_layouts_have_drawers_doors_and_handles(layout):
    for seed in SEEDS:
        cab = make_cabinet(np.random.default_rng(seed), layout)
        labels = [p.label for p in cab.parts]
        n_drawers, n_doors = labels.count("drawer"), labels.count("door")
        assert labels.count("handle") == n_drawers + n_doors
        if layout in ("drawers_doors", "door_drawers_door", "drawers_over_doors"):
            assert n_drawers >= 1 and n_doors >= 1
        for j in cab.joints:
            child = cab.part(j.child)
            if child.label == "drawer":
                assert j.type is JointType.PRISMATIC and np.allclose(j.axis, [1, 0, 0])
                assert cab.part(j.handle).label == "handle"
                depth = max(s.size[0] for s in child.shapes)
                assert 0.5 * depth < j.upper <= 0.8 * depth + 1e-9
            if child.label == "door":
                assert j.type is JointType.REVOLUTE and abs(abs(j.axis[2]) - 1) < 1e-12
                assert 1.6 <= j.upper <= 1.9


def test_cabinet_body_is_hollow_and_drawer_is_an_open_box():
    cab = make_cabinet(np.random.default_rng(1), "drawer_stack")
    body = cab.root
    assert len(body.shapes) >= 6                   # panels, not one solid block
    drawer = next(p for p in cab.parts if p.label == "drawer")
    assert len(drawer.shapes) == 5                  # bottom, 2 sides, back, front panel; no top
    lo, hi = cab.bounds()
    box_tops = [s.T_link_shape[2, 3] + s.size[2] / 2 for s in drawer.shapes[:4]]
    assert max(box_tops) <= drawer.shapes[4].T_link_shape[2, 3] + drawer.shapes[4].size[2] / 2 + 1e-9
    assert lo[2] == pytest.approx(0.0) and hi[2] > 0.7


def test_drawer_slides_out_and_door_swings_outwards():
    cab = make_cabinet(np.random.default_rng(2), "drawers_doors")
    for j in cab.joints:
        if not j.movable:
            continue
        T0 = cab.T_object_part_at(j.child)
        T1 = cab.T_object_part_at(j.child, {j.child: j.upper})
        if j.type is JointType.PRISMATIC:
            assert T1[0, 3] - T0[0, 3] == pytest.approx(j.upper)
        else:
            free_edge = [p.T_link_shape[:3, 3] for p in cab.part(j.child).shapes][0] * 2
            x0 = (T0 @ np.append(free_edge, 1))[0]
            x1 = (T1 @ np.append(free_edge, 1))[0]
            assert x1 > x0 + 0.2                     # the free edge moved out in front (+x)
            assert np.allclose(T1[:3, 3], T0[:3, 3])  # the hinge line stays put


@pytest.mark.parametrize("layout", FRIDGE_LAYOUTS)
def test_refrigerator_layouts(layout):
    fr = make_refrigerator(np.random.default_rng(0), layout)
    doors = [p for p in fr.parts if p.label == "door"]
    assert len(doors) == (1 if layout == "single" else 2)
    assert fr.size[2] > 1.5


def test_table_chair_bed_are_rigid_with_expected_parts():
    rng = np.random.default_rng(0)
    t = GENERATORS["table"](rng)
    c = GENERATORS["chair"](rng, arms=True)
    b = GENERATORS["bed"](rng)
    assert all(not j.movable for o in (t, c, b) for j in o.joints)
    assert {p.label for p in c.parts} == {"seat", "leg", "back", "arm"}
    assert {p.label for p in b.parts} == {"frame", "leg", "headboard", "mattress"}
    assert t.root.label == "top" and 0.7 < t.size[2] < 0.8
    # contacts are symmetric pairs of existing parts; the part tree is among them
    for o in (t, c, b):
        ids = {p.id for p in o.parts}
        assert all(a < b_ and a in ids and b_ in ids for a, b_ in o.contacts)
        assert {tuple(sorted((j.parent, j.child))) for j in o.joints if j.parent is not None} <= set(o.contacts)


def test_generators_are_deterministic_and_seed_dependent():
    for category, make in GENERATORS.items():
        a, b = make(np.random.default_rng(5)), make(np.random.default_rng(5))
        c = make(np.random.default_rng(6))
        assert all(p.isclose(q) for p, q in zip(a.parts, b.parts)), category
        assert not np.allclose(a.size, c.size), category


def test_overlap_check_catches_a_drawer_pushed_into_its_body():
    cab = make_cabinet(np.random.default_rng(0), "drawer_stack")
    j = next(j for j in cab.joints if j.type is JointType.PRISMATIC)
    assert part_overlaps(cab, {j.child: -0.03})     # pushed 3 cm in: its front hits the carcass
    assert not part_overlaps(cab, {j.child: j.upper})


def test_inertia_of_a_single_box_matches_the_closed_form():
    cab = make_cabinet(np.random.default_rng(0))
    box = Shape.box([0.2, 0.4, 0.6], pose([0.1, 0.2, 0.3]))
    part = dataclasses.replace(cab.root, shapes=(box,), density=500.0)
    m, com, inertia = mass_properties(part.shapes, part.density)
    assert m == pytest.approx(0.048 * 500)
    assert np.allclose(com, [0.1, 0.2, 0.3])
    assert np.allclose(np.diag(inertia), m / 12 * np.array([0.16 + 0.36, 0.04 + 0.36, 0.04 + 0.16]))


@pytest.mark.parametrize("mutate, match", [
    (lambda o: dataclasses.replace(o, parts=o.parts + (dataclasses.replace(o.parts[1]),)), "duplicate part ids"),
    (lambda o: dataclasses.replace(o, parts=(dataclasses.replace(o.parts[0], label="lid"),) + o.parts[1:]),
     "unknown label 'lid'"),
    (lambda o: dataclasses.replace(o, joints=o.joints[:-1]), "exactly one joint"),
    (lambda o: dataclasses.replace(o, joints=tuple(dataclasses.replace(j, upper=-0.1) if j.movable else j
                                                   for j in o.joints)), r"limits \[0.0, -0.1\]"),
    (lambda o: dataclasses.replace(o, joints=tuple(dataclasses.replace(j, axis=2 * j.axis) if j.movable else j
                                                   for j in o.joints)), "unit vector"),
    (lambda o: dataclasses.replace(o, parts=(dataclasses.replace(
        o.parts[0], shapes=(Shape.box([0.1, -0.2, 0.1], np.eye(4)),)),) + o.parts[1:]), "must be > 0"),
])
def test_invalid_objects_are_rejected_with_names(mutate, match):
    cab = make_cabinet(np.random.default_rng(0), "drawers_doors")
    with pytest.raises(SceneSpecError, match=match) as e:
        validate_object(mutate(cab))
    assert "cabinet0" in str(e.value)


def test_unknown_layout_is_rejected():
    with pytest.raises(ValueError, match="unknown cabinet layout 'tall'"):
        make_cabinet(np.random.default_rng(0), "tall")
