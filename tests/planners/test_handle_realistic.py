"""The backed-off grasp candidate on reconstructed handles: it must still close on the bar.

Realistic reconstructions of kitchen seed 1 (cabinet1_drawer2/4) gave 12 mm bars standing only 12 mm proud
of a front fitted 30 mm too far out; the centre grasp put the tilted fingertips into that front, the
planner took the candidate backed off 15 mm, and on the truth the fingers closed on air. The back-off is
now at most half the grasped shape's depth along the approach (``PlannerConfig.grasp_backoff_share``).
"""

from __future__ import annotations

import re

import numpy as np
import pytest
import trimesh

from planners import OpenTask, PlannerConfig
from planners.handle import find_handle
from planners.scene_urdf import read_scene_urdf

DRAWER = "cabinet1_drawer12_joint"
CFG = PlannerConfig()


def _drawer_handle(variants, name: str, collisions: str):
    """The fixture with the drawer handle (on the drawer front at x = 0.285 in the drawer link, outward +x in
    the link, world -x) replaced by ``collisions`` (URDF <collision> elements in the handle link's frame)."""
    link = (f'<link name="cabinet1_handle13">\n    <inertial><origin xyz="0 0 0"/><mass value="0.1"/>'
            f'<inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>\n{collisions}\n  </link>')
    text = re.sub(r'<link name="cabinet1_handle13">.*?</link>', link, variants.text, count=1, flags=re.S)
    return read_scene_urdf(variants.write(name, text))


def _recon_bar(bar_depth: float = 0.012) -> str:
    """A reconstructed bar (recon.handle_shapes): 300 x 12 mm box, ``bar_depth`` along the outward +x, centred
    at the link origin, on two 6 mm posts reaching back 12 mm to the front."""
    post = ('    <collision><origin xyz="{x} {y} 0" rpy="0 1.5707963 0"/><geometry><cylinder radius="0.003" '
            'length="0.012"/></geometry></collision>')
    return (f'    <collision><origin xyz="0 0 0"/><geometry><box size="{bar_depth} 0.30 0.012"/></geometry></collision>\n'
            + post.format(x=-bar_depth / 2 - 0.006, y=0.135) + "\n" + post.format(x=-bar_depth / 2 - 0.006, y=-0.135))


def _backoffs(scene, cfg: PlannerConfig = CFG) -> np.ndarray:
    """(k,) metres each backed-off candidate lies outside its centre candidate, along the outward direction."""
    h = find_handle(scene, OpenTask("drawer", DRAWER), {}, cfg)
    T = scene.T_world_link(h.moving_link, {})
    frames = [T @ G for G in h.T_link_grasps]
    half = len(frames) // 2   # (centre candidates, backed-off candidates), same order
    return np.array([(c[:3, 3] - b[:3, 3]) @ c[:3, 2] for c, b in zip(frames[:half], frames[half:])])


def _fingertip_reach(robot) -> float:
    """Metres the Panda's fingertips reach past the tool frame along its approach axis (from the robot URDF's
    finger meshes: 7.2 mm)."""
    s = read_scene_urdf(robot.urdf)
    T_tool = s.T_world_link(robot.tool_frame, {})
    reach = -np.inf
    for link in ("panda_leftfinger", "panda_rightfinger"):
        T = np.linalg.solve(T_tool, s.T_world_link(link, {}))
        for g in s.links[link].collisions:
            v = trimesh.load(g.mesh, force="mesh").vertices * np.asarray(g.size)
            reach = max(reach, float(((T @ g.T_link_shape)[:3, :3] @ v.T + (T @ g.T_link_shape)[:3, 3:]).T[:, 2].max()))
    return reach


def test_thin_reconstructed_bar_is_backed_off_half_its_depth_and_fingertips_still_hold_it(variants, robot):
    scene = _drawer_handle(variants, "recon_bar.urdf", _recon_bar(0.012))
    back = _backoffs(scene)
    assert np.allclose(back, 0.006, atol=1e-9)   # half the 12 mm bar, not the 15 mm grasp_backoff
    reach = _fingertip_reach(robot)
    assert reach == pytest.approx(0.0072, abs=5e-4)
    # The fingertips end deeper than the bar's outer face by at least 5 mm of the bar: they close on it.
    # (With the former 15 mm back-off they ended 1.8 mm outside the bar: "closed on 0 of 2 contacts".)
    overlap = 0.012 / 2 - back.max() + reach
    assert overlap >= 0.005
    assert 0.012 / 2 - CFG.grasp_backoff + reach < 0   # the old candidate really missed this bar


def test_deep_envelope_keeps_the_full_backoff(variants):
    """A handle kept as its envelope box (70 mm deep, down to its mount) is backed off the full 15 mm."""
    scene = _drawer_handle(variants, "envelope.urdf",
                           '    <collision><origin xyz="-0.02 0 0"/><geometry><box size="0.07 0.30 0.012"/></geometry>'
                           '</collision>')
    assert np.allclose(_backoffs(scene), CFG.grasp_backoff, atol=1e-9)


def test_knob_lying_along_the_face_is_backed_off_up_to_half_its_diameter(variants):
    """A knob cylinder lying along the face (axis along the bar, r 8 mm): its depth along the approach is its
    diameter, 16 mm -> 8 mm back-off (measured along the outward direction, not the 20 deg tilted approach)."""
    scene = _drawer_handle(variants, "knob.urdf",
                           '    <collision><origin xyz="0 0 0" rpy="1.5707963 0 0"/><geometry><cylinder radius="0.008" '
                           'length="0.036"/></geometry></collision>')
    assert np.allclose(_backoffs(scene), 0.008, atol=1e-6)
    # A share of the whole depth (16 mm) is capped by grasp_backoff (15 mm).
    assert np.allclose(_backoffs(scene, PlannerConfig(grasp_backoff_share=1.0)), CFG.grasp_backoff, atol=1e-9)


def test_no_stand_pose_reason_names_what_the_grasp_collides_with(variants, robot):
    """A noise-inflated box in front of the drawer front engulfing the handle (as realistic kitchen seed 4's
    microwave body swallowed its door handle): no stand pose, and the reason names that box."""
    from planners import plan_open_task
    from planners.task import PlanStatus
    blocker = ('  <link name="cabinet1_panel99"><collision><origin xyz="1.225 0 0.615"/><geometry>'
               '<box size="0.07 0.4 0.2"/></geometry></collision></link>\n'
               '  <joint name="cabinet1_panel99_joint" type="fixed"><parent link="world"/>'
               '<child link="cabinet1_panel99"/></joint>\n</robot>')
    path = variants.write("engulfed.urdf", variants.text.replace("</robot>", blocker))
    plan = plan_open_task(robot, path, OpenTask("drawer", DRAWER), seed=0,
                          config=PlannerConfig(stand_candidates=12))
    assert plan.status is PlanStatus.NO_STAND_POSE
    assert "IK reached the grasp from 0" in plan.reason
    assert re.search(r"the grasp collides with: panda_\w+ / scene::cabinet1_panel99_0 \(\d+ of \d+\)", plan.reason)


def test_planning_world_exempts_the_real_handle_geometries(robot, variants):
    from planners.pin_world import PlanningWorld
    from planners.plan import robot_kinematics
    scene = read_scene_urdf(variants.walled(0.3))   # a wall link fixed to the world, after the cabinet
    h = find_handle(scene, OpenTask("drawer", DRAWER), {}, CFG)
    world = PlanningWorld(robot_kinematics(robot), scene, DRAWER, set(h.handle_geoms), {}, CFG.clearance)
    names = sorted(world.geom.geometryObjects[i].name for i in world.handle_geom_ids)
    assert names and all(n.startswith("scene::cabinet1_handle13") for n in names), names
