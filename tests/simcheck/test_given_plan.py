"""simcheck/given_plan.py: a plan saved by ``certify --save-plan`` replayed with ``certify-plan`` gets the same
criteria values; the same plan spoiled (base shifted 5 cm toward the drawer, gripper closed at the pre-grasp,
expecting the other cabinet's drawer) fails with reasons naming the segment. Scene: the fixture cabinet twice,
1 m apart (one drawer planned for, with the default robot)."""

import json
import re

import numpy as np
import pytest

from simcheck.certification import certify
from simcheck.cli import main
from simcheck.certificate import Certificate
from simcheck.plan_file import plan_to_dict, read_plan
from simcheck_fixture_plans import CABINET

DRAWER = "cabinet1_drawer2_joint"
DOOR = "cabinet2_door4_joint"
OTHER = "cabinet2_drawer2_joint"

#: how close a replayed criterion must be to the planned run's: 1 % of the value, or this much per unit for
#: values near zero (m: a millimetre; N: one newton, 0.7 % of the 140 N grasp bound; fractions and ratios: 0.01)
ABS_TOL = {"m": 1e-3, "N": 1.0, "m/s": 5e-3, "rad/s": 0.02, "rad": 1e-3, "": 0.01}


def _two_cabinets(path):
    """The fixture cabinet and a copy of it 1 m along +y (links and joints cabinet2_*)."""
    text = CABINET.read_text()
    body = text[text.index("<link name=\"cabinet1_body1\""):text.index("</robot>")]
    copy = body.replace("cabinet1_", "cabinet2_").replace(
        '<parent link="world"/><child link="cabinet2_body1"/><origin xyz="0 0 0"',
        '<parent link="world"/><child link="cabinet2_body1"/><origin xyz="0 1 0"')
    assert copy.count('origin xyz="0 1 0"') == 1
    path.write_text(text.replace("</robot>", copy + "</robot>"))
    return path


@pytest.fixture(scope="module")
def planned(tmp_path_factory):
    """(scene, the certificate of the planned drawer opening then door opening (one world, the door planned
    with the drawer open), the drawer's saved plan file; the door's is beside it)."""
    out = tmp_path_factory.mktemp("given_plan")
    scene = _two_cabinets(out / "two_cabinets.urdf")
    cert = certify(scene, [f"open-drawer:{DRAWER}", f"open-door:{DOOR}"], out=out / "planned", images=False,
                   save_plan=True, carry_state=True)
    assert cert.ok, cert.summary()
    return scene, cert, out / "planned" / "plans" / f"{DRAWER}.plan.json"


def _run(scene, plan, out, capsys):
    code = main(["certify-plan", str(scene), str(plan), "--out", str(out), "--no-images", "-q", "--json"])
    return code, json.loads(capsys.readouterr().out)


def test_our_plan_replayed_gets_the_same_criteria_values(planned, tmp_path, capsys):
    scene, cert, plan = planned
    code, summary = _run(scene, plan, tmp_path, capsys)
    assert code == 0, summary
    replay = Certificate.load(tmp_path)[DRAWER]
    for c in cert[DRAWER].criteria:
        r = replay.criterion(c.name)
        assert r.passed
        assert abs(r.value - c.value) <= max(0.01 * abs(c.value), ABS_TOL[c.unit]), (c.name, c.value, r.value)
    extra = {c.name for c in replay.criteria} - {c.name for c in cert[DRAWER].criteria}
    assert extra == {"expectation_met", "articulations_still", "waypoint_gap", "joint_speed", "joint_acceleration"}


def _edited(plan_path, tmp_path, name, edit):
    doc = plan_to_dict(read_plan(plan_path))
    edit(doc)
    out = tmp_path / f"{name}.plan.json"
    out.write_text(json.dumps(doc))
    return out


def test_base_shifted_toward_the_drawer_fails_naming_the_segment(planned, tmp_path, capsys):
    scene, _, plan_path = planned
    plan = read_plan(plan_path)
    grasp = plan.segments[1]
    toward = grasp.T_world_tool[-1, :2, 3] - grasp.q[-1, :2]     # from the base to the handle, in the plane
    shift = 0.05 * toward / np.linalg.norm(toward)

    def edit(doc):
        for s in doc["segments"]:
            s.pop("tool_positions", None)
            for row in s["waypoints"]:
                row[0] += shift[0]
                row[1] += shift[1]
    code, summary = _run(scene, _edited(plan_path, tmp_path, "shifted", edit), tmp_path / "out", capsys)
    assert code == 1
    task = summary["tasks"][0]
    assert task["status"] == "failed"
    assert re.search(r"segment '(approach|grasp)'|during (approach|grasp)", task["reason"]), task["reason"]


def test_gripper_closed_at_the_pre_grasp_fails_naming_the_segment(planned, tmp_path, capsys):
    scene, _, plan_path = planned

    def edit(doc):
        doc["segments"][0]["gripper"] = "close"        # closes at the end of the approach: the pre-grasp pose
        doc["segments"][1]["gripper"] = "hold"
    code, summary = _run(scene, _edited(plan_path, tmp_path, "closed_early", edit), tmp_path / "out", capsys)
    assert code == 1
    reason = summary["tasks"][0]["reason"]
    assert "the gripper never held handle cabinet1_handle3 during segment 'open'" in reason, reason
    assert "the fingers closed in segment 'approach'" in reason, reason


def test_a_plan_that_opens_the_wrong_drawer_fails_its_expectation(planned, tmp_path, capsys):
    scene, _, plan_path = planned

    def edit(doc):
        doc["segments"][2]["expect"]["joint"] = OTHER
    code, summary = _run(scene, _edited(plan_path, tmp_path, "wrong", edit), tmp_path / "out", capsys)
    assert code == 1
    task = summary["tasks"][0]
    assert task["joint"] == OTHER and task["status"] == "failed"
    assert f"segment 'open' expected {OTHER} to move from 0.000" in task["reason"]
    assert f"moved scene joint {DRAWER}" in task["reason"]          # the drawer it did open, named


def test_a_scenario_plan_must_start_where_the_robot_is(planned, tmp_path):
    scene, _, plan_path = planned
    from simcheck.errors import PlanFileError
    from simcheck.run import run_scenario
    sc = tmp_path / "twice.yaml"
    sc.write_text(f"scene: {scene}\ntasks:\n  - plan: {plan_path}\n  - plan: {plan_path}\n")
    with pytest.raises(PlanFileError, match=r"segments\[0\].waypoints\[0\]' starts joint \w+ at .* but the robot is at"):
        run_scenario(sc, images=False)


def test_a_scenario_mixes_a_given_plan_and_a_planned_task(planned, tmp_path):
    scene, _, plan_path = planned
    from simcheck.run import run_scenario
    sc = tmp_path / "mixed.yaml"
    sc.write_text(f"scene: {scene}\ntasks:\n  - plan: {plan_path}\n  - open-drawer:{OTHER}\n")
    cert = run_scenario(sc, images=False)
    assert [t.joint for t in cert.tasks] == [DRAWER, OTHER]
    assert cert.ok, cert.summary()
    assert cert[OTHER].start_state[DRAWER] > 0.3          # the given plan's opening carried over


def test_robust_and_against_as_for_certify(planned, tmp_path, capsys):
    """--against executes on a reference; --robust N --replay-sample I executes one sampled world (the plan as
    given) and the certificate gets the robust block."""
    scene, _, plan_path = planned
    code = main(["certify-plan", str(scene), str(plan_path), "--against", str(scene), "--robust", "2",
                 "--replay-sample", "1", "--out", str(tmp_path), "--no-images", "-q"])
    capsys.readouterr()
    task = Certificate.load(tmp_path)[DRAWER]
    assert task.robust["replayed_sample"] == 1 and task.robust["samples"] == 1
    assert code in (0, 1) and task.reason.startswith("replayed sample 1")
    assert "expectation_met" in {c.name for c in task.criteria}


def test_the_held_part_follows_the_tool_in_the_recheck():
    """followed_values: a drawer moves with the tool along its axis, a door turns with it about its hinge."""
    from types import SimpleNamespace

    from planners.task import Expectation
    from simcheck.given_plan import followed_values

    drawer = SimpleNamespace(type="prismatic", axis_world=np.array([1.0, 0, 0]), origin_world=np.zeros(3))
    p = np.stack([0.3 + np.linspace(0, 0.4, 5), np.full(5, 0.2), np.full(5, 0.7)], axis=1)
    assert np.allclose(followed_values(p, drawer, Expectation("d", 0.0, 0.3)), [0.0, 0.1, 0.2, 0.3, 0.3])
    door = SimpleNamespace(type="revolute", axis_world=np.array([0, 0, -1.0]), origin_world=np.array([0.25, -0.28, 0]))
    a = np.linspace(0, 1.2, 7)
    p = np.stack([0.25 + 0.5 * np.sin(a), -0.28 + 0.5 * np.cos(a), np.full(7, 0.5)], axis=1)   # clockwise seen from +z
    assert np.allclose(followed_values(p, door, Expectation("h", 0.0, 1.5)), a)


def _drawer_then_door(plan_path, tmp_path, second=DOOR):
    """The drawer's plan joined with the door's (planned from where the drawer's execution left the robot: its
    first waypoint moved onto the drawer plan's last, by the tracking error, < 1 mm or mrad), the door's
    expectation naming ``second``."""
    from simcheck.plan_file import join_plans
    joined = plan_to_dict(join_plans(read_plan(plan_path), read_plan(plan_path.with_name(f"{DOOR}.plan.json"))))
    last, first = joined["segments"][4]["waypoints"][-1], joined["segments"][5]["waypoints"]
    assert np.abs(np.subtract(first[0], last)).max() < 1e-3
    first[0] = last
    joined["segments"][5].pop("tool_positions", None)
    joined["segments"][7]["expect"]["joint"] = second
    out = tmp_path / f"drawer_then_{second}.plan.json"
    out.write_text(json.dumps(joined))
    return out


def test_a_plan_with_two_expectations_is_judged_per_expectation(planned, tmp_path, capsys):
    scene, cert, plan_path = planned
    code, summary = _run(scene, _drawer_then_door(plan_path, tmp_path), tmp_path / "ok", capsys)
    assert code == 0, summary
    replay = Certificate.load(tmp_path / "ok")
    assert [t.joint for t in replay.tasks] == [DRAWER, DOOR]
    for joint in (DRAWER, DOOR):                      # each part executed and judged as its planned task was
        for c in cert[joint].criteria:
            r = replay[joint].criterion(c.name)
            assert r.passed and abs(r.value - c.value) <= max(0.01 * abs(c.value), ABS_TOL[c.unit]), \
                (joint, c.name, c.value, r.value)
    assert replay[DOOR].start_state[DRAWER] > 0.3     # the drawer stayed open while the door opened


def test_a_wrong_second_expectation_fails_that_expectation_only(planned, tmp_path, capsys):
    scene, _, plan_path = planned
    code, summary = _run(scene, _drawer_then_door(plan_path, tmp_path, OTHER), tmp_path / "wrong", capsys)
    assert code == 1
    first, second = summary["tasks"]
    assert (first["joint"], first["status"]) == (DRAWER, "certified"), first["reason"]
    assert (second["joint"], second["status"]) == (OTHER, "failed")
    assert f"segment 'open_2' expected {OTHER} to move from 0.000" in second["reason"], second["reason"]
    assert f"moved scene joint {DOOR}" in second["reason"]


def test_expectations_without_a_release_between_them_exit_2(planned, tmp_path, capsys):
    scene, _, plan_path = planned

    def edit(doc):
        doc["segments"] = doc["segments"][:3] + [dict(doc["segments"][2], name="open_more",
                                                            expect={"joint": DOOR, "from": 0.0, "to": 1.0})]
    code = main(["certify-plan", str(scene), str(_edited(plan_path, tmp_path, "norelease", edit)), "-q"])
    assert code == 2
    assert "no segment between segments[2] ('open') and segments[3] ('open_more')" in capsys.readouterr().err
