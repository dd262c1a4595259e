"""recon.label_fragments: a handle's points reduced to its cluster, a segmentation's stray handle labels
dropped (a ScanNet-style door's handle had 2 of its 17 points 40 cm away: its bar spanned the door and
the door became a flap)."""

from __future__ import annotations

import numpy as np

from recon.config import ScanConfig
from recon.label_fragments import handle_cluster, point_spacing, without_label_fragments
from recon.scan import ObjectPoints, PartPoints, Scan


def _bar(n: int, y0: float, seed: int) -> np.ndarray:
    """``n`` points 2 cm apart along a vertical bar at (0.03, y0), 3 mm noise."""
    rng = np.random.default_rng(seed)
    return np.c_[np.full(n, 0.03), np.full(n, y0), 0.4 + 0.02 * np.arange(n)] + rng.normal(0, 0.003, (n, 3))


def test_points_apart_from_the_handle_are_dropped():
    pts = np.concatenate([_bar(15, 0.0, 0), [[0.0, 0.40, 0.36], [0.0, 0.41, 0.35]]])
    keep = handle_cluster(pts, 0.08, 0.34)
    assert keep[:15].all() and not keep[15:].any()


def test_a_bar_seen_in_two_pieces_keeps_both():
    pts = np.concatenate([_bar(8, 0.0, 1), _bar(8, 0.0, 2) + [0.0, 0.0, 0.3]])
    assert handle_cluster(pts, 0.08, 0.34).all()


def test_the_scan_stage_reduces_handles_only_and_links_by_the_objects_spacing():
    rng = np.random.default_rng(3)
    door = np.c_[np.zeros(400), rng.uniform(-0.2, 0.2, 400), rng.uniform(0.1, 0.8, 400)]
    stray = np.array([[0.0, 0.40, 0.36], [0.0, 0.41, 0.35]])
    handle = np.concatenate([_bar(15, 0.0, 4), stray])
    parts = (PartPoints(1, 2, "door", np.concatenate([door, stray + [0.0, -0.3, 0.0]])),
             PartPoints(1, 3, "handle", handle, np.tile([1.0, 0.0, 0.0], (17, 1))))
    pts = np.concatenate([p.points for p in parts])
    scan = Scan(pts, np.ones(len(pts), np.int64), np.repeat([2, 3], [len(parts[0].points), 17]), None, None,
                (ObjectPoints(1, "cabinet", parts),), (), "test")
    out, removed = without_label_fragments(scan, ScanConfig())
    assert removed == 2 and 0.01 < point_spacing(pts) < 0.03
    door_out, handle_out = out.objects[0].parts
    assert door_out is parts[0] and len(handle_out.points) == 15 and len(handle_out.normals) == 15
    assert np.array_equal(out.points, scan.points)           # the scan's arrays keep every point


def test_a_legs_label_fragment_on_the_mattress_is_dropped():
    # random/2 scannet bed4_leg20: 25 points on the leg + 7 leg-labelled points on the mattress 1.4 m away
    rng = np.random.default_rng(5)
    leg = np.c_[rng.uniform(-0.54, -0.48, 25), rng.uniform(-2.6, -2.54, 25), rng.uniform(0.0, 0.17, 25)]
    frag = np.c_[rng.uniform(-1.62, -1.56, 7), rng.uniform(-1.7, -1.65, 7), np.full(7, 0.5)]
    frame = np.c_[rng.uniform(-1.8, -0.5, 600), rng.uniform(-2.6, -0.6, 600), rng.uniform(0.18, 0.32, 600)]
    parts = (PartPoints(1, 2, "frame", frame), PartPoints(1, 3, "leg", np.concatenate([leg, frag])))
    pts = np.concatenate([p.points for p in parts])
    scan = Scan(pts, np.ones(len(pts), np.int64), np.repeat([2, 3], [600, 32]), None, None,
                (ObjectPoints(1, "bed", parts),), (), "test")
    out, removed = without_label_fragments(scan, ScanConfig())
    assert removed == 7 and np.array_equal(out.objects[0].parts[1].points, leg)
