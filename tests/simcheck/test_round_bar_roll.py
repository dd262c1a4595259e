"""A round bar rolls between the gripper's flat pads: the planner lets the tool follow only part of a horizontal
hinge's turn when the bar is round and lies along the hinge, and simcheck does not count the bar's roll about its
own axis as the handle turning out of the fingers (a square bar turned the same is still lost)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planners.config import PlannerConfig
from planners.handle import find_handle, grasp_path
from planners.scene_urdf import read_scene_urdf
from planners.task import parse_task
from reach_fixtures import single_front_urdf
from simcheck.certification import certify
from simcheck.grasp import round_bar_axis

DOOR = "unit1_door2_joint"
# a top-hinged flap 1.35-1.7 m up whose friction stay (6 N*m) holds its weight (3 kg: <= 5.2 N*m) at any angle
FLAP = dict(hinge="top", bottom=1.35, width=0.6, height=0.35, upper=1.4, friction=6.0)

BAR = (np.eye(4), 0.011, 0.3)                  # a cylinder along z, radius 11 mm, 30 cm long
CLOSE = dict(tolerance=0.003, max_angle=math.radians(15.0))


def test_pads_on_a_round_bar_s_side_closing_across_it_hold_it_on_its_axis():
    pads = np.array([[0.0, -0.011, 0.05], [0.0, 0.011, 0.05]])
    axis, point = round_bar_axis(pads, np.array([0.0, 1.0, 0.0]), [BAR], **CLOSE)
    assert np.allclose(axis, [0, 0, 1]) and np.allclose(point, [0, 0, 0.05])


@pytest.mark.parametrize("pads, closing, cylinder", [
    ([[0.0, -0.011, 0.05], [0.0, 0.011, 0.05]], [0.0, 0.0, 1.0], BAR),           # closing along the axis
    ([[0.0, -0.011, 0.05], [0.0, 0.011, 0.05]], [0.0, 1.0, 0.0], (np.eye(4), 0.011, 0.02)),   # a knob (short)
    ([[0.0, -0.005, 0.15], [0.0, 0.005, 0.15]], [0.0, 1.0, 0.0], BAR),           # pads on its end, not its side
    ([[0.0, -0.011, 0.20], [0.0, 0.011, 0.20]], [0.0, 1.0, 0.0], BAR),           # beyond its end
])
def test_anything_else_is_not_a_round_bar_held_across_its_axis(pads, closing, cylinder):
    assert round_bar_axis(np.array(pads), np.array(closing), [cylinder], **CLOSE) is None


def test_the_tool_follows_part_of_the_turn_only_on_a_round_bar_along_a_horizontal_hinge(tmp_path):
    cfg = PlannerConfig()
    task = parse_task(f"open-door:{DOOR}")
    shares = {}
    for bar in ("round", "box"):
        scene = read_scene_urdf(single_front_urdf(tmp_path / f"{bar}.urdf", bar=bar, **FLAP))
        shares[bar] = find_handle(scene, task, {}, cfg, 1.0, 1.0).turn_share
    side = read_scene_urdf(single_front_urdf(tmp_path / "side.urdf", hinge="side", bottom=1.0, bar="round"))
    shares["side"] = find_handle(side, task, {}, cfg, 1.0, 1.0).turn_share
    assert shares == {"round": cfg.grasp_turn_share, "box": 1.0, "side": 1.0}
    scene = read_scene_urdf(tmp_path / "round.urdf")
    handle = find_handle(scene, task, {}, cfg, 1.0, 1.0)
    s = np.array([0.0, 1.0])
    T_moving = np.array([scene.T_world_link(handle.moving_link, {DOOR: v}) for v in s])
    T = grasp_path(handle, 0, T_moving, s, scene.joints[DOOR].axis)
    rigid = T_moving @ handle.T_link_grasps[0]
    assert np.allclose(T[:, :3, 3], rigid[:, :3, 3])                         # the held point moves with the door
    turned = math.acos(np.clip((np.trace(T[0, :3, :3].T @ T[1, :3, :3]) - 1) / 2, -1, 1))
    assert turned == pytest.approx(cfg.grasp_turn_share * 1.0, abs=1e-9)       # the tool turns half the door's turn
    assert np.allclose(T[1, :3, 0], rigid[1, :3, 0])                         # about the bar, which stays in the pads


def test_a_round_bar_rolls_in_the_fingers_and_a_square_bar_turned_the_same_is_lost(tmp_path):
    """The flap lifted to 1.0 rad with the tool turning half of it: the round bar rolls 29 deg between the pads
    and the flap is certified; the same plan executed on the same flap with a square bar (same size) turns the
    bar out of the fingers at 20 deg and is refused (grasp_held). The whole lift is held (no push finish:
    planners.push_finish would hand the flap over to a push before the wrist is loaded, the bar turned less)."""
    round_urdf = single_front_urdf(tmp_path / "round.urdf", bar="round", **FLAP)
    square_urdf = single_front_urdf(tmp_path / "square.urdf", bar="box", **FLAP)
    task = f"open-door:{DOOR}=1.0"
    held_only = PlannerConfig(push_finish=False)
    t = certify(round_urdf, [task], images=False, planner_config=held_only).tasks[0]
    assert t.status.value == "certified", t.reason
    t = certify(round_urdf, [task], against=square_urdf, images=False, planner_config=held_only).tasks[0]
    held = next(c for c in t.criteria if c.name == "grasp_held")
    assert t.status.value == "failed" and not held.passed, t.reason
    assert "turned out of the fingers" in held.detail and "round bar" not in held.detail, held.detail
