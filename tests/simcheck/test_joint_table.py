"""simcheck.joint_table: a body's joints and links by name from PyBullet's rows (no simulator)."""

from __future__ import annotations

from simcheck.joint_table import JointInfo, joint_table


def _info(name, child, type_="revolute"):
    return JointInfo(name=name, type=type_, index=-9, child_link=child, parent_link="", lower=0.0, upper=1.0,
                     max_force=10.0, max_velocity=2.0, damping=0.1, friction=0.2)


def test_links_are_indexed_by_joint_and_parents_are_named():
    joints, links = joint_table("base", [_info("j0", "a"), _info("j1", "b", "prismatic"), _info("j2", "c")],
                                [-1, 0, -1])
    assert links == {"base": -1, "a": 0, "b": 1, "c": 2}
    assert list(joints) == ["j0", "j1", "j2"]
    assert (joints["j1"].index, joints["j1"].parent_link, joints["j1"].child_link) == (1, "a", "b")
    assert joints["j2"].parent_link == "base" and joints["j1"].type == "prismatic"
    assert (joints["j0"].max_force, joints["j0"].friction, joints["j0"].damping) == (10.0, 0.2, 0.1)


def test_a_single_link_body_has_only_its_base():
    assert joint_table("box", [], []) == ({}, {"box": -1})
