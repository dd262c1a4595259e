"""A few fronts of the third-party corpus (thirdparty.FIXTURES) certified on their own URDF, and wrong estimates
of them executed against that URDF never certified (the whole corpus: ``python -m bench.thirdparty_bench``)."""

from __future__ import annotations

import pytest

import thirdparty
from simcheck.certification import certify
from thirdparty.wrong import wrong_estimate

CASES = [("kitchen_unit_double_door", 1),   # mesh handle, opens toward negative values, touches its sibling
         ("dresser_six", 4),                # mesh handle drawer, negative range, touching fronts, no inertials
         ("microwave_left_hinge", 0),       # 100 deg range, negative
         ("nightstand", 1),                 # a knob as its own link; the door opens toward negative values
         ("microwave_continuous", 0),       # a continuous hinge (pinocchio stores it as cos, sin)
         ("wall_cabinet_finger_pull", 0)]   # no handle: the door's edge overhanging the carcass is pinched


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("corpus")
    return {o.spec.name: o for o in thirdparty.build_corpus(folder, thirdparty.FIXTURES)}


@pytest.mark.parametrize("obj, k", CASES)
def test_a_corpus_front_is_certified_on_its_own_urdf(corpus, obj, k):
    o = corpus[obj]
    t = certify(o.urdf, [o.fronts[k].task], images=False).tasks[0]
    assert t.status.value == "certified", t.reason
    assert (t.amount < 0) == (o.fronts[k].sign < 0)


@pytest.mark.parametrize("obj, k, kind", [("kitchen_unit_double_door", 1, "wrong_hinge_side"),
                                          ("microwave_left_hinge", 0, "door_as_drawer"),
                                          ("dresser_six", 4, "axis30")])
def test_a_wrong_estimate_of_a_corpus_front_is_never_certified(corpus, obj, k, kind, tmp_path):
    o = corpus[obj]
    f = o.fronts[k]
    est = wrong_estimate(o.urdf, f.joint, kind, tmp_path / "wrong.urdf")
    task = f"open-drawer:{f.joint}" if kind == "door_as_drawer" else f.task
    t = certify(est, [task], against=o.urdf, images=False).tasks[0]
    assert t.status.value != "certified", t.reason


def test_an_estimate_whose_hinge_passes_through_the_handle_is_not_planned_never_unusable(tmp_path):
    """The 30 deg axis of the wall cabinet's door, tilted about the top of its hinge, passes through the handle:
    the estimate is usable but moves the handle nowhere. A verdict (not_planned, exit 1), not exit 2."""
    o = thirdparty.build_object(thirdparty.spec_named("wall_cabinet_double"), tmp_path)
    f = o.fronts[0]
    est = wrong_estimate(o.urdf, f.joint, "axis30", tmp_path / "wrong.urdf")
    t = certify(est, [f.task], against=o.urdf, images=False).tasks[0]
    assert t.status.value == "not_planned" and "does not move when the joint opens" in t.reason


def test_a_front_whose_edges_cannot_be_pinched_says_what_is_in_the_way(tmp_path):
    """``sink_base_no_handles``: no handle, and every edge of the closed door has the carcass or the touching
    sibling door behind or beside it: a verdict of the robot (unreachable) naming the sibling, not exit 2."""
    o = thirdparty.build_object(thirdparty.spec_named("sink_base_no_handles"), tmp_path)
    t = certify(o.urdf, [o.fronts[0].task], images=False).tasks[0]
    assert t.status.value == "unreachable", t.reason
    assert "no edge" not in t.reason and "20 mm front panel can be pinched" in t.reason
    assert "scene::DoorRight1" in t.reason
