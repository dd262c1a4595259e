"""Each task of a ``certify`` command is judged in freshly loaded worlds: its certificate is the same
whether it runs alone or after other tasks of the same command (real planner, mobile Panda, kitchen
seed 0, an estimate whose door hinge is 1.5 cm off -- a boundary case whose verdict once depended on
the task run before it)."""

import pytest

from simcheck.certification import certify

import simcheck.estimate_faults as wrong
from simcheck_kitchen import kitchen_truth

DOOR = "cabinet1_door2_joint"
DRAWER = "cabinet1_drawer4_joint"
FRIDGE = "refrigerator3_door14_joint"


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory):
    return kitchen_truth(tmp_path_factory, DOOR, DRAWER, FRIDGE)


def _judged(task) -> dict:
    """Everything a task certificate says except its wall-clock timings."""
    d = task.to_dict()
    d.pop("timings")
    return d


def _assert_same(a, b):
    da, db = _judged(a), _judged(b)
    ca, cb = da.pop("criteria"), db.pop("criteria")
    assert da == db
    assert [c["name"] for c in ca] == [c["name"] for c in cb]
    for x, y in zip(ca, cb):
        assert x["value"] == pytest.approx(y["value"], abs=1e-9), x["name"]
        assert (x["passed"], x["threshold"]) == (y["passed"], y["threshold"]), x["name"]


def test_a_task_is_judged_the_same_alone_and_after_other_tasks(kitchen, tmp_path):
    est = wrong.shift_hinge(kitchen / "truth.urdf", DOOR, tmp_path / "hinge15mm.urdf", sideways=0.015)
    door, drawer, fridge = f"open-door:{DOOR}", f"open-drawer:{DRAWER}", f"open-door:{FRIDGE}"
    alone = certify(est, [door], against=kitchen / "truth.urdf", images=False)
    after = certify(est, [drawer, fridge, door], against=kitchen / "truth.urdf", images=False)
    _assert_same(alone[DOOR], after[DOOR])
    drawer_alone = certify(est, [drawer], against=kitchen / "truth.urdf", images=False)
    _assert_same(drawer_alone[DRAWER], after[DRAWER])
    # every task starts from the loaded scene, each in worlds loaded for it
    assert all(v == 0.0 for t in after.tasks for v in t.start_state.values())
    assert all(t.timings["load_worlds"] > 0 for t in after.tasks)
