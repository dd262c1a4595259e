"""simcheck.grasp_spring: the grasp attachment's force-capped spring-damper (no simulator)."""

from __future__ import annotations

import numpy as np

from simcheck.grasp_spring import GraspSpring, spring_force


def _spring(cap=100.0):
    return GraspSpring(body=1, index=0, p_local=np.zeros(3), stiffness=1000.0, damping=10.0, cap=cap)


def test_below_the_cap_the_force_is_stiffness_times_stretch_plus_damping():
    s = _spring()
    f, slide_to = spring_force(s, np.zeros(3), np.zeros(3), np.array([0.01, 0, 0]), np.array([0, 0.5, 0]))
    assert np.allclose(f, [10.0, 5.0, 0.0]) and slide_to is None
    assert np.isclose(s.force, np.hypot(10, 5)) and not s.slid


def test_above_the_cap_the_force_is_capped_and_the_held_point_slides_to_the_cap_stretch():
    s = _spring(cap=100.0)
    p_tool = np.array([0.3, 0, 0])                           # 300 N of stretch for a 100 N cap
    f, slide_to = spring_force(s, np.zeros(3), np.zeros(3), p_tool, np.zeros(3))
    assert np.allclose(f, [100.0, 0, 0]) and s.slid and np.isclose(s.force, 300.0)
    assert np.allclose(slide_to, [0.2, 0, 0])                # 0.1 m from the tool: 100 N at 1000 N/m


def test_a_cap_reached_by_damping_alone_slides_nothing():
    s = _spring(cap=100.0)
    f, slide_to = spring_force(s, np.zeros(3), np.zeros(3), np.array([0.05, 0, 0]), np.array([10.0, 0, 0]))
    assert np.isclose(np.linalg.norm(f), 100.0) and s.slid and slide_to is None
