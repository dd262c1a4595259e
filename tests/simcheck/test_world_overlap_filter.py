"""simcheck's overlap filter (for third-party files): links that interpenetrate as loaded stop colliding
with each other, and the pair is logged as a warning and recorded by name."""

from __future__ import annotations

import logging

_URDF = """<?xml version="1.0"?>
<robot name="third_party">
  <link name="world"/>
  <link name="body"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.5 0.5 0.5"/></geometry></collision></link>
  <link name="drawer"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.4 0.3"/></geometry></collision></link>
  <link name="wall"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 2 2"/></geometry></collision></link>
  <joint name="wall_joint" type="fixed"><parent link="world"/><child link="wall"/><origin xyz="0.39 0 1"/></joint>
  <joint name="body_joint" type="fixed"><parent link="world"/><child link="body"/><origin xyz="0 0 0.25"/></joint>
  <joint name="drawer_joint" type="prismatic"><parent link="body"/><child link="drawer"/>
    <origin xyz="0.30 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.3" effort="10" velocity="1"/></joint>
</robot>
"""


def test_links_overlapping_as_loaded_are_filtered_and_named_in_a_warning(tmp_path, caplog):
    from simcheck.world import World

    path = tmp_path / "third_party.urdf"
    path.write_text(_URDF)
    with caplog.at_level(logging.WARNING, logger="simcheck.scene_loading"), World(path) as world:
        (a, b, depth), = world.disabled_overlaps
    assert {a, b} == {"wall", "drawer"} and 0.005 < depth < 0.015      # the drawer reaches 10 mm into the wall
    assert any("wall" in r.message and "drawer" in r.message and "disabled" in r.message for r in caplog.records)
