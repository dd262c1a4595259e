"""A corpus object as a scenes Scene: labelled parts the scanner sees, and joints in the scenes convention
that move each part as the object's own URDF does."""

from __future__ import annotations

import numpy as np
import pytest

import thirdparty
from scenes.description import read_urdf
from scenes.scanner import scan_scene
from scenes.scanner.params import params_for_preset
from thirdparty.scannable import reference_named_as_scan, scene_of


@pytest.mark.parametrize("name", ["kitchen_unit_double_door", "dresser_six", "wall_flap", "microwave_continuous"])
def test_each_part_moves_as_in_the_urdf_with_positive_opening(name, tmp_path):
    o = thirdparty.build_object(thirdparty.spec_named(name), tmp_path)
    scene, joint_part = scene_of(o)
    obj, m = scene.objects[0], read_urdf(o.urdf)
    for f in o.fronts:
        j = m.joints[f.joint]
        sign = 1.0 if j.upper >= -j.lower else -1.0
        value = 0.2 if f.kind == "drawer" else 0.7
        T_scene = obj.T_object_part_at(joint_part[f.joint], {joint_part[f.joint]: value})
        T_urdf = m.T_world_link(f.moving_link, {f.joint: sign * value})
        assert np.allclose(T_scene, T_urdf, atol=1e-9)
        assert obj.joint_of(joint_part[f.joint]).upper > 0


def test_a_scan_labels_the_body_every_front_and_every_handle(tmp_path):
    o = thirdparty.build_object(thirdparty.spec_named("nightstand"), tmp_path)
    scene, _ = scene_of(o)
    scan = scan_scene(scene, params_for_preset("clean"), seed=0)
    labels = {p["id"]: p["label"] for p in scan.labels["objects"][0]["parts"]}
    assert sorted(labels.values()) == ["body", "door", "drawer", "handle", "handle"]
    seen = scan.counts_by_part()
    assert all(seen.get(pid, 0) > 20 for pid in labels), (seen, labels)


def test_the_reference_renamed_as_the_scan_names_its_joints_and_moves_alike(tmp_path):
    o = thirdparty.build_object(thirdparty.spec_named("kitchen_unit_double_door"), tmp_path)
    scene, joint_part = scene_of(o)
    path, names = reference_named_as_scan(o, scene, joint_part, tmp_path / "ref" / "reference.urdf")
    assert names == {"joint_1": "cabinet1_door12_joint", "joint_2": "cabinet1_door14_joint"}
    a, b = read_urdf(o.urdf), read_urdf(path)
    for old, new in names.items():
        assert np.allclose(a.T_world_link(a.joints[old].child, {old: -0.5}),
                           b.T_world_link(b.joints[new].child, {new: -0.5}))


def test_the_counter_an_object_stands_on_is_scanned_as_an_object_of_its_own(tmp_path):
    """A segmentation of a real room labels the counter apart from the microwave on it: the counter is a
    second object (one body part) supporting the first, not part of the microwave's body."""
    pytest.importorskip("mujoco")
    from pathlib import Path
    from thirdparty.mjcf_assets import asset_named, build_mjcf_object
    data = Path(__file__).parent / "data" / "mjcf" / "libero_microwave.xml"
    o = build_mjcf_object(asset_named("libero_microwave"), {}, tmp_path, source=data)
    scene, _ = scene_of(o)
    micro, counter = scene.objects
    assert micro.supported_by == counter.id and [p.label for p in counter.parts] == ["body"]
    top = max(c[2] for s in counter.parts[0].shapes for c in (counter.parts[0].T_object_part @ np.c_[
        s.corners(), np.ones(8)].T).T)
    body = micro.parts[0]
    assert min(c[2] for s in body.shapes for c in (body.T_object_part @ np.c_[s.corners(), np.ones(8)].T).T) >= top - 1e-6
    scan = scan_scene(scene, params_for_preset("clean"), seed=0)
    assert [o["category"] for o in scan.labels["objects"]] == ["microwave", "cabinet"]
