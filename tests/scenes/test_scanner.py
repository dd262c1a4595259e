"""Virtual scanner: determinism, on-surface labels, occlusion, voxel grid, noise statistics, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from scenes.errors import ScanError
from scenes.scanner import params_for_preset, scan_scene
from scenes.scanner.degrade import depth_sigma
from scenes.scanner.meshes import FACET_TOLERANCE
from scenes.surface_distance import part_surface_distance

# float32 ray casting (relative error ~1e-7 of a few metres) + cylinder faceting
ON_SURFACE_TOL = FACET_TOLERANCE + 5e-5   # m
# a cheaper scan for the statistics tests: no downsampling, so every return is kept
RAW = dict(width=96, height=72, n_frames=10, frames_per_object=0, voxel_size=0.0, background_voxel=0.0)


def _eyes(scan):
    return scan.T_world_cameras[scan.frame, :3, 3]


def _parts(scene):
    return {p.id: (o, p) for o in scene.objects for p in o.parts}


def test_scan_is_deterministic_for_a_seed(kitchen, clean_scan, small):
    again = scan_scene(kitchen, params_for_preset("clean", **small), seed=3)
    other = scan_scene(kitchen, params_for_preset("clean", **small), seed=4)
    assert np.array_equal(again.points, clean_scan.points)
    assert np.array_equal(again.part_id, clean_scan.part_id)
    assert len(other) != len(clean_scan) or not np.array_equal(other.points, clean_scan.points)


def test_every_labelled_point_lies_on_its_part(kitchen, clean_scan):
    parts = _parts(kitchen)
    assert set(np.unique(clean_scan.part_id)) - {-1} <= set(parts)
    for pid in np.unique(clean_scan.part_id[clean_scan.part_id >= 0]):
        o, p = parts[pid]
        sel = clean_scan.part_id == pid
        assert np.all(clean_scan.object_id[sel] == o.id)
        d = part_surface_distance(p, o.T_world_object @ p.T_object_part, clean_scan.points[sel])
        assert d.max() < ON_SURFACE_TOL, f"{o.link(p)}: {d.max():.2e} m off its surface"


def test_labels_json_lists_every_part(kitchen, clean_scan):
    listed = {(o["id"], p["id"], p["label"]) for o in clean_scan.labels["objects"] for p in o["parts"]}
    truth = {(o.id, p.id, p.label) for o in kitchen.objects for p in o.parts}
    assert listed == truth


def test_occluded_surfaces_get_no_points(kitchen, clean_scan):
    parts = _parts(kitchen)
    fg = clean_scan.part_id >= 0
    # no underside is seen: every camera is above 1.2 m and every horizontal down-facing face is lower
    # (tilted facets of a cylinder may face down and still toward a camera, so only |nz| ~ 1 counts)
    assert not np.any(clean_scan.normals[fg, 2] < -0.99)
    for pid, (o, p) in parts.items():
        sel = clean_scan.part_id == pid
        if p.label == "drawer":
            # the inside of a closed drawer: nothing behind the back face of its front panel
            T = np.linalg.inv(o.T_world_object @ p.T_object_part)
            local = clean_scan.points[sel] @ T[:3, :3].T + T[:3, 3]
            assert np.all(local[:, 0] > -0.002), o.link(p)
    # backs against a wall: no object point faces the wall it stands at
    for o in kitchen.objects:
        if o.supported_by is None and o.category in ("cabinet", "refrigerator"):
            sel = clean_scan.object_id == o.id
            back = -o.T_world_object[:3, 0]
            assert not np.any(clean_scan.normals[sel] @ back > 0.9), o.name
    # but the fronts are seen
    for o in kitchen.objects:
        for p in o.parts:
            if p.label in ("drawer", "door"):
                assert np.count_nonzero(clean_scan.part_id == p.id) > 100, o.link(p)


def test_voxel_downsampling_keeps_one_point_per_voxel(clean_scan):
    fg = clean_scan.points[clean_scan.object_id >= 0]
    keys = np.floor(fg / 0.01).astype(np.int64)
    assert len(np.unique(keys, axis=0)) == len(fg)


def test_depth_noise_matches_its_model(kitchen):
    base, quad = 0.002, 0.003
    clean = scan_scene(kitchen, params_for_preset("clean", **RAW), seed=1)
    noisy = scan_scene(kitchen, params_for_preset("clean", depth_noise_base=base, depth_noise_quadratic=quad,
                                                  **RAW), seed=1)
    assert len(noisy) == len(clean) > 20000
    d = clean.points - _eyes(clean)
    r = np.linalg.norm(d, axis=1)
    assert np.allclose(r, noisy.range, atol=1e-6)
    err = np.einsum("ij,ij->i", noisy.points - clean.points, d / r[:, None])
    z = err / depth_sigma(r, base, quad)
    assert abs(z.mean()) < 0.03 and abs(z.std() - 1.0) < 0.03
    # and the error is along the ray only
    assert np.allclose(noisy.points - clean.points, err[:, None] * d / r[:, None], atol=1e-5)


def test_realistic_points_lie_on_their_part_within_the_noise(kitchen):
    """Without label noise, a non-outlier point is within 5 sigma(range) of its part's surface."""
    p = params_for_preset("realistic", label_flip_prob=0.0, **RAW)
    sc = scan_scene(kitchen, p, seed=8)
    parts = _parts(kitchen)
    ok = (sc.part_id >= 0) & ~sc.is_outlier
    for pid in np.unique(sc.part_id[ok]):
        o, part = parts[pid]
        sel = ok & (sc.part_id == pid)
        d = part_surface_distance(part, o.T_world_object @ part.T_object_part, sc.points[sel])
        bound = 5 * depth_sigma(sc.range[sel], p.depth_noise_base, p.depth_noise_quadratic) + ON_SURFACE_TOL
        assert np.all(d <= bound), o.link(part)


def test_missing_returns_and_grazing_limit(kitchen):
    full = scan_scene(kitchen, params_for_preset("clean", **RAW), seed=2)
    holes = scan_scene(kitchen, params_for_preset("clean", missing_rate=0.2, **RAW), seed=2)
    assert len(holes) / len(full) == pytest.approx(0.8, abs=0.01)
    graze = scan_scene(kitchen, params_for_preset("clean", grazing_limit_deg=60.0, **RAW), seed=2)
    d = graze.points - _eyes(graze)
    cos = np.abs(np.einsum("ij,ij->i", d / np.linalg.norm(d, axis=1)[:, None], graze.normals))
    assert cos.min() >= np.cos(np.radians(60.0)) - 1e-6
    assert len(graze) < 0.95 * len(full)


def test_outliers_leave_the_surface_at_their_rate(kitchen):
    rate = 0.02
    sc = scan_scene(kitchen, params_for_preset("clean", outlier_rate=rate, outlier_range=0.3, **RAW), seed=5)
    assert sc.is_outlier.mean() == pytest.approx(rate, abs=0.003)
    parts = _parts(kitchen)
    fg = np.flatnonzero(sc.part_id >= 0)
    off = np.zeros(len(sc), bool)
    for pid in np.unique(sc.part_id[fg]):
        o, p = parts[pid]
        sel = np.flatnonzero(sc.part_id == pid)
        off[sel] = part_surface_distance(p, o.T_world_object @ p.T_object_part, sc.points[sel]) > ON_SURFACE_TOL
    assert not np.any(off[fg] & ~sc.is_outlier[fg])               # inliers stay on their part
    assert off[fg][sc.is_outlier[fg]].mean() > 0.9                 # outliers mostly leave it


def test_label_noise_only_flips_points_at_part_boundaries(kitchen, small):
    width, prob = 0.015, 0.5
    clean = scan_scene(kitchen, params_for_preset("clean", **small), seed=6)
    noisy = scan_scene(kitchen, params_for_preset("clean", label_boundary_width=width, label_flip_prob=prob,
                                                  **small), seed=6)
    assert np.array_equal(clean.points, noisy.points)
    flipped = np.flatnonzero(clean.part_id != noisy.part_id)
    assert len(flipped) > 100
    assert np.all(clean.object_id[flipped] == clean.object_id[flipped])
    # each flipped point has a point of its new part (clean labels) within the boundary width
    for pid in np.unique(noisy.part_id[flipped]):
        f = flipped[noisy.part_id[flipped] == pid]
        d, _ = cKDTree(clean.points[clean.part_id == pid]).query(clean.points[f])
        assert d.max() <= width + 1e-9
    # flips happen at about the requested probability among boundary points
    fg = np.flatnonzero(clean.object_id >= 0)
    tree = cKDTree(clean.points[fg])
    pairs = tree.query_pairs(width, output_type="ndarray")
    diff = (clean.part_id[fg][pairs[:, 0]] != clean.part_id[fg][pairs[:, 1]]) & \
           (clean.object_id[fg][pairs[:, 0]] == clean.object_id[fg][pairs[:, 1]])
    boundary = np.unique(pairs[diff].ravel())
    assert len(flipped) / len(boundary) == pytest.approx(prob, abs=0.1)


def test_camera_path_is_a_walk_at_head_height(clean_scan, kitchen):
    from shapely.geometry import Point

    from scenes.footprints import footprint

    eyes = clean_scan.T_world_cameras[:, :3, 3]
    assert np.all((eyes[:, 2] >= 1.2) & (eyes[:, 2] <= 1.7))
    for e in eyes:
        for o in kitchen.objects:
            assert not footprint(o).contains(Point(e[:2])), o.name
    # every object is looked at by some camera and gets points
    assert set(np.unique(clean_scan.object_id)) >= {o.id for o in kitchen.objects}


@pytest.mark.parametrize("overrides, match", [
    (dict(missing_rate=1.5), "missing_rate=1.5 is out of range"),
    (dict(fov_deg=2.0), "fov_deg=2.0"),
    (dict(camera_height=(1.7, 1.2)), "camera_height"),
    (dict(voxel_size=-0.01), "voxel_size"),
    (dict(lens="fisheye"), "bad scan parameter override for preset 'clean'"),
])
def test_bad_scan_parameters_are_rejected(overrides, match):
    with pytest.raises(ScanError, match=match):
        params_for_preset("clean", **overrides)


def test_unknown_preset_and_bad_seed(kitchen):
    with pytest.raises(ScanError, match="unknown scan preset 'noisy'; expected one of clean, realistic"):
        params_for_preset("noisy")
    with pytest.raises(ScanError, match="seed must be a non-negative integer"):
        scan_scene(kitchen, params_for_preset("clean"), seed=-3)


def test_scanning_an_empty_room_is_an_error(kitchen):
    import dataclasses

    empty = dataclasses.replace(kitchen, objects=())
    with pytest.raises(ScanError, match="scene 'kitchen' has no objects to scan"):
        scan_scene(empty, params_for_preset("clean", **RAW), seed=0)


def test_bigger_rooms_get_more_views():
    from scenes.builtin import build_scene
    from scenes.scanner.camera_path import camera_poses

    studio = build_scene("studio", 0)
    p = params_for_preset("clean", n_frames=10, frames_per_object=5)
    assert len(camera_poses(studio, p, np.random.default_rng(0))) == 5 * len(studio.objects)
    p = params_for_preset("clean", n_frames=10, frames_per_object=0)
    assert len(camera_poses(studio, p, np.random.default_rng(0))) == 10
