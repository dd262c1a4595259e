"""End to end on synthetic scans: invariance, determinism, levelling, output round trips, the CLI."""

import json
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon import read_graph_json
from recon.graph_json import graph_dict
from recon.model import JointType
from recon.output import write_reconstruction
from recon.part_tree import contact_scores
from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays


def pose(rotvec, t):
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    T[:3, 3] = t
    return T


def movable(rec):
    return {j.name: j for j in rec.joints() if j.type is not JointType.FIXED}


def test_reconstruction_moves_with_the_scan(synth, kitchen_rec):
    """Rotating the room about the vertical and shifting it rotates and shifts every joint."""
    T = pose([0, 0, 0.7], [1.5, -0.8, 0.0])
    props, labels = synth.scan_arrays([synth.cabinet(), synth.table()], T=T)
    rec = reconstruct_scan(scan_from_arrays(props, labels))
    a, b = movable(kitchen_rec), movable(rec)
    assert a.keys() == b.keys() == {"cabinet1_drawer102_joint", "cabinet1_door104_joint"}
    for name, ja in a.items():
        jb = b[name]
        assert jb.type is ja.type
        assert np.degrees(np.arccos(np.clip(jb.axis @ (T[:3, :3] @ ja.axis), -1, 1))) < 1.0
        moved = T[:3, :3] @ ja.origin + T[:3, 3]
        assert np.linalg.norm(np.cross(jb.origin - moved, jb.axis)) < 0.01       # same axis line
        assert jb.upper == pytest.approx(ja.upper, abs=0.04)
    assert sorted(rec.object(2).tree_edges()) == sorted(kitchen_rec.object(2).tree_edges())


def _rounded(x, digits=8):
    if isinstance(x, float):
        return round(x, digits) + 0.0
    if isinstance(x, dict):
        return {k: _rounded(v, digits) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_rounded(v, digits) for v in x]
    return x


def test_same_seed_same_result(kitchen_scan, kitchen_rec):
    """Identical up to floating-point summation order (open3d's multi-threaded reductions: ~1e-14)."""
    again = reconstruct_scan(kitchen_scan[0], seed=0)
    d1, d2 = graph_dict(kitchen_rec), graph_dict(again)
    d1.pop("timings"), d2.pop("timings")
    assert _rounded(d1) == _rounded(d2)


def test_level_floor_recovers_a_tilted_camera_frame_scan(synth, kitchen_rec):
    T = pose([1.2, 0.3, -0.4], [0.3, 1.1, 1.4])          # a camera frame: z is not up, floor not at 0
    props, labels = synth.scan_arrays([synth.cabinet(), synth.table()], T=T)
    rec = reconstruct_scan(scan_from_arrays(props, labels), level_floor=True)
    drawer = movable(rec)["cabinet1_drawer102_joint"]
    assert abs(drawer.axis[2]) < 0.02                                # slides horizontally again
    body = rec.object(1).part(101).primitive
    assert body.corners()[:, 2].min() == pytest.approx(0.0, abs=0.01)   # stands on z = 0
    assert body.corners()[:, 2].max() == pytest.approx(0.8, abs=0.02)
    assert rec.graph.supports == ((1, None), (2, None))


def test_graph_json_round_trip(tmp_path, kitchen_rec):
    paths = write_reconstruction(kitchen_rec, tmp_path)
    back = read_graph_json(paths["graph.json"])
    assert len(back.objects) == len(kitchen_rec.objects)
    for o1, o2 in zip(kitchen_rec.objects, back.objects):
        assert o1.name == o2.name and o1.root_part_id == o2.root_part_id
        assert all(p1.isclose(p2) for p1, p2 in zip(o1.parts, o2.parts))
        assert all(j1.isclose(j2) for j1, j2 in zip(o1.joints, o2.joints))
        assert contact_scores(o1, kitchen_rec.config.tree) == contact_scores(o2, back.config.tree)
        assert np.allclose(o1.T_world_object, o2.T_world_object)
    assert back.graph == kitchen_rec.graph
    doc = json.loads(paths["graph.json"].read_text())
    part = doc["objects"][0]["parts"][0]
    assert {"part_id", "label", "link", "type", "size", "T_world_part", "surface_planes"} <= part.keys()
    for o, written in zip(kitchen_rec.objects, doc["objects"]):    # the contact graph the kinematic mAP scores
        scored = {tuple(e["part_ids"]): e["score"] for e in written["scored_contacts"]}
        assert scored == contact_scores(o, kitchen_rec.config.tree) and scored


def test_scene_urdf_loads_everywhere_and_matches_the_graph(tmp_path, kitchen_rec):
    import pinocchio
    import pybullet
    import yourdfpy

    path = write_reconstruction(kitchen_rec, tmp_path)["scene.urdf"]
    urdf = yourdfpy.URDF.load(str(path))
    assert urdf.validate()
    assert urdf.robot.links[0].name == "world" or urdf.base_link == "world"
    graph = {j.name: j for j in kitchen_rec.joints()}
    assert {j.name for j in urdf.robot.joints} == set(graph)
    for uj in urdf.robot.joints:
        gj = graph[uj.name]
        assert uj.type == gj.type.value
        if uj.type != "fixed":
            assert np.allclose(uj.axis, gj.axis) and uj.limit.lower == 0.0
            assert uj.limit.upper == pytest.approx(gj.upper) and float(uj.dynamics.damping) > 0
            # link frames are world-aligned and sit on the axis: the joint origin is the axis point
            T_world_child = urdf.get_transform(uj.child, "world")
            assert np.allclose(T_world_child[:3, 3], gj.origin, atol=1e-6)  # scene.urdf rounds lengths to 1e-6
            assert np.allclose(T_world_child[:3, :3], np.eye(3), atol=1e-9)
    for link in urdf.robot.links[1:]:
        assert link.inertial.mass > 0 and np.all(np.linalg.eigvalsh(link.inertial.inertia) > 0)
    # moving parts' collision boxes are shrunk by the clearance; fixed parts' are not
    drawer = next(lk for lk in urdf.robot.links if lk.name == "cabinet1_drawer102")
    body = next(lk for lk in urdf.robot.links if lk.name == "cabinet1_body101")
    clr = kitchen_rec.config.urdf.collision_clearance
    assert np.allclose(drawer.visuals[0].geometry.box.size - drawer.collisions[0].geometry.box.size, 2 * clr)
    assert np.allclose(body.visuals[0].geometry.box.size, body.collisions[0].geometry.box.size)

    model = pinocchio.buildModelFromUrdf(str(path))
    assert model.nq == 2 and set(model.names[1:]) == set(movable(kitchen_rec))
    cid = pybullet.connect(pybullet.DIRECT)
    try:
        body_id = pybullet.loadURDF(str(path), useFixedBase=True, physicsClientId=cid)
        names = {pybullet.getJointInfo(body_id, i, physicsClientId=cid)[1].decode(): i
                 for i in range(pybullet.getNumJoints(body_id, physicsClientId=cid))}
        info = pybullet.getJointInfo(body_id, names["cabinet1_drawer102_joint"], physicsClientId=cid)
        assert info[2] == pybullet.JOINT_PRISMATIC and info[9] == pytest.approx(graph["cabinet1_drawer102_joint"].upper)
    finally:
        pybullet.disconnect(cid)


def _write_inputs(synth, tmp_path, props, labels):
    synth.write_ply(tmp_path / "scan.ply", props)
    (tmp_path / "labels.json").write_text(json.dumps({"objects": labels}))


def test_cli_builds_and_refuses_bad_input_without_writing(synth, tmp_path):
    props, labels = synth.scan_arrays([synth.cabinet()], points_per_m2=3000)
    _write_inputs(synth, tmp_path, props, labels)
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "recon", "build", str(tmp_path / "scan.ply"), "--labels",
                          str(tmp_path / "labels.json"), "--out", str(out)], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    assert sorted(p.name for p in out.iterdir()) == [".partscene-run.json", "graph.json", "preview.png", "scene.srdf",
                                                     "scene.urdf"]
    assert "[1/1]" in run.stderr or "done" in run.stderr
    assert (out / "preview.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

    bad = dict(props, z=props["z"].copy())
    bad["z"][7] = np.nan
    _write_inputs(synth, tmp_path, bad, labels)
    out2 = tmp_path / "out2"
    run = subprocess.run([sys.executable, "-m", "recon", "build", str(tmp_path / "scan.ply"), "--labels",
                          str(tmp_path / "labels.json"), "--out", str(out2)], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 2
    assert "NaN" in run.stderr and "scan.ply" in run.stderr and "point 7" in run.stderr
    assert not out2.exists() or not any(out2.iterdir())


def test_flat_and_collinear_parts_are_reconstructed_with_a_warning_naming_them():
    rng = np.random.default_rng(2)
    flat = np.c_[rng.uniform(0, 0.4, 300), rng.uniform(0, 0.3, 300), np.full(300, 0.5)]
    line = np.c_[np.linspace(1, 1.5, 200), np.full(200, 0.2), np.full(200, 0.3)]
    pts = np.vstack([flat, line])
    props = {"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2], "object_id": np.full(len(pts), 4),
             "part_id": np.r_[np.full(300, 41), np.full(200, 42)]}
    labels = [{"id": 4, "category": "table", "parts": [{"id": 41, "label": "top"}, {"id": 42, "label": "leg"}]}]
    rec = reconstruct_scan(scan_from_arrays(props, labels))
    text = "\n".join(rec.warnings)
    assert "object 4 (table) part 41 (top): its points are flat" in text
    assert "object 4 (table) part 42 (leg): its points are collinear" in text
    sizes = {p.part_id: np.sort(p.primitive.size) for p in rec.object(4).parts}
    assert sizes[41][0] == pytest.approx(rec.config.fitting.min_thickness) and sizes[41][2] == pytest.approx(0.4, abs=0.02)
