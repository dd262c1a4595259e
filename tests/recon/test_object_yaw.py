"""An object's yaw from the planes of its faces (recon.object_yaw), and a base box turned onto it
(pipeline._base_along_measured_frame): Eq. 3 does not fix a noisy carcass's yaw, Alg. 1 turns the fronts onto it."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.config import ReconConfig
from recon.object_yaw import FaceYaw, face_yaws, measured_yaw, yaw_difference
from recon.open3d_engine import estimate_normals
from recon.primitive import Primitive

CFG = ReconConfig().fitting
UP = np.array([0.0, 0.0, 1.0])


def _box(size, yaw, centre=(0.0, 0.0, 0.5)) -> Primitive:
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("z", yaw).as_matrix()
    T[:3, 3] = centre
    return Primitive("box", size, T)


def _face_points(prim: Primitive, faces: list[tuple[int, float]], spacing: float, sigma: float, rng) -> np.ndarray:
    """Points on the faces (axis, side +-1) of ``prim`` on a grid of ``spacing`` (m), noise ``sigma`` (m) along
    a view ray from 2 m in front of each face, 30 deg off its normal (depth noise of a range camera)."""
    R, h, out = prim.T_world_part[:3, :3], prim.size / 2, []
    for k, s in faces:
        a, b = [j for j in range(3) if j != k]
        ua = np.arange(-h[a], h[a], spacing)
        ub = np.arange(-h[b], h[b], spacing)
        A, B = np.meshgrid(ua, ub)
        q = np.zeros((A.size, 3))
        q[:, a], q[:, b], q[:, k] = A.ravel(), B.ravel(), s * h[k]
        p = prim.center + q @ R.T
        n = s * R[:, k]
        ray = Rotation.from_rotvec(np.radians(30.0) * UP).apply(n)
        out.append(p + rng.normal(0.0, sigma, (len(p), 1)) * ray)
    return np.concatenate(out)


@pytest.mark.parametrize("estimated", [False, True])
def test_the_yaw_of_a_noisy_box_comes_from_its_faces_not_from_a_box_fitted_off_it(estimated):
    """A carcass seen on its front and one side, 4 mm depth noise along oblique rays, its box given 2.8 deg off
    (where ICP put kitchen 0's): the faces' planes give the true yaw within 0.15 deg, with exact or estimated normals."""
    rng = np.random.default_rng(0)
    true = _box([1.0, 0.6, 0.88], np.radians(17.0))
    pts = _face_points(true, [(1, -1.0), (0, 1.0)], 0.012, 0.004, rng)
    normals = estimate_normals(pts) if estimated else None
    off = _box(true.size, np.radians(17.0 - 2.8), true.center)
    faces = face_yaws(off, pts, normals, UP, CFG)
    yaw, se = measured_yaw(faces, CFG.yaw_consensus)
    assert abs(np.degrees(yaw_difference(yaw, np.radians(17.0)))) < 0.15
    assert np.degrees(se) < 0.15


def test_an_opened_door_does_not_turn_the_object():
    """A door 20 deg open whose face is the best fitted plane of the object: the body's and a drawer's faces (two
    parts) decide; with the body alone against the door (one part each), the base part's faces decide."""
    body = [FaceYaw(np.radians(0.1), np.radians(0.05), 3000, 1), FaceYaw(np.radians(89.9), np.radians(0.1), 2000, 1)]
    door = [FaceYaw(np.radians(20.0), np.radians(0.02), 9000, 2)]
    drawer = [FaceYaw(np.radians(-0.1), np.radians(0.3), 1500, 3)]
    for faces, base in ((body + door + drawer, None), (body + door, 1)):
        yaw, _ = measured_yaw(faces, CFG.yaw_consensus, base)
        assert abs(np.degrees(yaw_difference(yaw, 0.0))) < 0.2
    assert measured_yaw([], CFG.yaw_consensus) is None
    assert measured_yaw([FaceYaw(0.3, 0.2, 50, 4)], CFG.yaw_consensus) is None      # a leg's strip: too uncertain


def test_a_face_of_two_strips_at_different_depths_says_how_little_it_knows():
    """A carcass side whose front half stands 3 mm proud of its back half (a face frame), 2 mm noise: one plane
    through both is turned; its halves disagree with it, and the turn lies within 2 standard errors."""
    rng = np.random.default_rng(1)
    prim = _box([0.02, 0.6, 0.8], 0.0)
    pts = _face_points(prim, [(0, 1.0)], 0.008, 0.002, rng)
    pts[pts[:, 1] > 0, 0] += 0.003
    face = max(face_yaws(prim, pts, None, UP, CFG), key=lambda f: f.n_points)
    error = abs(yaw_difference(face.yaw, 0.0))
    assert np.degrees(error) > 0.2 and 2 * face.se >= error       # outside 2 se: not the face's yaw


def test_drawer_axes_of_a_realistic_scan_follow_its_fronts(tmp_path):
    """Regression: a third-party nightstand, realistic scan seed 2: its body's box was fitted 2 deg off in yaw (Eq. 3
    is flat there; ICP landed it off) and refinement turned the drawer onto it (axis 2.1 deg off). Now within 0.5 deg."""
    import recon
    import thirdparty
    from bench.hinge_bench import truth_scene
    from recon.metrics import estimate_from_reconstruction, truth_from_dict
    from recon.metrics.joint_errors import compare_joints
    from scenes.scan_io import write_scan
    from scenes.scanner import scan_scene
    from scenes.scanner.params import params_for_preset
    from scenes.truth_json import truth_dict_from_scene
    from thirdparty.scannable import scene_of

    built = thirdparty.build_corpus(tmp_path / "corpus", ["nightstand"])[0]
    scene, _ = scene_of(built)
    truth = truth_from_dict(truth_dict_from_scene(truth_scene(scene))).objects[0]
    files = write_scan(scan_scene(scene, params_for_preset("realistic"), seed=2), tmp_path / "scan")
    rec = recon.reconstruct(files["scan_ply"], files["labels_json"], seed=2)
    est = estimate_from_reconstruction(rec.objects[0], rec.config)
    rows = [c for c in compare_joints(truth.joints, est.joints, {p.id: p.centre for p in truth.parts})
            if c.true_type == "prismatic"]
    assert rows and all(c.axis_error_deg < 0.5 for c in rows), [c.axis_error_deg for c in rows]


def test_a_noisy_face_is_placed_at_its_plane_unless_other_parts_cover_it():
    """A carcass side seen at 3 cm depth noise (a far object of the realistic preset), its box's end 3 cm out
    (realistic room 10's cabinet 4 was 3.5 cm wide of its points' side plane): the face's plane puts it within
    1 cm. A front face with a door's points in front of it (the carcass's edges and what shows between the
    fronts) is left where the box has it."""
    from recon.object_yaw import on_face_planes

    rng = np.random.default_rng(2)
    true = _box([0.5, 0.5, 0.85], 0.0)
    side = _face_points(true, [(1, 1.0)], 0.012, 0.03, rng)
    front = _face_points(true, [(0, 1.0)], 0.012, 0.004, rng)
    front = front[rng.random(len(front)) < 0.2] - [0.02, 0.0, 0.0]          # sparse edges, 2 cm in
    pts = np.concatenate([side, front])
    wide = _box([0.5, 0.5 + 0.03, 0.85], 0.0, (0.0, 0.015, 0.5))             # +y end 3 cm out
    faces = face_yaws(wide, pts, estimate_normals(pts, 48), UP, CFG)
    door = _face_points(_box([0.02, 0.5, 0.8], 0.0, (0.26, 0.0, 0.5)), [(0, 1.0)], 0.012, 0.004, rng)
    placed = on_face_planes(wide, faces, UP, CFG.yaw_consensus, CFG.seen_face_band, CFG.min_thickness, door)
    assert abs(placed.center[1] + placed.size[1] / 2 - 0.25) < 0.01
    assert abs(placed.center[0] + placed.size[0] / 2 - 0.25) < 1e-9            # the covered front is kept
    assert on_face_planes(wide, [], UP, CFG.yaw_consensus, CFG.seen_face_band, CFG.min_thickness) is wide
