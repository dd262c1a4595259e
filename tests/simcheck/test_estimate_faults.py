"""The wrong-estimate builders of ``simcheck.estimate_faults`` (pure XML edits, no PyBullet): each moves
exactly what it says by exactly how much, and leaves the part's geometry where it was."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import simcheck.estimate_faults as wrong
from simcheck_fixture_plans import CABINET, DOOR, DRAWER

DOOR_LINK, DOOR_HANDLE = "cabinet1_door4", "cabinet1_handle5"
DRAWER_HANDLE = "cabinet1_handle3"


def _T(el) -> np.ndarray:
    T = np.eye(4)
    o = el.find("origin") if el is not None else None
    if o is not None:
        T[:3, 3] = [float(v) for v in o.get("xyz", "0 0 0").split()]
        T[:3, :3] = Rotation.from_euler("xyz", [float(v) for v in o.get("rpy", "0 0 0").split()]).as_matrix()
    return T


class _Closed:
    """World poses of an URDF's links and its joints' axes (world frame), every joint at 0."""

    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.links = {l.get("name"): l for l in root.findall("link")}
        self.joints = {j.get("name"): j for j in root.findall("joint")}
        self.by_child = {j.find("child").get("link"): j for j in root.findall("joint")}

    def link(self, name) -> np.ndarray:
        j = self.by_child.get(name)
        return np.eye(4) if j is None else self.link(j.find("parent").get("link")) @ _T(j)

    def joint_frame(self, name) -> np.ndarray:
        return self.link(self.joints[name].find("child").get("link"))

    def axis(self, name) -> np.ndarray:
        a = np.array([float(v) for v in self.joints[name].find("axis").get("xyz").split()])
        return self.joint_frame(name)[:3, :3] @ a / np.linalg.norm(a)

    def geometry(self, link) -> list[np.ndarray]:
        """World poses (4, 4) of every visual, collision and inertial element of ``link``."""
        T = self.link(link)
        return [T @ _T(el) for tag in ("visual", "collision", "inertial") for el in self.links[link].findall(tag)]


def _same_geometry(a: _Closed, b: _Closed, link: str) -> None:
    for x, y in zip(a.geometry(link), b.geometry(link)):
        np.testing.assert_allclose(x, y, atol=2e-6)


@pytest.mark.parametrize("sideways, normal", [(0.015, 0.0), (-0.03, 0.0), (0.0, 0.02), (0.01, -0.05)])
def test_shift_hinge_moves_the_hinge_line_and_keeps_the_door(tmp_path, sideways, normal):
    before = _Closed(CABINET)
    after = _Closed(wrong.shift_hinge(CABINET, DOOR, tmp_path / "e.urdf", sideways=sideways, normal=normal))
    # the fixture door: hinge at its -y edge, free edge toward +y, front toward +x, axis -z
    moved = after.joint_frame(DOOR)[:3, 3] - before.joint_frame(DOOR)[:3, 3]
    np.testing.assert_allclose(moved, [normal, sideways, 0.0], atol=2e-6)
    np.testing.assert_allclose(after.axis(DOOR), before.axis(DOOR), atol=1e-12)
    _same_geometry(before, after, DOOR_LINK)
    _same_geometry(before, after, DOOR_HANDLE)


@pytest.mark.parametrize("deg", [3.0, -10.0])
def test_tilt_hinge_tilts_the_axis_in_the_door_plane(tmp_path, deg):
    before = _Closed(CABINET)
    after = _Closed(wrong.tilt_hinge(CABINET, DOOR, deg, tmp_path / "e.urdf"))
    a0, a1 = before.axis(DOOR), after.axis(DOOR)
    assert np.degrees(np.arccos(np.clip(a0 @ a1, -1, 1))) == pytest.approx(abs(deg), abs=1e-4)
    assert a1[0] == pytest.approx(0.0, abs=1e-12)            # stays in the door's plane (front normal +x)
    np.testing.assert_allclose(after.joint_frame(DOOR), before.joint_frame(DOOR), atol=1e-12)
    _same_geometry(before, after, DOOR_LINK)


@pytest.mark.parametrize("joint, handle, outward", [(DOOR, DOOR_HANDLE, 0.015), (DOOR, DOOR_HANDLE, -0.03),
                                                    (DRAWER, DRAWER_HANDLE, 0.02)])
def test_move_handle_moves_only_the_handle_along_the_front_normal(tmp_path, joint, handle, outward):
    before = _Closed(CABINET)
    after = _Closed(wrong.move_handle(CABINET, joint, outward, tmp_path / "e.urdf"))
    moved = after.link(handle)[:3, 3] - before.link(handle)[:3, 3]
    np.testing.assert_allclose(moved, [outward, 0.0, 0.0], atol=2e-6)     # both fronts face +x
    np.testing.assert_allclose(after.joint_frame(joint), before.joint_frame(joint), atol=1e-12)
    _same_geometry(before, after, after.joints[joint].find("child").get("link"))


def test_move_handle_names_a_joint_without_a_handle(tmp_path):
    with pytest.raises(KeyError, match="cabinet1_body1_joint"):
        wrong.move_handle(CABINET, "cabinet1_body1_joint", 0.01, tmp_path / "e.urdf")


def test_flip_hinge_puts_the_hinge_on_the_other_edge(tmp_path):
    before = _Closed(CABINET)
    after = _Closed(wrong.flip_hinge(CABINET, DOOR, tmp_path / "e.urdf"))
    np.testing.assert_allclose(after.joint_frame(DOOR)[:3, 3] - before.joint_frame(DOOR)[:3, 3], [0.0, 0.56, 0.0],
                               atol=2e-6)
    np.testing.assert_allclose(after.axis(DOOR), -before.axis(DOOR), atol=1e-12)
    _same_geometry(before, after, DOOR_LINK)


def test_the_source_is_never_modified(tmp_path):
    data = CABINET.read_bytes()
    wrong.shift_hinge(CABINET, DOOR, tmp_path / "a.urdf", sideways=0.01)
    wrong.tilt_hinge(CABINET, DOOR, 5.0, tmp_path / "b.urdf")
    wrong.move_handle(CABINET, DOOR, 0.01, tmp_path / "c.urdf")
    assert CABINET.read_bytes() == data
