"""Chamfer distance and voxel IoU against closed forms (recon.metrics)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.metrics import (EstimateError, MetricsError, ObjectEstimate, UnitBox, chamfer_distance, object_chamfer,
                           object_iou, occupied_voxels, unit_box_from_truth, voxel_iou)
from recon.primitive import Primitive


def pose(xyz=(0.0, 0.0, 0.0), rotvec=(0.0, 0.0, 0.0)) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    T[:3, 3] = xyz
    return T


def box(size, xyz=(0.0, 0.0, 0.0), rotvec=(0.0, 0.0, 0.0)) -> Primitive:
    return Primitive("box", np.asarray(size, float), pose(xyz, rotvec))


def sphere(radius, xyz=(0.0, 0.0, 0.0)) -> Primitive:
    return Primitive("sphere", np.full(3, 2.0 * radius), pose(xyz))


# ---------------------------------------------------------------- Chamfer
def test_point_set_chamfer_of_two_parallel_grids_is_their_offset():
    g = np.stack(np.meshgrid(np.linspace(0, 1, 30), np.linspace(0, 1, 30), indexing="ij"), -1).reshape(-1, 2)
    a = np.c_[g, np.zeros(len(g))]
    b = np.c_[g, np.full(len(g), 0.03)]
    assert chamfer_distance(a, b) == pytest.approx(0.03, abs=1e-12)
    assert chamfer_distance(a, a) == 0.0


def test_chamfer_is_symmetric_mean_of_both_directions():
    # A = one point at 0; B = points at 0 and 1 on x: A->B mean 0, B->A mean 0.5, CD = 0.25
    a = np.zeros((1, 3))
    b = np.array([[0.0, 0, 0], [1.0, 0, 0]])
    assert chamfer_distance(a, b) == pytest.approx(0.25)
    assert chamfer_distance(b, a) == pytest.approx(0.25)


def test_object_chamfer_of_concentric_spheres_is_the_gap():
    truth = [sphere(0.5, (1.0, 2.0, 0.5))]
    box_ = unit_box_from_truth(truth, np.eye(4))
    assert box_.scale == pytest.approx(1.0, abs=2e-3)
    # point-to-surface distances: no sampling floor, only the icosphere's tessellation (< 0.3%)
    assert object_chamfer(truth, truth, box_, seed=0) < 0.003
    grown = [sphere(0.55, (1.0, 2.0, 0.5))]
    cd = object_chamfer(truth, grown, box_, seed=0)
    assert cd == pytest.approx(0.05, abs=0.002)   # every point is 0.05 m = 0.05 unit from the other surface


def test_object_chamfer_is_invariant_to_a_rigid_motion_of_both_sides():
    truth = [box([0.8, 0.5, 0.9], (0, 0, 0.45)), box([0.02, 0.4, 0.3], (0.41, 0.0, 0.6))]
    est = [box([0.75, 0.55, 0.9], (0.01, 0.02, 0.45), (0, 0, 0.05))]
    b0 = unit_box_from_truth(truth, np.eye(4))
    cd0 = object_chamfer(truth, est, b0, n_samples=5000, seed=3)
    M = pose((2.0, -1.0, 0.3), (0, 0, 1.1))
    truth_m = [p.transformed(M) for p in truth]
    est_m = [p.transformed(M) for p in est]
    cd1 = object_chamfer(truth_m, est_m, unit_box_from_truth(truth_m, M), n_samples=5000, seed=3)
    assert cd1 == pytest.approx(cd0, abs=1e-5)   # same samples up to float rounding
    assert cd0 > 0.005


def test_object_chamfer_is_in_units_of_the_truths_largest_extent():
    truth = [box([2.0, 1.0, 1.0])]
    shifted = [box([2.0, 1.0, 1.0], (0.0, 0.0, 0.2))]
    b = unit_box_from_truth(truth, np.eye(4))
    assert b.scale == pytest.approx(2.0)
    cd = object_chamfer(truth, shifted, b, n_samples=5000, seed=0)
    # the same scene twice as large gives the same unit-box Chamfer
    big = [box([4.0, 2.0, 2.0])]
    big_shifted = [box([4.0, 2.0, 2.0], (0.0, 0.0, 0.4))]
    cd_big = object_chamfer(big, big_shifted, unit_box_from_truth(big, np.eye(4)), n_samples=5000, seed=0)
    assert cd_big == pytest.approx(cd, abs=1e-6)
    # and it lies below the 0.2 m / 2 m = 0.1 shift (side faces slide within themselves)
    assert 0.02 < cd < 0.1
    assert object_chamfer(truth, truth, b) < 1e-9              # boxes mesh exactly


@pytest.mark.parametrize("bad, message", [
    (np.array([[np.nan, 0, 0]]), "points_b contains NaN"),
    (np.zeros((0, 3)), "points_b must be a non-empty"),
    (np.zeros((4, 2)), r"points_b must be a non-empty \(n, 3\) array, got shape \(4, 2\)"),
])
def test_chamfer_rejects_bad_points(bad, message):
    with pytest.raises(EstimateError, match=message):
        chamfer_distance(np.zeros((3, 3)), bad)


def test_object_estimate_rejects_nan_pose_and_empty_primitives_naming_the_object():
    bad = Primitive("box", np.ones(3), np.full((4, 4), np.nan))
    with pytest.raises(MetricsError, match=r"object 3 \(cabinet\).*NaN"):
        ObjectEstimate(3, "cabinet", (bad,))
    with pytest.raises(MetricsError, match=r"object 4 \(table\): the estimate has no primitives"):
        ObjectEstimate(4, "table", ())


def test_unit_box_rejects_zero_scale():
    with pytest.raises(EstimateError, match="scale must be > 0"):
        UnitBox(np.eye(4), 0.0)


# ---------------------------------------------------------------- IoU
def test_iou_of_an_object_with_itself_is_one_and_far_away_is_zero():
    truth = [box([0.8, 0.5, 0.9], (0, 0, 0.45)), Primitive("cylinder", np.array([0.1, 0.1, 0.4]), pose((0, 0, 1.1)))]
    b = unit_box_from_truth(truth, np.eye(4))
    assert object_iou(truth, truth, b) == 1.0
    assert object_iou(truth, [box([0.8, 0.5, 0.9], (5.0, 0, 0.45))], b) == 0.0


def test_iou_of_a_box_shifted_by_whole_voxels_is_the_closed_form():
    # truth 1 x 0.5 x 0.5 m -> scale 1 m, 32 x 16 x 16 voxels; estimate shifted 4 voxels along x
    truth = [box([1.0, 0.5, 0.5])]
    b = unit_box_from_truth(truth, np.eye(4))
    occ = occupied_voxels(truth, b)
    assert len(occ) == 32 * 16 * 16
    est = [box([1.0, 0.5, 0.5], (4 / 32, 0.0, 0.0))]
    assert object_iou(truth, est, b) == pytest.approx(28 / 36, abs=1e-12)
    half = [box([0.5, 0.5, 0.5])]
    assert object_iou(truth, half, b) == pytest.approx(0.5, abs=1e-12)


def _shell(open_face: bool) -> list:
    """Six (or five, front +x open) 1-voxel-thick panels on the lattice around a 1 m cube."""
    h = 1.0 / 32
    panels = []
    for axis in range(3):
        for sign in (-1, 1):
            if open_face and axis == 0 and sign == 1:
                continue
            size = np.ones(3)
            size[axis] = h
            xyz = np.zeros(3)
            xyz[axis] = sign * (0.5 - h / 2)
            panels.append(box(size, xyz))
    return panels


def test_iou_is_solid_a_closed_shell_is_filled_an_open_one_is_not():
    solid = [box([1.0, 1.0, 1.0])]
    b = unit_box_from_truth(solid, np.eye(4))
    assert object_iou(solid, _shell(open_face=False), b) == 1.0        # the enclosed inside is filled
    # five panels, front open: 32^3 - 30^2 * 31 voxels, nothing enclosed
    assert len(occupied_voxels(_shell(open_face=True), b)) == 32 ** 3 - 30 * 30 * 31
    assert object_iou(solid, _shell(open_face=True), b) == pytest.approx((32 ** 3 - 30 * 30 * 31) / 32 ** 3)


def test_iou_of_a_closed_thin_walled_box_is_stable_under_sub_voxel_shifts():
    t = 0.018
    walls = lambda dx: [box([t, 0.8, 0.8], (dx + s * (0.3 - t / 2), 0, 0)) for s in (-1, 1)] + \
                       [box([0.6, t, 0.8], (dx, s * (0.4 - t / 2), 0)) for s in (-1, 1)] + \
                       [box([0.6, 0.8, t], (dx, 0, s * (0.4 - t / 2))) for s in (-1, 1)]
    truth = walls(0.0)
    b = unit_box_from_truth(truth, np.eye(4))
    for dx in (0.002, 0.005, 0.01):
        assert object_iou(truth, walls(dx), b) > 0.9


def test_thin_panel_occupies_a_voxel_layer_wherever_it_sits():
    b = unit_box_from_truth([box([1.0, 1.0, 1.0])], np.eye(4))
    for x in np.linspace(-0.3, 0.3, 7):
        n = len(occupied_voxels([box([0.004, 0.5, 0.5], (x, 0, 0))], b))
        assert n in (16 * 16, 2 * 16 * 16)


def test_estimate_sticking_out_of_the_truth_box_counts_in_the_union():
    truth = [box([1.0, 0.5, 0.5])]
    b = unit_box_from_truth(truth, np.eye(4))
    bigger = [box([2.0, 0.5, 0.5])]            # twice as long: IoU = 1/2, not 1 (no clipping at the box)
    assert object_iou(truth, bigger, b) == pytest.approx(0.5, abs=1e-12)


def test_distance_to_union_surface_outside_inside_and_on_a_seam():
    from recon.metrics import distance_to_union_surface
    two = [box([1.0, 1.0, 1.0], (-0.5, 0, 0)), box([1.0, 1.0, 1.0], (0.5, 0, 0))]   # a 2 x 1 x 1 union
    p = np.array([[1.3, 0, 0],      # outside, 0.3 beyond the +x face
                  [0.0, 0, 0],      # on the internal seam: truly 0.5 from the union's surface; the
                                    # documented lower bound (depth in the deepest box) gives 0
                  [0.9, 0.0, 0.0],  # inside, 0.1 from the +x face
                  [0.0, 0.7, 0.7]])  # outside near an edge: sqrt(0.2^2 + 0.2^2)
    d = distance_to_union_surface(p, two)
    np.testing.assert_allclose(d, [0.3, 0.0, 0.1, np.hypot(0.2, 0.2)], atol=1e-12)


def test_voxel_iou_of_index_sets():
    a = np.array([[0, 0, 0], [0, 0, 1], [1, 0, 0]])
    b = np.array([[0, 0, 1], [1, 0, 0], [5, 5, 5], [-3, 2, 1]])
    assert voxel_iou(a, b) == pytest.approx(2 / 5)
    assert voxel_iou(np.zeros((0, 3)), np.zeros((0, 3))) == 1.0
