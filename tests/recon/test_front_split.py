"""Fronts under one label (issue 12, item 4): a chest's column of drawer fronts carrying one part id is
split at the rails between them into one drawer per front, with a warning; a single front is not."""

from __future__ import annotations

import numpy as np

from recon.config import ScanConfig
from recon.front_split import horizontal_gaps
from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays

FRONTS = [(0.02, 0.19), (0.21, 0.39), (0.41, 0.59), (0.61, 0.78)]
"""The chest's drawer fronts, bottom to top (z, m); the body's rails fill the gaps between them."""


def _chest(synth):
    box = synth.box
    body = [box([0.0, -0.4, 0.78], [0.5, 0.4, 0.8]), box([0.0, -0.4, 0.0], [0.5, 0.4, 0.02]),
            box([0.0, -0.4, 0.0], [0.5, -0.38, 0.8]), box([0.0, 0.38, 0.0], [0.5, 0.4, 0.8]),
            box([0.0, -0.4, 0.0], [0.02, 0.4, 0.8])]
    body += [box([0.48, -0.38, z1], [0.5, 0.38, z2]) for (_, z1), (z2, _) in zip(FRONTS, FRONTS[1:])]
    fronts = [box([0.48, -0.375, z0 + 0.002], [0.5, 0.375, z1 - 0.002]) for z0, z1 in FRONTS]
    handles = [(120 + k, "handle", [box([0.5, -0.08, (z0 + z1) / 2 - 0.01], [0.53, 0.08, (z0 + z1) / 2 + 0.01])])
               for k, (z0, z1) in enumerate(FRONTS)]
    return (1, "cabinet", [(101, "body", body), (102, "drawer", fronts), *handles])


def test_gaps_are_found_only_across_the_whole_front():
    rng = np.random.default_rng(0)
    z = np.concatenate([rng.uniform(z0, z1, 2000) for z0, z1 in FRONTS])
    assert np.allclose(horizontal_gaps(z, ScanConfig()), [0.2, 0.4, 0.6], atol=0.01)
    assert horizontal_gaps(rng.uniform(0.0, 0.8, 8000), ScanConfig()) == []


def test_one_label_over_four_drawer_fronts_gives_four_drawers(synth):
    props, labels = synth.scan_arrays([_chest(synth)], points_per_m2=4000.0)
    rec = reconstruct_scan(scan_from_arrays(props, labels), seed=0)
    split = [w for w in rec.warnings if "fronts separated by horizontal gaps" in w]
    assert len(split) == 1 and "object 1 (cabinet) part 102 (drawer): its points show 4 fronts" in split[0]
    obj = rec.objects[0]
    drawers = sorted((p for p in obj.parts if p.label == "drawer"), key=lambda p: p.primitive.center[2])
    assert len(drawers) == 4
    for d, (z0, z1) in zip(drawers, FRONTS):
        assert abs(d.primitive.center[2] - (z0 + z1) / 2) < 0.02 and d.primitive.size[2] < 0.2
    joints = {j.child_part_id: j for j in obj.joints}
    for d in drawers:
        j = joints[d.part_id]
        assert j.type.value == "prismatic" and j.axis[0] > 0.99 and j.upper > 0.2
    for h in (p for p in obj.parts if p.label == "handle"):     # each handle on the front it stands on
        parent = next(d for d in drawers if d.part_id == joints[h.part_id].parent_part_id)
        assert abs(parent.primitive.center[2] - h.primitive.center[2]) < 0.03


def test_a_single_front_is_not_split(kitchen_rec):
    assert not [w for w in kitchen_rec.warnings if "horizontal gaps" in w]


def _chest_without_gaps(synth, handle_levels):
    """The chest with its fronts touching (no rail shows between them) and handles centred at ``handle_levels``
    (z, m), side by side when two share a level."""
    box = synth.box
    body = [box([0.0, -0.4, 0.0], [0.48, 0.4, 0.8])]
    front = [box([0.48, -0.375, 0.02], [0.5, 0.375, 0.78])]
    ys = {z: [y for y in (-0.2, 0.2)] if handle_levels.count(z) > 1 else [0.0] for z in handle_levels}
    handles = [(120 + k, "handle", [box([0.5, y - 0.06, z - 0.01], [0.53, y + 0.06, z + 0.01])])
               for k, (z, y) in enumerate((z, y) for z in sorted(set(handle_levels)) for y in ys[z])]
    return (1, "cabinet", [(101, "body", body), (102, "drawer", front), *handles])


def test_a_drawer_label_over_fronts_without_gaps_is_cut_between_its_stacked_handles(synth):
    levels = [(z0 + z1) / 2 for z0, z1 in FRONTS]
    props, labels = synth.scan_arrays([_chest_without_gaps(synth, levels)], points_per_m2=4000.0)
    rec = reconstruct_scan(scan_from_arrays(props, labels), seed=0)
    split = [w for w in rec.warnings if "with handles stacked one above another" in w]
    assert len(split) == 1 and "part 102 (drawer): its points show 4 fronts" in split[0]
    drawers = sorted((p for p in rec.objects[0].parts if p.label == "drawer"), key=lambda p: p.primitive.center[2])
    assert len(drawers) == 4
    for d, z in zip(drawers, levels):
        assert abs(d.primitive.center[2] - z) < 0.03


def test_a_drawer_pulled_by_two_handles_side_by_side_is_one_drawer(synth):
    props, labels = synth.scan_arrays([_chest_without_gaps(synth, [0.6, 0.6])], points_per_m2=4000.0)
    rec = reconstruct_scan(scan_from_arrays(props, labels), seed=0)
    assert not [w for w in rec.warnings if "fronts" in w]
    assert sum(p.label == "drawer" for p in rec.objects[0].parts) == 1
