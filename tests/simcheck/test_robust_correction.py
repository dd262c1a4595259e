"""The guarded approach of a robust sample (pure numpy): the rest of the plan is moved rigidly into the
frame the robot re-localised; with a perfect re-perception the robot stands relative to the moved scene
exactly where the plan put it, and nothing before the grasp but one appended waypoint changes."""

from __future__ import annotations

import numpy as np

from planners.task import OpenTask, PlanResult, PlanStatus, Segment
from simcheck.perturbed_scene import base_error_inverse
from simcheck.robust_correction import correction_transform, guarded_plan

PIVOT = (1.0, 0.5)
HANDLE = (1.7, 0.6)


def _T_base(q) -> np.ndarray:
    """(4, 4) planar base pose of a configuration (x, y, yaw, ...)."""
    c, s = np.cos(q[2]), np.sin(q[2])
    T = np.eye(4)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:2, 3] = q[:2]
    return T


def _segment(name: str, q: np.ndarray, gripper: str = "open") -> Segment:
    T = np.repeat(np.eye(4)[None], len(q), axis=0)
    T[:, :2, 3] = q[:, :2] + [0.7, 0.1]
    return Segment(name, q, np.zeros(len(q)), T, gripper)


def _plan() -> PlanResult:
    rng = np.random.default_rng(0)
    stand = np.array([*PIVOT, 0.1, *rng.uniform(-1, 1, 7)])
    approach = np.vstack([stand + np.r_[-0.5, -0.2, 0.3, np.zeros(7)], stand])
    later = [stand + np.r_[rng.normal(0, 0.01, 3), rng.normal(0, 0.1, 7)] for _ in range(3)]
    segs = (_segment("approach", approach), _segment("grasp", np.vstack([stand, later[0]])),
            _segment("open", np.vstack(later[:2]), "closed"), _segment("release", np.vstack(later[1:])))
    return PlanResult(PlanStatus.OK, "", OpenTask("drawer", "j", 0.3), tuple(f"j{i}" for i in range(10)), segs)


def test_a_perfect_reperception_undoes_the_base_error_after_the_approach():
    plan, err = _plan(), (0.015, -0.01, np.radians(1.0))
    out = guarded_plan(plan, err, (0.0, 0.0, 0.0), PIVOT)
    T_scene = base_error_inverse(err, PIVOT)            # where the sampled world put the scene
    assert [s.name for s in out.segments] == [s.name for s in plan.segments]
    a0, a1 = plan.segments[0], out.segments[0]
    assert len(a1.q) == len(a0.q) + 1 and np.array_equal(a1.q[:-1], a0.q)   # the drive itself is not corrected
    assert np.allclose(a1.q[-1, 3:], a0.q[-1, 3:])                            # the base moves, the arm holds
    for s0, s1 in zip(plan.segments[1:], out.segments[1:]):
        assert np.allclose(s1.q[:, 3:], s0.q[:, 3:])
        for q0, q1 in zip(s0.q, s1.q):   # relative to the moved scene the robot stands where planned
            assert np.allclose(np.linalg.inv(T_scene) @ _T_base(q1), _T_base(q0), atol=1e-12)
        assert np.allclose(np.linalg.inv(T_scene) @ s1.T_world_tool, s0.T_world_tool, atol=1e-12)


def test_the_reperception_error_is_what_is_left():
    err, rep, shift = (0.015, -0.01, np.radians(1.0)), (0.003, -0.002, np.radians(0.5)), (0.004, 0.002, 0.005)
    C = correction_transform(err, rep, PIVOT, HANDLE, shift)
    residual = np.linalg.inv(base_error_inverse(err, PIVOT)) @ C
    h = np.array([HANDLE[0] - shift[0], HANDLE[1] - shift[1], 0.0, 1.0])    # the robot follows the handle
    assert np.allclose((residual @ h)[:2] - HANDLE, rep[:2], atol=1e-12)      # turned about the handle
    assert np.isclose(np.arctan2(residual[1, 0], residual[0, 0]), rep[2])


def test_without_errors_or_a_grasp_after_an_approach_the_plan_is_kept():
    plan = _plan()
    assert guarded_plan(plan, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), PIVOT) is plan
    no_approach = PlanResult(plan.status, "", plan.task, plan.joint_names, plan.segments[1:])
    assert guarded_plan(no_approach, (0.01, 0.0, 0.0), (0.0, 0.0, 0.0), PIVOT) is no_approach
