"""A flap or a drop-down door holds where it is left (the stay or counterbalance spring a scan does not show):
the gravity torque and stay friction of the scene description, recon writing it, a robust world keeping it,
and physics showing why: with the bearing's friction alone the reconstructed flap falls shut when released."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import thirdparty
from bench.thirdparty_bench import reconstructed_fronts
from scenes.description import (STAY_HOLD, Dynamics, Inertial, Joint, Link, SceneModel, T_translation,
                                gravity_torque, read_urdf, stay_friction, write_urdf)
from simcheck.certification import certify

G = np.array([0.0, 0.0, -9.81])


def _hinged(axis, joint_type="revolute") -> SceneModel:
    """A 2 kg panel whose centre of mass hangs 0.2 m below (and 0.05 m along) a joint at (1, 0, 1)."""
    links = [Link("world"), Link("panel", Inertial(2.0, T_translation([0.05, 0.0, -0.2]), np.eye(3) * 0.01))]
    joints = [Joint("hinge", joint_type, "world", "panel", T_translation([1.0, 0.0, 1.0]), np.asarray(axis, float),
                    dynamics=Dynamics(1.0, 0.1))]
    return SceneModel("flap", links, joints)


def test_the_stay_holds_the_largest_gravity_torque_of_a_horizontal_hinge_only():
    assert gravity_torque(_hinged([0, 1, 0]), "hinge", G) == pytest.approx(2.0 * np.hypot(0.05, 0.2) * 9.81)
    assert gravity_torque(_hinged([1, 0, 0]), "hinge", G) == pytest.approx(2.0 * 0.2 * 9.81)   # r along the axis
    assert stay_friction(_hinged([1, 0, 0]), "hinge", G) == pytest.approx(STAY_HOLD * 2.0 * 0.2 * 9.81)
    assert stay_friction(_hinged([0, 0, 1]), "hinge", G) == 0.0                 # a side-hinged door: no stay
    assert stay_friction(_hinged([1, 0, 1.5]), "hinge", G) == 0.0               # 56 deg up: nearer a side hinge
    assert stay_friction(_hinged([1, 0, 0.8]), "hinge", G) > 0.0                # 39 deg up: a tilted flap
    assert stay_friction(_hinged([1, 0, 0], "prismatic"), "hinge", G) == 0.0   # a drawer's runners hold it


@pytest.fixture(scope="module")
def flap(tmp_path_factory):
    """The corpus's top-hinged wall flap, scanned (realistic), reconstructed; (its scene.urdf, its task)."""
    folder = tmp_path_factory.mktemp("flap")
    built = thirdparty.build_object(thirdparty.spec_named("wall_flap"), folder / "corpus")
    est, _, tasks = reconstructed_fronts(built, folder / "e2e")
    return est, tasks[0][1]


def test_recon_writes_the_stay_and_a_reconstructed_flap_opens_and_stays_open(flap):
    est, task = flap
    j = read_urdf(est).joints[task.split(":")[1]]
    model = read_urdf(est)
    assert j.dynamics.friction == pytest.approx(stay_friction(model, j.name, G), rel=1e-6)
    assert j.dynamics.friction > 2.0            # a flap of a few kilograms, its centre of mass ~0.2 m off the hinge
    t = certify(est, [task], images=False).tasks[0]
    assert t.status.value == "certified", t.reason


def test_without_its_stay_the_reconstructed_flap_falls_shut_when_released(flap, tmp_path):
    """The same flap with only a bearing's friction (recon's ``joint_friction``): opened by the robot, then
    shut by gravity once let go: not certified, opened_fraction says so."""
    est, task = flap
    model = read_urdf(est)
    j = model.joints[task.split(":")[1]]
    bare = model.replaced(dataclasses.replace(j, dynamics=Dynamics(j.dynamics.damping, 0.1)))
    t = certify(write_urdf(bare, tmp_path / "bare.urdf"), [task], images=False).tasks[0]
    assert t.status.value == "failed"
    assert "opened_fraction" in t.reason, t.reason


def test_a_robust_world_of_a_flap_keeps_its_stay_whatever_friction_it_samples(flap):
    from simcheck.perturbations import Perturbation
    from simcheck.perturbed_scene import perturbed_scene

    est, task = flap
    model = read_urdf(est)
    j = model.joints[task.split(":")[1]]
    T = model.T_world_link(j.parent) @ j.T_parent_joint
    p = Perturbation(0, j.name, tuple(T[:3, :3] @ j.axis), tuple(T[:3, 3]), j.upper, 0.0, 0.0, 0.5, 1.0, 1.5, 0.8,
                     (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 1.0)
    world = perturbed_scene(est, p)
    held = world.joints[j.name].dynamics.friction
    assert held == pytest.approx(stay_friction(world, j.name, G), rel=1e-5)
    assert held == pytest.approx(1.5 * j.dynamics.friction, rel=0.05)      # the heavier world's stay is stronger
