"""Doors of the third-party corpus that swing down (dishwasher) or up (lift-up flap): the robot pulls or lifts the
handle as far as it follows it, lets go, and pushes the rest with its fingertips on the door's inner face
(planners.push_finish); the door's stay holds it wherever it is left. A flap without a stay falls shut once
released, and the certificate says so."""

from __future__ import annotations

import re

import numpy as np
import pytest

import thirdparty
from simcheck.certification import certify
from simcheck.rollout import Rollout
from thirdparty.build import G, STAY_MARGIN, stay_friction
from thirdparty.urdf_writer import Geom


def test_a_stay_holds_the_front_with_a_margin_over_its_weight_torque():
    """A 0.5 x 0.02 x 0.4 m panel (2 kg at 500 kg/m^3) hinged along x at its top edge: weight torque 2 g 0.2."""
    panel = Geom("box", np.block([[np.eye(3), np.array([[0.25], [0.0], [-0.2]])], [np.zeros((1, 3)), 1.0]]),
                 size=[0.5, 0.02, 0.4])
    assert stay_friction([[panel]], np.zeros(3), np.array([1.0, 0, 0])) == pytest.approx(STAY_MARGIN * 2.0 * G * 0.2)


@pytest.fixture(scope="module")
def swings(tmp_path_factory):
    folder = tmp_path_factory.mktemp("swings")
    return {o.spec.name: o for o in thirdparty.build_corpus(folder, ["dishwasher", "wall_flap"])}


def test_a_dishwasher_door_is_pulled_down_then_pushed_by_the_fingertips(swings, tmp_path):
    o = swings["dishwasher"]
    t = certify(o.urdf, [o.fronts[0].task], images=False, out=tmp_path / "c").tasks[0]
    assert t.status.value == "certified", t.reason
    r = Rollout.load(tmp_path / "c" / t.rollout)
    assert r.segment_names[-3:] == ("reposition", "push", "withdraw") and r.push_segment == "push"
    push = r.in_segment("push")[r.contact_sample] & (r.contact_scene_link == o.fronts[0].moving_link)
    assert push.any() and set(r.contact_robot_link[push]) <= set(r.finger_links)
    released = np.flatnonzero(r.in_segment("release"))[-1]
    assert 0.3 * r.requested_amount < r.object_q[released] < 0.9 * r.requested_amount   # the push did the rest


def test_a_flap_with_its_stay_is_certified_and_without_one_falls_shut(swings, tmp_path):
    o = swings["wall_flap"]
    task = o.fronts[0].task
    assert certify(o.urdf, [task], images=False).tasks[0].status.value == "certified"
    loose = tmp_path / "no_stay" / o.urdf.name
    loose.parent.mkdir()
    loose.write_text(re.sub(r'friction="[0-9.]+"', 'friction="0.1"', o.urdf.read_text()))
    t = certify(loose, [task], images=False).tasks[0]
    fraction = next(c for c in t.criteria if c.name == "opened_fraction")
    assert t.status.value == "failed" and not fraction.passed, t.reason
    assert "moved back by itself once released" in fraction.detail


def test_a_plan_finished_by_a_push_is_saved_and_replayed_as_one_task(swings, tmp_path):
    """--save-plan writes the pull and the push as two consecutive expectations of the door's joint; certify-plan
    replays them as one task (the whole swing), judged as the planned one was."""
    from simcheck import certify_plan

    o = swings["dishwasher"]
    planned = certify(o.urdf, [o.fronts[0].task], images=False, out=tmp_path / "c", save_plan=True).tasks[0]
    assert planned.status.value == "certified", planned.reason
    plan_file = next((tmp_path / "c" / "plans").glob("*.plan.json"))
    replay = certify_plan(o.urdf, plan_file, images=False, out=tmp_path / "r")
    assert [t.joint for t in replay.tasks] == [planned.joint]
    t = replay.tasks[0]
    assert t.status.value == "certified", t.reason
    assert t.amount == pytest.approx(planned.amount, abs=1e-6)
