"""simcheck.grasp_spring: the grasp attachment's force-capped spring-damper (no simulator)."""

from __future__ import annotations

import numpy as np

from simcheck.grasp_spring import GraspSpring, cartesian_stiffness, spring_force, stable_damping, stable_stiffness


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


def test_an_anisotropic_spring_pulls_along_k_times_stretch_and_slides_to_the_cap():
    K = np.diag([1000.0, 4000.0, 9000.0])
    s = GraspSpring(body=1, index=0, p_local=np.zeros(3), stiffness=K, damping=0.0, cap=100.0)
    f, slide_to = spring_force(s, np.zeros(3), np.zeros(3), np.array([0.01, 0.01, 0.0]), np.zeros(3))
    assert np.allclose(f, [10.0, 40.0, 0.0]) and slide_to is None
    f, slide_to = spring_force(s, np.zeros(3), np.zeros(3), np.array([0.0, 0.05, 0.0]), np.zeros(3))     # 200 N
    assert np.allclose(f, [0.0, 100.0, 0.0]) and np.allclose(slide_to, [0.0, 0.025, 0.0])


def test_stiffness_above_the_stable_bound_is_lowered_to_it_direction_by_direction():
    K = np.diag([1000.0, 50000.0, 9000.0])
    s = GraspSpring(body=1, index=0, p_local=np.zeros(3), stiffness=K, damping=0.0, cap=1e6, max_stiffness=20000.0)
    f, _ = spring_force(s, np.zeros(3), np.zeros(3), np.array([0.001, 0.001, 0.001]), np.zeros(3))
    assert np.allclose(f, [1.0, 20.0, 9.0])


def test_cartesian_stiffness_of_a_two_link_planar_arm():
    # a point 1 m out along x from joint 1 and 0.5 m from joint 2: each moves it along y
    J = np.array([[1.0, 0.5]])                               # the point's y over the two joints
    K = cartesian_stiffness(J, np.array([1000.0, 500.0]))
    # along y: compliance 1^2/1000 + 0.5^2/500 = 0.0015 m/N -> 666.7 N/m
    assert np.allclose(K, [[1.0 / 0.0015]])


def test_the_stable_stiffness_is_the_effective_mass_over_twice_the_time_step_squared():
    # a door of inertia 0.5 kg m^2 about its hinge, the point 0.5 m out: effective mass 2 kg along the tangent
    J = np.array([[0.0], [0.5], [0.0]])
    assert np.isclose(stable_stiffness(J, np.array([[0.5]]), 0.01), 2.0 / 2e-4)
    assert stable_stiffness(np.zeros((3, 1)), np.array([[0.5]]), 0.01) == np.inf


def test_the_stable_damping_is_the_effective_mass_over_the_time_step_and_caps_the_damper():
    J = np.array([[0.0], [0.5], [0.0]])                      # effective mass 2 kg (as above)
    assert np.isclose(stable_damping(J, np.array([[0.5]]), 0.01), 200.0)
    assert stable_damping(np.zeros((3, 1)), np.array([[0.5]]), 0.01) == np.inf
    s = GraspSpring(body=1, index=0, p_local=np.zeros(3), stiffness=0.0, damping=50.0, cap=1e6, max_damping=20.0)
    f, _ = spring_force(s, np.zeros(3), np.zeros(3), np.zeros(3), np.array([1.0, 0, 0]))
    assert np.allclose(f, [20.0, 0, 0])


def test_a_replaced_stiffness_is_capped_again_not_the_one_before():
    s = GraspSpring(body=1, index=0, p_local=np.zeros(3), stiffness=np.diag([1000.0, 50000.0, 9000.0]), damping=0.0,
                    cap=1e6, max_stiffness=20000.0)
    stretch = np.array([0.001, 0.001, 0.001])
    for _ in range(2):                                       # the capped matrix kept for the same stiffness
        f, _ = spring_force(s, np.zeros(3), np.zeros(3), stretch, np.zeros(3))
        assert np.allclose(f, [1.0, 20.0, 9.0])
    s.stiffness = np.diag([30000.0, 2000.0, 9000.0])        # the adapter's next configuration
    f, _ = spring_force(s, np.zeros(3), np.zeros(3), stretch, np.zeros(3))
    assert np.allclose(f, [20.0, 2.0, 9.0])
    s.stiffness = 500.0                                      # isotropic, below the cap
    f, _ = spring_force(s, np.zeros(3), np.zeros(3), stretch, np.zeros(3))
    assert np.allclose(f, [0.5, 0.5, 0.5])
