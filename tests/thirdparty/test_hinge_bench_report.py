"""bench.hinge_bench's report: a door's miss counts as within what recon states only when its hinge error is at
most twice the joint's stated uncertainty (graph.json's ``uncertainty.origin_m``); a door without one is not."""

from __future__ import annotations

from bench.hinge_bench import DoorRow, report


def _door(hinge_cm: float, stated_cm: float, name: str = "thick_cabinet") -> DoorRow:
    return DoorRow("wall_cabinet", name, 0, 12, hinge_cm, 0.3, hinge_cm, 0.0, "revolute", False, stated_cm)


def test_a_door_counts_as_within_its_stated_uncertainty_only_up_to_twice_it():
    assert _door(1.7, 2.1).within_stated                  # a thick door's undecided pivot, reported
    assert not _door(1.7, 0.2).within_stated              # a miss recon was sure of
    assert not _door(0.3, float("nan")).within_stated     # nothing stated


def test_the_report_prints_the_count_per_category_and_the_stated_uncertainty_of_a_door_far_off(capsys):
    report([_door(1.7, 2.1), _door(1.5, 0.2), _door(3.1, 0.3, "safe")], [], [])
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("wall_cabinet"))
    assert "1/3" in row.split("|")[0], row
    far = next(line for line in out.splitlines() if line.startswith("- safe seed 0 part 12: 3.10 cm"))
    assert far.endswith("stated uncertainty 0.30 cm"), far        # not "(within)": 3.1 > 2 x 0.3
