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


def _flip(hinge_cm: float, other_cm: float, warned: bool, stated_cm: float = 0.4) -> DoorRow:
    """A handleless door 60 cm wide: hinged at its free edge when ``hinge_cm`` is the larger."""
    return DoorRow("wall_cabinet", "finger_pull", 2, 12, hinge_cm, hinge_cm, 0.1, 180.0, "revolute", warned,
                   stated_cm, other_cm)


def test_a_door_flagged_side_undecided_is_reported_apart_and_within_its_statement_only_by_the_nearer_line(capsys):
    """recon hinged it on the free edge but said the side is a guess: its 60 cm do not enter the category's
    figures; its own row shows them as estimated and by the nearer line (what a robust certificate samples)."""
    wrong, right = _flip(60.0, 0.3, True), _flip(0.3, 60.0, True)
    assert wrong.wrong_side and not right.wrong_side
    assert wrong.stated_hinge_cm == 0.3 and wrong.within_stated
    assert not _flip(60.0, 3.0, True).within_stated          # the nearer line itself 3 cm off: not covered
    ok = report([_door(0.3, 0.4), _door(0.5, 0.4), wrong, right], [], [])
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("wall_cabinet"))
    assert row.split()[1:5] == ["2", "0.40", "0.50", "0.50"] and "YES" in row, row    # the decided doors only
    every = next(line for line in out.splitlines() if line.startswith("ALL+undecided"))
    assert every.split()[1] == "4" and "NO" in every, every            # nothing hidden: 60 cm counted there
    assert "1 on the free edge" in out
    flagged = out[out.index("## Doors whose hinge side"):].splitlines()
    cells = next(line for line in flagged if line.startswith("wall_cabinet")).split()
    assert cells[1:3] == ["2", "1"] and cells[6] == "60.00" and cells[8:11] == ["0.30", "0.30", "0.30"], cells
    assert ok


def test_a_door_on_the_wrong_side_that_recon_states_as_certain_fails_its_category():
    """The same 60 cm miss without recon's flag is a wrong hinge stated as certain: it counts in its category
    (and fails it), and a flagged door whose nearer line is not within its stated uncertainty fails the run."""
    assert not report([_door(0.3, 0.4), _flip(60.0, 0.3, False)], [], [])
    assert not report([_door(0.3, 0.4), _door(0.4, 0.4), _flip(60.0, 3.0, True)], [], [])
