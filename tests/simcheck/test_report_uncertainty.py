"""The report's joint-uncertainty table shows graph.json's numbers under their keys."""

from simcheck.report._tables import uncertainty_table


def test_uncertainty_table_shows_each_movable_joints_spreads():
    graph = {"objects": [{"joints": [
        {"name": "cab_root", "type": "fixed"},
        {"name": "cab_door2_joint", "type": "revolute",
         "uncertainty": {"axis_deg": 0.25, "origin_m": 0.0042, "upper": 0.03, "samples": 10, "method": "bootstrap"}}]}]}
    html = uncertainty_table(graph)
    assert 'data-key="graph.cab_door2_joint.uncertainty.origin_m">0.0042<' in html
    assert 'data-key="graph.cab_door2_joint.uncertainty.axis_deg">0.25<' in html
    assert "cab_root" not in html and "bootstrap" in html
    assert uncertainty_table({"objects": [{"joints": [{"name": "a", "type": "fixed"}]}]}) == ""
    assert "undecided" not in html
    graph["objects"][0]["joints"][1]["uncertainty"]["side_undecided"] = True
    assert ">undecided<" in uncertainty_table(graph)


def test_robust_table_shows_successes_bound_and_each_failing_sample():
    from simcheck.report._tables import robust_table

    block = {"samples": 30, "successes": 28, "success_lower_bound": 0.806, "confidence": 0.95,
             "worst_margins": {"grasp_held": -0.01, "opened_fraction": None}, "perturbations": [],
             "failures": [{"sample": 4, "outcome": "failed", "reason": "grasp_held: lost at t=7.8 s"},
                          {"sample": 17, "outcome": "failed", "reason": "handle left the path",
                           "perturbation": {"hinge_side": "other"}}]}
    html = robust_table("door4", block)
    assert 'data-key="cert.door4.robust.success_lower_bound">0.806<' in html
    assert 'data-key="cert.door4.robust.worst_margins.grasp_held">-0.01<' in html
    assert "grasp_held: lost at t=7.8 s" in html and ">17<" in html
    assert html.count("hinged at the door's other edge") == 1
    assert robust_table("door4", None) == ""
