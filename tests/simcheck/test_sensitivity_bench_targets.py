"""bench.sensitivity_bench's targets: a certified wrong estimate must have opened the truth within the robot's
bounds (re-checked on its rollout, not by the criteria code), the largest error of each kind is never
certified, every truth is certified -- and each line can say NO."""

from __future__ import annotations

import numpy as np

from bench.sensitivity_bench import KINDS, Run, targets, truth_execution_problems

from simcheck_rollout_factory import good_rollout, with_


def test_a_clean_opening_is_within_the_robots_bounds():
    assert truth_execution_problems(good_rollout()) == []


def test_each_bound_beyond_which_a_real_robot_fails_is_named():
    r = good_rollout()
    opening = r.segment == 2
    lost = with_(r, grasp_active=r.grasp_active & ~(opening & (np.arange(r.n) > np.flatnonzero(opening)[5])))
    assert "not held" in truth_execution_problems(lost)[0]
    pulled = with_(r, grasp_force=np.where(r.grasp_active, 60.0, 0.0))               # holds 112 N: 56 N certified
    assert "60 N through the grasp" in truth_execution_problems(pulled)[0]
    effort = np.full((r.n, 4), 0.2)
    effort[opening, 1] = 1.0
    assert "robot joint y at 100% of its effort limit" in truth_execution_problems(with_(r, robot_effort=effort))[0]
    short = with_(r, object_q=r.object_q * 0.5)                                       # the truth opened half
    assert "opened 50% of the request" in truth_execution_problems(short)[0]
    # the truth's joint opens the other way (its reference_joint direction -1): judged by its own value
    assert truth_execution_problems(with_(r, object_q=-r.object_q), direction=-1) == []
    hit = with_(r, contact_robot_link=np.array(["finger_a", "link3"]), contact_scene_link=np.array(["cabinet1_handle3",
                                                                                                  "cabinet1_body1"]))
    assert "robot link link3 hit cabinet1_body1 with 40 N" in truth_execution_problems(hit)[0]


def _run(kind, error, status, problems=()):
    return Run(kind, error, 0, "open-door:d", status, (), 20.0, 1.0, "", problems=problems)


def test_the_targets_say_no():
    kinds = [k for k in KINDS if k.name == "hinge_sideways"]
    big = max(kinds[0].full)
    ok = [_run("hinge_sideways", 0.0, "certified"), _run("hinge_sideways", 0.015, "certified"),
          _run("hinge_sideways", big, "failed"), _run("hinge_sideways", -big, "failed")]
    assert all(met for _, met, _ in targets(kinds, ok))
    beyond = ok[:1] + [_run("hinge_sideways", 0.015, "certified", ("75 N through the grasp",))] + ok[2:]
    lines = {name: (met, measured) for name, met, measured in targets(kinds, beyond)}
    met, measured = lines["every certified wrong estimate opened the truth within the robot's bounds"]
    assert not met and "75 N through the grasp" in measured
    gross = ok[:3] + [_run("hinge_sideways", -big, "certified")]
    assert not dict((n, m) for n, m, _ in targets(kinds, gross))["hinge sideways 5 cm (largest swept) never certified"]
    truth_failed = [_run("hinge_sideways", 0.0, "failed")] + ok[1:]
    assert not targets(kinds, truth_failed)[0][1]
