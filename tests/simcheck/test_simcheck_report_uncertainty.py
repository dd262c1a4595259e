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
