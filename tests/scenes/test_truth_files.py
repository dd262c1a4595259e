"""truth.urdf and truth.json: the contract schema, names, loaders without warnings, FK agreement."""

from __future__ import annotations

import json
import logging

import numpy as np
import pybullet as pb
import pytest

from scenes.builtin import build_scene
from scenes.errors import SceneSpecError
from scenes.description import WORLD_LINK, joint_name, link_name, parse_link_name
from scenes.truth_json import TRUTH_FORMAT, read_truth_json, scene_from_truth_dict, truth_dict_from_scene


def _pybullet_body(urdf):
    cid = pb.connect(pb.DIRECT)
    body = pb.loadURDF(str(urdf), useFixedBase=True, physicsClientId=cid)
    links = {pb.getJointInfo(body, i, physicsClientId=cid)[12].decode(): i
             for i in range(pb.getNumJoints(body, physicsClientId=cid))}
    return cid, body, links


def test_truth_json_follows_the_contract(kitchen_files, kitchen):
    d = json.loads(kitchen_files[1].read_text())
    assert d["format"] == TRUTH_FORMAT and d["scene"] == "kitchen" and d["seed"] == 0
    assert d["floor"] == {"z": 0.0}
    assert {w["name"] for w in d["walls"]} == {"wall_north", "wall_south", "wall_east", "wall_west"}
    for o in d["objects"]:
        assert set(o) >= {"id", "name", "category", "T_world_object", "size", "supported_by", "parts",
                          "joints", "contacts"}
        assert np.array(o["T_world_object"]).shape == (4, 4)
        for p in o["parts"]:
            assert p["link"] == link_name(o["category"], o["id"], p["label"], p["id"])
            for s in p["shapes"]:
                assert s["type"] in ("box", "cylinder")
                assert np.array(s["T_part_shape"]).shape == (4, 4)
        child_ids = sorted(j["child_part_id"] for j in o["joints"])
        assert child_ids == sorted(p["id"] for p in o["parts"])        # joints = the whole part tree
        for j in o["joints"]:
            child = next(p for p in o["parts"] if p["id"] == j["child_part_id"])
            assert j["name"] == joint_name(o["category"], o["id"], child["label"], child["id"])
            assert j["type"] in ("fixed", "prismatic", "revolute")
            assert np.linalg.norm(j["axis"]) == pytest.approx(1.0)
            if j["type"] != "fixed":
                assert j["lower"] == 0.0 and j["upper"] > 0
                assert j["handle_part_id"] is not None
                hp = next(p for p in o["parts"] if p["id"] == j["handle_part_id"])
                assert hp["label"] == "handle"
        for a, b in o["contacts"]:
            assert a < b


def test_truth_json_round_trips(kitchen_files, kitchen):
    back = read_truth_json(kitchen_files[1])
    assert back.isclose(kitchen, atol=1e-9)
    assert not back.isclose(build_scene("kitchen", 1))
    assert [o.name for o in back.objects] == [o.name for o in kitchen.objects]
    for a, b in zip(kitchen.objects, back.objects):
        assert np.allclose(a.T_world_object, b.T_world_object)
        assert all(p.isclose(q, 1e-9) for p, q in zip(a.parts, b.parts))
        for ja, jb in zip(a.joints, b.joints):
            assert ja.type == jb.type and ja.child == jb.child and ja.handle == jb.handle
            assert np.allclose(ja.axis, jb.axis) and np.allclose(ja.origin, jb.origin)
        assert a.contacts == b.contacts


@pytest.mark.parametrize("mutate, match", [
    (lambda d: d.update(format="other/9"), "format is 'other/9'"),
    (lambda d: d["objects"][0].pop("joints"), r"object \d+ \(\w+\): missing field 'joints'"),
    (lambda d: d["objects"][0]["parts"][0].update(label="lid"), "part 1: unknown label 'lid'"),
])
def test_bad_truth_json_is_rejected(tmp_path, kitchen, mutate, match):
    d = truth_dict_from_scene(kitchen)
    mutate(d)
    path = tmp_path / "truth.json"
    path.write_text(json.dumps(d))
    with pytest.raises(SceneSpecError, match=match):
        read_truth_json(path)


def test_urdf_loads_in_pybullet_without_warnings(kitchen_files, kitchen, capfd):
    capfd.readouterr()
    cid, body, links = _pybullet_body(kitchen_files[0])
    out, err = capfd.readouterr()
    assert "warn" not in (out + err).lower() and "error" not in (out + err).lower(), out + err
    n_parts = sum(len(o.parts) for o in kitchen.objects)
    assert len(links) == n_parts + len(kitchen.walls)
    assert all(parse_link_name(n) for n in links if not n.startswith("wall"))
    pb.disconnect(cid)


def test_urdf_loads_in_pinocchio_and_yourdfpy_without_warnings(kitchen_files, kitchen, capfd, caplog):
    import pinocchio as pin
    import yourdfpy

    urdf = str(kitchen_files[0])
    capfd.readouterr()
    with caplog.at_level(logging.WARNING):
        model = pin.buildModelFromUrdf(urdf)
        geom = pin.buildGeomFromUrdf(model, urdf, pin.GeometryType.COLLISION)
        robot = yourdfpy.URDF.load(urdf)
        assert robot.validate()
    out, err = capfd.readouterr()
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text
    assert "warn" not in (out + err).lower(), out + err
    movable = [o.joint_name(j) for o in kitchen.objects for j in o.joints if j.movable]
    assert sorted(robot.actuated_joint_names) == sorted(movable)
    assert model.nq == len(movable)
    assert geom.ngeoms == sum(len(p.shapes) for o in kitchen.objects for p in o.parts) + len(kitchen.walls)
    assert robot.base_link == WORLD_LINK


def test_pybullet_link_frames_and_joint_axes_match_truth_json(kitchen_files, kitchen):
    d = json.loads(kitchen_files[1].read_text())
    cid, body, links = _pybullet_body(kitchen_files[0])
    for o in d["objects"]:
        for p in o["parts"]:
            st = pb.getLinkState(body, links[p["link"]], computeForwardKinematics=True, physicsClientId=cid)
            T = np.array(p["T_world_part"])
            assert np.allclose(st[4], T[:3, 3], atol=1e-6), p["link"]
            R = np.array(pb.getMatrixFromQuaternion(st[5])).reshape(3, 3)
            assert np.allclose(R, T[:3, :3], atol=1e-6), p["link"]
        for j in o["joints"]:
            if j["type"] == "fixed":
                continue
            child = next(p for p in o["parts"] if p["id"] == j["child_part_id"])
            li = links[child["link"]]
            q = 0.5 * j["upper"]
            pb.resetJointState(body, li, q, physicsClientId=cid)
            st = pb.getLinkState(body, li, computeForwardKinematics=True, physicsClientId=cid)
            pb.resetJointState(body, li, 0.0, physicsClientId=cid)
            T0 = np.array(child["T_world_part"])
            p1, R1 = np.array(st[4]), np.array(pb.getMatrixFromQuaternion(st[5])).reshape(3, 3)
            axis, origin = np.array(j["axis"]), np.array(j["origin"])
            if j["type"] == "prismatic":
                assert np.allclose(p1 - T0[:3, 3], q * axis, atol=1e-6), j["name"]
            else:
                dR = R1 @ T0[:3, :3].T                      # rotation about the world axis by +q
                K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
                expect = np.eye(3) + np.sin(q) * K + (1 - np.cos(q)) * K @ K
                assert np.allclose(dR, expect, atol=1e-6), j["name"]
                assert np.allclose(p1, origin + expect @ (T0[:3, 3] - origin), atol=1e-6), j["name"]
    pb.disconnect(cid)


def test_urdf_has_limits_dynamics_and_inertials(kitchen_files):
    import xml.etree.ElementTree as ET

    root = ET.parse(kitchen_files[0]).getroot()
    for j in root.iter("joint"):
        assert j.find("dynamics") is not None, j.get("name")
        if j.get("type") != "fixed":
            lim = j.find("limit")
            assert float(lim.get("effort")) > 0 and float(lim.get("velocity")) > 0
            assert float(lim.get("lower")) == 0.0 and float(lim.get("upper")) > 0
    for link in root.iter("link"):
        assert link.find("inertial") is not None, link.get("name")
        if link.get("name") != WORLD_LINK:
            assert float(link.find("inertial/mass").get("value")) > 0
            for geom in link.iter("geometry"):
                assert geom.find("box") is not None or geom.find("cylinder") is not None


def test_every_builtin_scene_writes_a_loadable_urdf(tmp_path):
    from scenes.truth_urdf import write_truth_urdf

    for name in ("bedroom", "office", "random"):
        urdf = write_truth_urdf(build_scene(name, 1), tmp_path / f"{name}.urdf")
        cid, body, links = _pybullet_body(urdf)
        assert len(links) > 10
        pb.disconnect(cid)
        sc = scene_from_truth_dict(truth_dict_from_scene(build_scene(name, 1)))
        assert len(sc.objects) >= 3


def test_every_generator_writes_loadable_urdf_for_many_seeds(tmp_path, capfd):
    import pinocchio as pin
    import yourdfpy

    from scenes.generators import GENERATORS
    from scenes.model import Scene
    from scenes.description import pose
    from scenes.truth_urdf import write_truth_urdf

    for seed in range(6):
        rng = np.random.default_rng(seed)
        objs, next_part = [], 1
        for k, make in enumerate(GENERATORS.values()):
            o = make(rng).renumbered(k + 1, next_part).placed(pose([3.0 * k, 0.0, 0.0]))
            next_part += len(o.parts)
            objs.append(o)
        urdf = str(write_truth_urdf(Scene("gen", seed, tuple(objs)), tmp_path / f"gen{seed}.urdf"))
        capfd.readouterr()
        cid, body, links = _pybullet_body(urdf)
        pb.disconnect(cid)
        model = pin.buildModelFromUrdf(urdf)
        assert yourdfpy.URDF.load(urdf).validate()
        out, err = capfd.readouterr()
        assert "warn" not in (out + err).lower(), out + err
        assert len(links) == sum(len(o.parts) for o in objs)
        assert model.nq == sum(j.movable for o in objs for j in o.joints)
