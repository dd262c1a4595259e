"""Kinematic AP on hand-made rankings with known AP, and joint errors against closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from recon.metrics import (EstimateError, JointMatch, average_precision, axis_angle_deg, compare_joints,
                           contact_edge_ap, joint_summary, line_distance_near, mean_average_precision,
                           undirected_scores, unsigned_axis_angle_deg)
from recon.model import JointEstimate, JointType


# ---------------------------------------------------------------- average precision
@pytest.mark.parametrize("scores, relevant, n_true, expected", [
    ([0.9, 0.8, 0.7], [True, True, True], 3, 1.0),                    # perfect
    ([0.9, 0.8, 0.7], [True, False, True], 2, (1 / 1 + 2 / 3) / 2),  # a false edge ranked second
    ([0.9, 0.8, 0.7], [False, True, True], 2, (1 / 2 + 2 / 3) / 2),  # a false edge ranked first
    ([0.9], [True], 2, 0.5),                                          # a true edge never estimated
    ([0.5, 0.5], [True, False], 1, 0.5),                              # a tie: order inside it cannot matter
    ([0.5, 0.5], [False, True], 1, 0.5),
    ([0.9, 0.5, 0.5], [True, False, True], 2, (1.0 + 2 / 3) / 2),     # tie after a hit
    ([], [], 3, 0.0),                                                 # nothing estimated
    ([0.3, 0.2], [False, False], 1, 0.0),
])
def test_average_precision_of_known_rankings(scores, relevant, n_true, expected):
    assert average_precision(np.array(scores), np.array(relevant, bool), n_true) == pytest.approx(expected)


def test_average_precision_is_undefined_without_true_items_and_rejects_inconsistent_input():
    assert np.isnan(average_precision(np.array([0.4]), np.array([False]), 0))
    with pytest.raises(EstimateError, match="2 relevant items retrieved but n_true=1"):
        average_precision(np.array([0.4, 0.3]), np.array([True, True]), 1)
    with pytest.raises(EstimateError, match="2 scores but 1 relevance"):
        average_precision(np.array([0.4, 0.3]), np.array([True]), 1)


def test_contact_edge_ap_merges_directions_and_ranks_by_score():
    true_edges = [(11, 12), (12, 13), (11, 14)]
    est = {(12, 11): 0.6, (11, 12): 0.3,       # one undirected edge, score max = 0.6
           (13, 12): 0.9,                      # true, best
           (11, 13): 0.5,                      # false, between the two
           (11, 14): 0.0}                      # score 0 = not retrieved
    # ranking: {12,13} T (0.9), {11,12} T (0.6), {11,13} F (0.5); {11,14} never retrieved
    expected = (1 / 1 + 2 / 2) / 3
    assert contact_edge_ap(true_edges, est, part_ids=[11, 12, 13, 14]) == pytest.approx(expected)
    assert undirected_scores(est) == {frozenset((11, 12)): 0.6, frozenset((12, 13)): 0.9,
                                      frozenset((11, 13)): 0.5}


def test_contact_edge_ap_perfect_and_single_part_object():
    assert contact_edge_ap([(1, 2), (2, 3)], {(1, 2): 0.2, (3, 2): 0.1}) == 1.0
    assert np.isnan(contact_edge_ap([], {}))
    assert mean_average_precision([1.0, float("nan"), 0.5]) == pytest.approx(0.75)
    assert np.isnan(mean_average_precision([float("nan")]))


@pytest.mark.parametrize("est, message", [
    ({(5, 5): 0.3}, r"cabinet3: contact edge \(5, 5\) joins a part to itself"),
    ({(5, 6): -0.1}, r"cabinet3: contact edge \(5, 6\) has score -0.1"),
    ({(5, 6): float("nan")}, r"cabinet3: contact edge \(5, 6\) has score nan"),
    ({(5, 99): 0.3}, r"cabinet3: estimated contact edge \[5, 99\] names unknown part\(s\) \[99\]"),
])
def test_contact_edge_ap_rejects_bad_estimates_naming_the_object(est, message):
    with pytest.raises(EstimateError, match=message):
        contact_edge_ap([(5, 6)], est, part_ids=[5, 6], where="cabinet3")


# ---------------------------------------------------------------- joints
def joint(child, jtype="revolute", axis=(0, 0, 1), origin=(0, 0, 0), upper=1.5, name=None):
    return JointEstimate(name or f"cabinet3_door{child}_joint", JointType(jtype), 1, child,
                         np.array(axis, float), np.array(origin, float), 0.0, upper)


def test_axis_angles_sign_aware_and_unsigned():
    assert axis_angle_deg([0, 0, 1], [0, 0, 1]) == pytest.approx(0.0)
    assert axis_angle_deg([0, 0, 1], [0, 0, -1]) == pytest.approx(180.0)       # opens the wrong way
    assert unsigned_axis_angle_deg([0, 0, 1], [0, 0, -1]) == pytest.approx(0.0)
    assert axis_angle_deg([1, 0, 0], [0, 2, 0]) == pytest.approx(90.0)
    a = np.radians(3.0)
    assert axis_angle_deg([1, 0, 0], [np.cos(a), np.sin(a), 0]) == pytest.approx(3.0)
    assert unsigned_axis_angle_deg([1, 0, 0], [-np.cos(a), np.sin(a), 0]) == pytest.approx(3.0)


def test_hinge_line_distance_closed_forms():
    # parallel vertical lines 2 cm apart: 0.02 wherever compared
    assert line_distance_near([0, 0, 0], [0, 0, 1], [0.02, 0, 5], [0, 0, 1], [0.3, 0.2, 0.7]) == pytest.approx(0.02)
    # estimated line tilted by angle t about the true line's foot at z=0: distance at height z is z*sin(t)
    t = np.radians(2.0)
    d = line_distance_near([0, 0, 0], [0, 0, 1], [0, 0, 0], [np.sin(t), 0, np.cos(t)], [0.1, 0.0, 0.5])
    assert d == pytest.approx(0.5 * np.sin(t))


def test_compare_joints_matches_by_child_and_scores_each_case():
    truth = (joint(12, "prismatic", (1, 0, 0), upper=0.35, name="cabinet3_drawer12_joint"),
             joint(13, "revolute", (0, 0, 1), (0.4, -0.3, 0.0), upper=1.6),
             joint(14, "fixed", (0, 0, 0), name="cabinet3_handle14_joint"),
             joint(15, "revolute", (0, 0, -1), (0.4, 0.3, 0.0), upper=1.6))
    est = (joint(12, "prismatic", (-1, 0, 0), (9, 9, 9), upper=0.30),        # flipped axis, origin irrelevant
           JointEstimate("cabinet3_handle14_joint", JointType.FIXED, 12, 14, np.zeros(3), np.zeros(3)),  # wrong parent
           joint(13, "revolute", (0, 0, 1), (0.4, -0.27, 0.0), upper=1.2),   # hinge 3 cm off
           joint(15, "prismatic", (1, 0, 0), upper=0.3))                     # wrong type
    centres = {12: np.array([0.4, 0, 0.5]), 13: np.array([0.4, -0.1, 0.5]), 14: np.zeros(3),
               15: np.array([0.4, 0.1, 0.5])}
    rows = {r.child_part_id: r for r in compare_joints(truth, est, centres)}
    assert rows[12].type_correct and rows[12].axis_error_deg == pytest.approx(180.0)
    assert rows[12].axis_error_unsigned_deg == pytest.approx(0.0)
    assert np.isnan(rows[12].hinge_distance_m) and rows[12].upper_error == pytest.approx(0.05)
    assert rows[13].type_correct and rows[13].hinge_distance_m == pytest.approx(0.03)
    assert rows[13].upper_error == pytest.approx(0.4)
    assert rows[14].type_correct and not rows[14].parent_correct          # fixed, but to the drawer 12
    assert rows[12].parent_correct and rows[13].parent_correct
    assert not rows[15].type_correct and rows[15].axis_error_deg == pytest.approx(90.0)
    assert np.isnan(rows[15].hinge_distance_m) and np.isnan(rows[15].upper_error)
    s = joint_summary(rows.values())
    assert s.n_joints == 4 and s.type_accuracy == pytest.approx(0.75) and s.parent_accuracy == pytest.approx(0.75)
    missing = compare_joints(truth, est[:1], centres)
    assert [r.match for r in missing] == [JointMatch.MATCHED] + [JointMatch.MISSING] * 3
    assert s.n_movable == 3 and s.median_axis_error_deg == pytest.approx(90.0)
    assert s.n_revolute == 2 and s.median_hinge_distance_m == pytest.approx(0.03)
