"""Every criterion passes on a clean rollout and FAILS on a rollout built to fail it (no PyBullet)."""

import math

import numpy as np
import pytest

from simcheck.config import CriteriaConfig
from simcheck.criteria import (CriterionResult, at_release, grasp_force, grasp_held, interaction_force,
                               opened_overshoot, handle_path_deviation, opened_fraction,
                               plan_collision_free, plan_found, robot_joint_limits, rollout_criteria,
                               settled_angular_speed, settled_linear_speed, unexpected_contact_depth,
                               unexpected_contact_force)

from simcheck_rollout_factory import good_rollout, with_


@pytest.fixture(scope="module")
def good():
    return good_rollout()


def test_clean_rollout_passes_every_criterion_with_margins(good):
    results = rollout_criteria(good)
    assert [r.name for r in results if not r.passed] == []
    by = {r.name: r for r in results}
    assert by["opened_fraction"].value == pytest.approx(1.0)
    assert by["opened_fraction"].margin == pytest.approx(0.1)
    assert by["handle_path_deviation"].value < 2e-3
    assert by["grasp_held"].value < 3e-3
    assert by["unexpected_contact_force"].value == 0.0   # finger-handle contacts are expected


def test_opened_fraction_fails_when_the_joint_stops_short(good):
    s = np.minimum(good.object_q, 0.2)
    r = opened_fraction(with_(good, object_q=s))
    assert not r.passed
    assert r.value == pytest.approx(0.2 / 0.3)
    assert r.margin == pytest.approx(0.2 / 0.3 - 0.9)
    assert "cabinet1_drawer2_joint opened 0.200 of the requested 0.300" in r.detail


def test_opened_fraction_counts_from_the_start_value(good):
    r = opened_fraction(with_(good, object_q0=0.1))
    assert r.value == pytest.approx((0.3 - 0.1) / 0.3) and not r.passed


def test_handle_path_deviation_fails_when_the_handle_leaves_the_plan(good):
    gp = good.grasp_point.copy()
    mask = good.in_segment("open")
    lateral = np.linspace(0.0, 0.15, mask.sum())            # a 30 deg axis error over 0.3 m
    gp[mask, 1] += lateral
    r = handle_path_deviation(with_(good, grasp_point=gp))
    assert not r.passed
    assert r.value == pytest.approx(0.15, abs=2e-3)
    assert "cabinet1_handle3 left the planned path by 0.15" in r.detail


def test_handle_path_deviation_is_infinite_without_a_grasp(good):
    r = handle_path_deviation(with_(good, grasp_point=np.full_like(good.grasp_point, np.nan)))
    assert not r.passed and math.isinf(r.value)
    assert "never grasped" in r.detail


def test_handle_path_deviation_does_not_pass_a_handle_that_stays_put(good):
    # the drawer does not move at all while the plan pulls: time-aligned deviation sees it
    T = good.T_world_handle.copy()
    T[:, :3, 3] = T[0, :3, 3]
    gp = np.where(np.isfinite(good.grasp_point), T[:, :3, 3], np.nan)
    r = handle_path_deviation(with_(good, grasp_point=gp, T_world_handle=T))
    assert not r.passed and r.value == pytest.approx(0.3, abs=2e-3)


def test_settled_linear_speed_fails_when_the_link_still_moves_after_release(good):
    v = good.link_speed.copy()
    k = at_release(good)
    assert good.segment[k] == 3 and good.segment[k + 1] == 4      # the last sample of "release"
    v[k] = 0.25
    r = settled_linear_speed(with_(good, link_speed=v))
    assert not r.passed and r.margin == pytest.approx(0.05 - 0.25)
    assert "cabinet1_drawer2 still moved at 0.250 m/s" in r.detail and "after the gripper let go" in r.detail


def test_settled_speed_is_read_before_the_final_hold(good):
    v = good.link_speed.copy()
    v[at_release(good)] = 0.25
    v[-1] = 0.0                                                    # at rest at the end: still failed
    assert not settled_linear_speed(with_(good, link_speed=v)).passed


def test_settled_angular_speed_fails_when_the_link_still_turns(good):
    w = good.link_angular_speed.copy()
    w[at_release(good)] = 1.5
    r = settled_angular_speed(with_(good, link_angular_speed=w))
    assert not r.passed and r.value == pytest.approx(1.5)


def test_unexpected_contact_force_fails_on_a_robot_scene_contact(good):
    r0 = good
    bad = with_(r0, contact_sample=np.append(r0.contact_sample, 30), contact_robot_link=np.append(r0.contact_robot_link, "link5"),
                contact_scene_link=np.append(r0.contact_scene_link, "cabinet1_body1"),
                contact_force=np.append(r0.contact_force, 42.0), contact_depth=np.append(r0.contact_depth, 0.002))
    r = unexpected_contact_force(bad)
    assert not r.passed and r.value == pytest.approx(42.0)
    assert "robot link link5 hit scene link cabinet1_body1" in r.detail and "grasp" in r.detail
    assert unexpected_contact_depth(bad).passed           # 2 mm is inside the penetration tolerance


def test_a_finger_pushing_the_part_is_expected_only_in_the_push_segment(good):
    """A plan finished by a push (planners.push_finish): the finger on the moving link is expected in the segment
    named by ``push_segment`` and counts toward the force applied to the part; anywhere else it is a hit."""
    k = 20                                             # samples per segment in good_rollout
    pushing = with_(good, segment_names=("approach", "grasp", "open", "release", "push"), push_segment="push",
                    contact_sample=np.append(good.contact_sample, 4 * k + 5),
                    contact_robot_link=np.append(good.contact_robot_link, "finger_a"),
                    contact_scene_link=np.append(good.contact_scene_link, "cabinet1_drawer2"),
                    contact_force=np.append(good.contact_force, 30.0),
                    contact_depth=np.append(good.contact_depth, 0.001))
    assert unexpected_contact_force(pushing).passed
    assert interaction_force(pushing).value == pytest.approx(max(30.0, float(good.grasp_force.max())))
    in_approach = with_(pushing, contact_sample=np.append(good.contact_sample, 5))
    not_a_push = with_(pushing, push_segment="")
    for bad in (in_approach, not_a_push):
        r = unexpected_contact_force(bad)
        assert not r.passed and r.value == pytest.approx(30.0) and "finger_a hit scene link cabinet1_drawer2" in r.detail


def test_gripper_on_a_non_handle_link_is_unexpected(good):
    bad = with_(good, contact_scene_link=np.array(["cabinet1_drawer2", "cabinet1_handle3"]))
    assert not unexpected_contact_force(bad).passed


def test_unexpected_contact_depth_fails_on_a_deep_floor_contact(good):
    bad = with_(good, contact_sample=np.array([5]), contact_robot_link=np.array(["link7"]),
                contact_scene_link=np.array(["floor"]), contact_force=np.array([1.0]), contact_depth=np.array([0.02]))
    r = unexpected_contact_depth(bad)
    assert not r.passed and r.value == pytest.approx(0.02)
    assert "floor" in r.detail and "20.0 mm" in r.detail
    assert unexpected_contact_force(bad).passed           # 1 N alone is tolerated


def test_grasp_held_fails_when_the_grasp_is_lost_mid_opening(good):
    active = good.grasp_active.copy()
    idx = np.flatnonzero(good.in_segment("open"))
    active[idx[10]:] = False
    r = grasp_held(with_(good, grasp_active=active, grasp_note="grasp torn off at t=1.00 s"))
    assert not r.passed and math.isinf(r.value)
    assert "lost at t=" in r.detail and "torn off" in r.detail


def test_grasp_held_fails_when_the_handle_slips(good):
    gp = good.grasp_point.copy()
    mask = good.in_segment("open")
    gp[mask, 0] -= np.linspace(0, 0.04, mask.sum())
    r = grasp_held(with_(good, grasp_point=gp))
    assert not r.passed and r.value == pytest.approx(0.04, abs=2e-3)


def test_grasp_held_fails_without_any_grasp(good):
    r = grasp_held(with_(good, grasp_active=np.zeros_like(good.grasp_active),
                         grasp_note="no grasp: finger finger_a does not touch handle cabinet1_handle3"))
    assert not r.passed and "never held handle cabinet1_handle3" in r.detail and "does not touch" in r.detail


def test_robot_joint_limits_fails_beyond_a_limit(good):
    q = good.robot_q.copy()
    q[40, 2] = 1.05
    r = robot_joint_limits(with_(good, robot_q=q))
    assert not r.passed and r.value == pytest.approx(0.05)
    assert "robot joint z" in r.detail


def test_robot_joint_limits_ignores_unlimited_joints(good):
    q = good.robot_q.copy()
    q[:, 3] = 7.0
    r = robot_joint_limits(with_(good, robot_q=q, robot_lower=np.array([-1, -1, -1, -np.inf]),
                                 robot_upper=np.array([1, 1, 1, np.inf])))
    assert r.passed


def test_robot_joint_limits_fails_when_a_joint_is_commanded_past_its_limit(good):
    target = good.robot_q.copy()
    target[10, 1] = 1.2                                   # the joint itself stopped at its limit
    r = robot_joint_limits(with_(good, robot_q_target=target))
    assert not r.passed and r.value == pytest.approx(0.2) and "robot joint y was commanded 0.200" in r.detail


def test_grasp_force_fails_above_what_the_gripper_holds_with_its_safety_factor(good):
    ok = grasp_force(good)                                  # the gripper holds 112 N: 56 N with a factor of 2
    assert ok.passed and ok.value == pytest.approx(20.0) and ok.threshold == 56.0 and ok.unit == "N"
    f = good.grasp_force.copy()
    f[np.flatnonzero(good.grasp_active)[5]] = 80.0          # held without slipping, but without margin
    bad = grasp_force(with_(good, grasp_force=f))
    assert not bad.passed and bad.margin == pytest.approx(56.0 - 80.0) and "80 N through the grasp" in bad.detail
    assert "holds 112 N, 56 N with a safety factor of 2" in bad.detail
    assert grasp_force(with_(good, grasp_force=f), CriteriaConfig(grasp_safety_factor=1.0)).passed


def test_grasp_force_is_not_judged_while_the_part_rests_on_its_end_stop(good):
    open_ = np.flatnonzero(good.in_segment("open"))
    f = good.grasp_force.copy()
    f[open_[-1]] = 150.0                                    # the last opening sample: the drawer is at 0.3 m
    stopped = with_(good, grasp_force=f, object_limits=np.array([0.0, 0.3]))
    r = grasp_force(stopped)
    assert r.passed and r.value == pytest.approx(20.0) and "150 N pulling cabinet1_drawer2_joint against its end stop" in r.detail
    assert interaction_force(stopped).passed
    f[open_[len(open_) // 2]] = 150.0                       # half open, far from the stop: judged
    r = grasp_force(with_(stopped, grasp_force=f))
    assert not r.passed and r.value == 150.0
    assert not grasp_force(with_(good, grasp_force=f)).passed          # no limits recorded: every sample judged


def test_grasp_force_without_a_grasp_is_not_measured(good):
    r = grasp_force(with_(good, grasp_active=np.zeros_like(good.grasp_active), grasp_force=np.zeros(good.n)))
    assert not r.passed and r.value == math.inf and "never grasped" in r.detail


def test_opened_overshoot_fails_past_the_request(good):
    assert opened_overshoot(good).passed and opened_overshoot(good).value == 0.0
    s = good.object_q * 1.25
    T = good.T_world_handle.copy()
    T[:, 0, 3] = 1.0 + s
    r = opened_overshoot(with_(good, object_q=s, T_world_handle=T))
    assert not r.passed and r.value == pytest.approx(0.25) and "25% past" in r.detail


def test_opened_fraction_is_measured_along_the_estimates_axis(good):
    """A reference whose joint axis is the opposite (-x, range negative): its raw value went -0.3, its
    handle moved +0.3 along the estimate's +x: judged by the motion."""
    flipped = with_(good, object_q=-good.object_q, opening_type="prismatic", opening_axis=np.array([1.0, 0, 0]))
    r = opened_fraction(flipped)
    assert r.passed and r.value == pytest.approx(1.0, abs=0.01) and "changed by -0.300" in r.detail
    sideways = with_(good, opening_type="prismatic", opening_axis=np.array([0.0, 1.0, 0]))
    assert not opened_fraction(sideways).passed           # it moved across the estimate's axis


def test_opened_fraction_of_a_door_is_its_rotation_about_the_estimated_axis(good):
    from scipy.spatial.transform import Rotation
    th = np.clip(good.object_q / 0.3, 0, 1) * 1.2
    T = np.repeat(np.eye(4)[None], good.n, axis=0)
    T[:, :3, :3] = Rotation.from_rotvec(np.outer(-th, [0, 0, 1.0])).as_matrix()    # turns about -z
    door = with_(good, object_q=th, T_world_handle=T, requested_amount=1.2, opening_type="revolute")
    assert opened_fraction(with_(door, opening_axis=np.array([0, 0, -1.0]))).value == pytest.approx(1.0, abs=1e-6)
    assert opened_fraction(with_(door, opening_axis=np.array([0, 0, 1.0]))).value == pytest.approx(-1.0, abs=1e-6)


def test_interaction_force_adds_pushes_of_non_finger_links_to_the_grasp(good):
    ok = interaction_force(good)                          # only the fingers touch the handle
    assert ok.passed and ok.value == pytest.approx(20.0) and ok.threshold == 112.0
    k = int(np.flatnonzero(good.grasp_active)[3])
    pushed = with_(good, contact_sample=np.append(good.contact_sample, k),
                   contact_robot_link=np.append(good.contact_robot_link, "hand"),
                   contact_scene_link=np.append(good.contact_scene_link, "cabinet1_drawer2"),
                   contact_force=np.append(good.contact_force, 100.0), contact_depth=np.append(good.contact_depth, 0.0))
    r = interaction_force(pushed)
    assert not r.passed and r.value == pytest.approx(120.0) and "pushed by hand 100 N" in r.detail


def test_plan_found_and_plan_collision_free():
    assert plan_found(True).passed and not plan_found(False, "no stand pose").passed
    assert plan_found(False, "no stand pose").detail == "no stand pose"
    ok = plan_collision_free(0.001, "")
    bad = plan_collision_free(0.02, "robot link hand penetrates scene link body by 20 mm")
    assert ok.passed and not bad.passed and bad.margin == pytest.approx(0.005 - 0.02)


def test_thresholds_come_from_the_config(good):
    strict = CriteriaConfig(opened_fraction=1.01)
    assert not opened_fraction(good, strict).passed
    assert opened_fraction(good, strict).threshold == 1.01


def test_criterion_json_round_trip_keeps_infinite_values_failing():
    r = grasp_held(with_(good_rollout(), grasp_active=np.zeros(120, bool)))
    d = r.to_dict()
    assert d["value"] is None                               # JSON has no infinity
    back = CriterionResult.from_dict(d)
    assert math.isinf(back.value) and not back.passed and back.name == "grasp_held"


def test_robot_joint_effort_fails_when_a_joint_is_held_at_its_limit(good):
    from simcheck.criteria import robot_joint_effort

    assert robot_joint_effort(good).passed and robot_joint_effort(good).detail == "not recorded"
    effort = np.full(np.shape(good.robot_q), 0.3)
    ok = robot_joint_effort(with_(good, robot_effort=effort))
    assert ok.passed and ok.value == pytest.approx(0.3) and ok.unit == ""
    effort[len(effort) // 2, 1] = 1.0
    bad = robot_joint_effort(with_(good, robot_effort=effort))
    assert not bad.passed and bad.threshold == pytest.approx(0.99)
    assert good.robot_joint_names[1] in bad.detail and "effort limit" in bad.detail
