"""A world loaded without visual shapes (a certification that renders nothing) moves exactly as one with
them: the same robot and scene states, step after step, to the bit."""

import numpy as np

import planners
from simcheck.robot_binding import sim_robot_from_spec
from simcheck.world import World

from simcheck_fixture_plans import CABINET


def _run(visuals: bool) -> np.ndarray:
    spec = planners.default_robot()
    with World(CABINET, sim_robot_from_spec(spec), visuals=visuals) as w:
        q0 = np.array(spec.home_q, dtype=float)
        w.reset_robot(q0)
        states = []
        for k in range(120):                      # drive every joint a little, then hold
            w.command_robot(q0 + 0.3 * min(k, 60) / 60, np.zeros_like(q0))
            w.step()
            states.append(np.concatenate([w.robot_q(), w.finger_q()]))
        return np.array(states)


def test_no_visual_shapes_same_physics():
    assert np.array_equal(_run(False), _run(True))
