"""Room composer and built-in scenes: required content, no overlap, inside the room, robot clearance."""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import Polygon

from scenes.builtin import SCENES, build_scene
from scenes.composer import RoomComposer
from scenes.config import DEFAULT_COMPOSER, ComposerConfig
from scenes.errors import PlacementError, SceneSpecError
from scenes.footprints import clearance, footprint, handle_reach, room_polygon, sweep
from scenes.generators import make_cabinet, make_refrigerator
from scenes.overlap import OVERLAP_TOLERANCE, object_overlap

SEEDS = range(4)


def _check_room(scene):
    room = room_polygon(scene.room_size).buffer(1e-6)
    objs = scene.objects
    for o in objs:
        assert room.contains(footprint(o)), o.name
        # gravity aligned: z axis up, resting on the floor or on the supporting object's top
        assert np.allclose(o.T_world_object[:3, 2], [0, 0, 1])
        lo, _ = o.bounds()
        assert lo[2] == pytest.approx(0.0, abs=1e-9)
        if o.supported_by is None:
            assert o.T_world_object[2, 3] == pytest.approx(0.0)
        else:
            sup = scene.object(o.supported_by)
            assert o.T_world_object[2, 3] == pytest.approx(sup.T_world_object[2, 3] + sup.bounds()[1][2])
        if any(j.movable for j in o.joints):
            free = clearance(o, DEFAULT_COMPOSER.front_clearance).union(sweep(o))
            assert room.contains(free), o.name
            free = free.union(handle_reach(o, DEFAULT_COMPOSER.robot_reach))
            for other in objs:
                if other.id not in (o.id, o.supported_by) and other.supported_by != o.id:
                    assert not free.intersects(footprint(other)), f"{other.name} blocks {o.name}"
    for i, a in enumerate(objs):
        for b in objs[i + 1:]:
            assert object_overlap(a, b) < OVERLAP_TOLERANCE, f"{scene.name}: {a.name} overlaps {b.name}"


@pytest.mark.parametrize("name", SCENES)
def test_builtin_scenes_are_valid_rooms_for_many_seeds(name):
    for seed in SEEDS:
        _check_room(build_scene(name, seed))


def test_kitchen_has_the_required_objects():
    for seed in SEEDS:
        sc = build_scene("kitchen", seed)
        cats = [o.category for o in sc.objects]
        assert {"cabinet", "microwave", "refrigerator", "table", "chair"} <= set(cats)
        mw = next(o for o in sc.objects if o.category == "microwave")
        assert sc.object(mw.supported_by).category == "cabinet"
        cab = sc.object(mw.supported_by)
        labels = [p.label for p in cab.parts]
        assert "drawer" in labels and "door" in labels
        # microwave faces the same way as its cabinet
        assert np.allclose(mw.T_world_object[:3, 0], cab.T_world_object[:3, 0])


def test_part_and_object_ids_are_unique_in_a_scene():
    sc = build_scene("random", 3)
    pids = [p.id for o in sc.objects for p in o.parts]
    assert len(pids) == len(set(pids))
    assert [o.id for o in sc.objects] == list(range(1, len(sc.objects) + 1))


def test_scenes_are_deterministic_and_seed_dependent():
    a, b, c = build_scene("office", 2), build_scene("office", 2), build_scene("office", 3)
    assert all(np.allclose(x.T_world_object, y.T_world_object) for x, y in zip(a.objects, b.objects))
    assert not all(np.allclose(x.T_world_object, y.T_world_object) for x, y in zip(a.objects, c.objects))


def test_articulated_objects_face_into_the_room():
    sc = build_scene("kitchen", 1)
    for o in sc.objects:
        if any(j.movable for j in o.joints) and o.supported_by is None:
            to_centre = -o.T_world_object[:2, 3]
            assert o.T_world_object[:2, 0] @ to_centre > 0, o.name


def test_composer_refuses_an_object_that_cannot_fit():
    rng = np.random.default_rng(0)
    comp = RoomComposer("tiny", 0, (1.2, 1.2), rng, ComposerConfig(max_tries=20))
    with pytest.raises(PlacementError, match=r"scene 'tiny' \(seed 0\): could not place refrigerator1"):
        comp.against_wall(make_refrigerator(rng))


def test_composer_keeps_the_front_clear_of_other_objects():
    rng = np.random.default_rng(1)
    comp = RoomComposer("two", 1, (3.0, 3.0), rng)
    a = comp.against_wall(make_cabinet(rng, "drawer_stack"), ("wall_north",))
    b = comp.against_wall(make_cabinet(rng, "drawer_stack"), ("wall_south",))
    sc = comp.build()
    fa, fb = sc.object(a), sc.object(b)
    assert DEFAULT_COMPOSER.front_clearance >= 1.0
    assert not clearance(fa, DEFAULT_COMPOSER.front_clearance).intersects(footprint(fb))
    assert isinstance(footprint(fa), Polygon) and footprint(fa).area > 0.1


@pytest.mark.parametrize("name, seed, match", [
    ("garage", 0, "unknown scene 'garage'; expected one of kitchen"),
    ("kitchen", -1, "seed must be a non-negative integer, got -1"),
    ("kitchen", 1.5, "seed must be a non-negative integer, got 1.5"),
])
def test_bad_scene_arguments(name, seed, match):
    with pytest.raises(SceneSpecError, match=match):
        build_scene(name, seed)


def test_object_overlap_sees_interpenetration_but_not_touching():
    sc = build_scene("kitchen", 0)
    cab = next(o for o in sc.objects if o.category == "cabinet")
    mw = next(o for o in sc.objects if o.category == "microwave")
    assert object_overlap(cab, mw) < OVERLAP_TOLERANCE               # resting on it: touching only
    T = mw.T_world_object.copy()
    T[2, 3] -= 0.01                                                  # sunk 1 cm into the top panel
    assert object_overlap(cab, mw.placed(T, mw.supported_by)) > 1e-4
