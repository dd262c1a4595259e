"""Joints from the articulated templates on synthetic furniture with known hinges and slides."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.config import ReconConfig
from recon.model import JointType
from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays


def joint(rec, name):
    return next(j for j in rec.joints() if j.name == name)


def test_drawer_slides_out_of_the_face_it_sits_in(kitchen_rec):
    j = joint(kitchen_rec, "cabinet1_drawer102_joint")
    assert j.type is JointType.PRISMATIC and j.parent_part_id == 101
    assert np.degrees(np.arccos(j.axis @ [1, 0, 0])) < 1.0
    assert j.lower == 0.0
    cfg = ReconConfig().joints
    assert j.upper == pytest.approx(cfg.drawer_travel_fraction * (0.5 - cfg.drawer_back_clearance), abs=0.01)
    assert j.handle_part_id == 103
    # the origin lies on the line through the drawer along the axis
    assert np.linalg.norm(np.cross(j.origin - [0.49, 0.0, 0.6], j.axis)) < 0.01


@pytest.mark.parametrize("side", [+1, -1])
def test_door_hinges_on_the_edge_opposite_its_handle(synth, side):
    props, labels = synth.scan_arrays([synth.cabinet(door_handle_side=side)])
    rec = reconstruct_scan(scan_from_arrays(props, labels))
    j = joint(rec, "cabinet1_door104_joint")
    assert j.type is JointType.REVOLUTE and j.handle_part_id == 105
    assert abs(abs(j.axis[2]) - 1.0) < 1e-3                         # vertical hinge
    hinge_y = -0.375 * side                                         # door spans y in [-0.375, 0.375]
    assert abs(j.origin[1] - hinge_y) < 0.01 and abs(j.origin[0] - 0.48) < 0.01   # back face edge
    # a small positive angle moves the door's free edge outward (+x)
    free = np.array([0.49, -hinge_y, 0.2])
    R = Rotation.from_rotvec(j.axis * 0.1).as_matrix()
    assert (R @ (free - j.origin) + j.origin)[0] > free[0] + 0.02
    assert 0.0 < j.upper <= ReconConfig().joints.door_max_angle


def _box_with_door(synth, category: str, handle_z: float):
    """Object 7: a 0.5 x 0.6 x 0.6 m open box (part 1), its front door (part 2) and a handle bar (part 3) whose
    bottom is at ``handle_z`` m."""
    body = [synth.box([0, -0.3, 0.0], [0.5, 0.3, 0.02]), synth.box([0, -0.3, 0.58], [0.5, 0.3, 0.6]),
            synth.box([0, -0.3, 0.0], [0.5, -0.28, 0.6]), synth.box([0, 0.28, 0.0], [0.5, 0.3, 0.6]),
            synth.box([0, -0.3, 0.0], [0.02, 0.3, 0.6])]
    door = [synth.box([0.48, -0.275, 0.025], [0.5, 0.275, 0.575])]
    handle = [synth.box([0.5, -0.1, handle_z], [0.53, 0.1, handle_z + 0.02])]
    return 7, category, [(1, "body", body), (2, "door", door), (3, "handle", handle)]


def test_fold_down_door_gets_a_horizontal_hinge_at_the_bottom(synth):
    props, labels = synth.scan_arrays([_box_with_door(synth, "oven", 0.5)])           # handle near the top edge
    rec = reconstruct_scan(scan_from_arrays(props, labels))
    j = joint(rec, "oven7_door2_joint")
    assert j.type is JointType.REVOLUTE
    assert abs(abs(j.axis[1]) - 1.0) < 1e-3                         # horizontal, along the front
    assert abs(j.origin[2] - 0.025) < 0.01                          # at the bottom edge
    top_edge = np.array([0.49, 0.0, 0.575])
    R = Rotation.from_rotvec(j.axis * 0.1).as_matrix()
    assert (R @ (top_edge - j.origin) + j.origin)[0] > top_edge[0] + 0.02   # folds outward
    assert j.upper == pytest.approx(ReconConfig().joints.door_drop_angle)      # down to horizontal, not 100 deg


def test_a_lift_up_flap_swings_to_the_furniture_hinge_stop_not_to_horizontal(synth):
    """The same box with its handle near the bottom edge: hinged at the top, the flap lifts up (outward) and its
    unseen stop is a furniture hinge's (``door_max_angle``), not the drop-down door's horizontal."""
    props, labels = synth.scan_arrays([_box_with_door(synth, "cabinet", 0.08)])       # handle near the bottom edge
    j = joint(reconstruct_scan(scan_from_arrays(props, labels)), "cabinet7_door2_joint")
    assert abs(abs(j.axis[1]) - 1.0) < 1e-3 and abs(j.origin[2] - 0.575) < 0.01   # horizontal, at the top edge
    assert j.upper == pytest.approx(ReconConfig().joints.door_max_angle)


def test_door_swing_stops_at_a_neighbour(synth):
    """A box 0.3 m in front of the hinge half stops the door at about 40 deg, not at the hinge stop."""
    cab = synth.cabinet(door_handle_side=+1)
    wall = (9, "wardrobe", [(901, "body", [synth.box([0.8, -0.6, 0.0], [1.0, 0.0, 1.0])])])
    props, labels = synth.scan_arrays([cab, wall])
    rec = reconstruct_scan(scan_from_arrays(props, labels))
    j = joint(rec, "cabinet1_door104_joint")
    free = joint(reconstruct_scan(scan_from_arrays(*synth.scan_arrays([cab]))), "cabinet1_door104_joint")
    assert free.upper == pytest.approx(ReconConfig().joints.door_max_angle)
    assert np.radians(30) < j.upper < np.radians(55)
    # at the limit the (clearance-shrunk) door holds no scan point of the neighbour
    door = rec.object(1).part(104).primitive.shrunk(ReconConfig().joints.sweep_clearance)
    pts = np.c_[props["x"], props["y"], props["z"]][props["object_id"] == 9]

    def swung(a):
        M = np.eye(4)
        M[:3, :3] = Rotation.from_rotvec(j.axis * a).as_matrix()
        M[:3, 3] = j.origin - M[:3, :3] @ j.origin
        return door.transformed(M)

    assert swung(j.upper).contains(pts).sum() < ReconConfig().joints.sweep_min_points
    # a little further the door runs into the neighbour's (fitted, solid) box
    neighbour = rec.object(9).part(901).primitive
    samples, _ = swung(j.upper + 0.15).sample_surface(4000, np.random.default_rng(0))
    assert neighbour.contains(samples).any()


def test_rigid_furniture_is_all_fixed_and_legs_hang_from_the_top(kitchen_rec):
    table = kitchen_rec.object(2)
    assert table.root_part_id == 201
    assert {j.type for j in table.joints} == {JointType.FIXED}
    assert sorted(table.tree_edges()) == [(201, 202), (201, 203), (201, 204), (201, 205)]
    cab = kitchen_rec.object(1)
    assert sorted(cab.tree_edges()) == [(101, 102), (101, 104), (102, 103), (104, 105)]
    assert cab.isolated_part_ids == () and table.isolated_part_ids == ()
