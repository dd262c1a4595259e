"""simcheck.contacts: PyBullet contact rows -> named contact points, and the overlap selection (no simulator)."""

from __future__ import annotations

import pytest

from simcheck.contacts import (FLOOR, deep_overlaps, excess_penetration, rest_contacts, robot_contact_points,
                               scene_link_contact_points)

ROBOT, FLOOR_BODY, CABINET, DRAWER = 5, 0, 1, 2
SCENE = {(CABINET, -1): "carcass", (DRAWER, 0): "drawer", (DRAWER, 1): "handle"}
ROBOT_NAMES = {-1: "base", 0: "link0", 1: "finger"}


def _row(a, b, link_a, link_b, distance, force=1.0):
    """A PyBullet contact row (only the fields simcheck reads are meaningful)."""
    return (0, a, b, link_a, link_b, (0.1, 0.2, 0.3), (0, 0, 0), (0, 0, 1), distance, force)


def test_robot_contacts_name_links_skip_base_floor_contacts_and_shallow_points():
    rows = [_row(ROBOT, FLOOR_BODY, -1, -1, -0.01),       # the base on the floor: left out
            _row(ROBOT, FLOOR_BODY, 0, -1, -0.02, 5.0),   # an arm link on the floor
            _row(ROBOT, DRAWER, 1, 1, -0.003, 2.0),       # the finger on the handle
            _row(ROBOT, DRAWER, 1, 0, -0.0001),           # shallower than min_depth
            _row(ROBOT, 9, 0, 0, -0.05)]                  # a body that is not the scene's
    out = robot_contact_points(rows, ROBOT_NAMES, SCENE, FLOOR_BODY, {-1}, min_depth=0.001)
    assert [(c.link_a, c.link_b, c.force, c.distance) for c in out] == [("link0", FLOOR, 5.0, -0.02),
                                                                       ("finger", "handle", 2.0, -0.003)]
    assert out[0].position == (0.1, 0.2, 0.3)


def test_scene_link_contacts_skip_itself_and_the_robot():
    rows = [_row(DRAWER, CABINET, 0, -1, -0.002), _row(DRAWER, DRAWER, 0, 0, -0.01),
            _row(DRAWER, ROBOT, 0, 1, -0.01), _row(DRAWER, FLOOR_BODY, 0, -1, 0.0)]
    out = scene_link_contact_points(rows, "drawer", (DRAWER, 0), SCENE, FLOOR_BODY, min_depth=0.0)
    assert [(c.link_a, c.link_b) for c in out] == [("drawer", "carcass"), ("drawer", FLOOR)]


def test_deep_overlaps_keep_the_deepest_point_of_each_scene_pair_in_first_seen_order():
    rows = [_row(DRAWER, CABINET, 1, -1, -0.004), _row(DRAWER, CABINET, 0, -1, -0.010),
            _row(DRAWER, CABINET, 1, -1, -0.006), _row(DRAWER, CABINET, 0, -1, -0.0005),
            _row(ROBOT, CABINET, 0, -1, -0.1)]
    assert deep_overlaps(rows, SCENE, tolerance=0.001) == {((DRAWER, 1), (CABINET, -1)): 0.006,
                                                           ((DRAWER, 0), (CABINET, -1)): 0.010}


def test_rest_contacts_keep_touching_and_overlapping_scene_pairs_once_with_their_depth():
    rows = [_row(DRAWER, CABINET, 0, -1, 0.0004),        # touching (a 0.4 mm gap)
            _row(CABINET, DRAWER, -1, 0, -0.0002),       # the same pair the other way round, 0.2 mm deep
            _row(DRAWER, CABINET, 1, -1, 0.005),         # 5 mm apart: not in contact
            _row(ROBOT, CABINET, 0, -1, -0.1)]           # the robot: not a scene pair
    assert rest_contacts(rows, SCENE, gap=0.001) == {((DRAWER, 0), (CABINET, -1)): 0.0002}


def test_excess_penetration_counts_only_what_is_deeper_than_at_rest():
    assert excess_penetration([], 0.001) == 0.0                       # apart now
    assert excess_penetration([-0.0005, -0.0015], 0.001) == pytest.approx(0.0005)
    assert excess_penetration([-0.004], -0.0003) == pytest.approx(0.004)   # a gap at rest counts as 0
    assert excess_penetration([-0.0008], 0.001) == 0.0
