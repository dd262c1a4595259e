"""simcheck.rest: the rest check fails on a file built to fail it (a drawer 10 mm inside a wall is pushed
out by every engine) and the pure predicate thresholds are exact."""

from __future__ import annotations

import pytest

from simcheck.rest import link_overlaps, moved_joints, rest_motion

_URDF = """<?xml version="1.0"?>
<robot name="third_party">
  <link name="world"/>
  <link name="body"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.5 0.5 0.5"/></geometry></collision></link>
  <link name="drawer"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.4 0.3"/></geometry></collision></link>
  <link name="wall"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 2 2"/></geometry></collision></link>
  <joint name="wall_joint" type="fixed"><parent link="world"/><child link="wall"/><origin xyz="-0.39 0 1"/></joint>
  <joint name="body_joint" type="fixed"><parent link="world"/><child link="body"/><origin xyz="0 0 0.25"/></joint>
  <joint name="drawer_joint" type="prismatic"><parent link="body"/><child link="drawer"/>
    <origin xyz="-0.30 0 0"/><axis xyz="-1 0 0"/><limit lower="-0.3" upper="0.3" effort="10" velocity="1"/></joint>
</robot>
"""


@pytest.fixture
def overlapping(tmp_path):
    path = tmp_path / "third_party.urdf"
    path.write_text(_URDF)
    return path


def test_moved_joints_keeps_only_joints_beyond_their_threshold():
    motion = {"d": ("slide", 0.0011), "e": ("slide", -0.0009), "h": ("hinge", 0.011), "k": ("hinge", -0.009)}
    assert moved_joints(motion) == {"d": 0.0011, "h": 0.011}


def test_overlapping_links_are_found_with_their_depth(overlapping):
    (a, b, depth), = link_overlaps(overlapping)
    assert {a, b} == {"drawer", "wall"} and depth == pytest.approx(0.01, abs=1e-6)


@pytest.mark.parametrize("engine", ["pybullet", "mujoco"])
def test_a_drawer_inside_a_wall_does_not_rest(overlapping, engine):
    if engine == "mujoco":
        pytest.importorskip("mujoco")
    assert "drawer_joint" in moved_joints(rest_motion(overlapping, engine))


def test_unknown_engine_is_named():
    with pytest.raises(ValueError, match="sapien"):
        rest_motion("x.urdf", "sapien")
