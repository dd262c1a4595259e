"""Opening faces (issue 12, item 4): a drawer hung from a thin rail (a table's apron) opens away from
the table, not into it, and travels as deep as the table lets it, with or without a handle."""

from __future__ import annotations

import numpy as np
import pytest

from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays


def _apron_table(synth, with_handle: bool):
    """A 1.2 x 0.8 m table (front +x) whose front apron (a 20 mm rail, labelled frame) holds a drawer."""
    box = synth.box
    apron = [box([0.50, -0.35, 0.60], [0.52, -0.2, 0.72]), box([0.50, 0.2, 0.60], [0.52, 0.35, 0.72]),
             box([0.50, -0.2, 0.70], [0.52, 0.2, 0.72])]
    parts = [(301, "top", [box([-0.6, -0.4, 0.72], [0.6, 0.4, 0.76])]), (302, "frame", apron),
             (303, "drawer", [box([0.50, -0.198, 0.602], [0.52, 0.198, 0.698])])]
    if with_handle:
        parts.append((304, "handle", [box([0.52, -0.05, 0.64], [0.545, 0.05, 0.66])]))
    for k, (sx, sy) in enumerate([(-1, -1), (-1, 1), (1, -1), (1, 1)]):
        x, y = sx * 0.55, sy * 0.35
        parts.append((305 + k, "leg", [box([x - 0.02, y - 0.02, 0.0], [x + 0.02, y + 0.02, 0.72])]))
    return (3, "table", parts)


@pytest.mark.parametrize("with_handle", [True, False])
def test_a_drawer_in_a_table_apron_opens_away_from_the_table(synth, with_handle):
    props, labels = synth.scan_arrays([_apron_table(synth, with_handle)], points_per_m2=6000.0)
    rng = np.random.default_rng(0)
    for k in ("x", "y", "z"):
        props[k] = props[k] + rng.normal(0.0, 0.002, len(props[k]))
    rec = reconstruct_scan(scan_from_arrays(props, labels), seed=0)
    joint = next(j for j in rec.joints() if j.child_part_id == 303)
    assert joint.type.value == "prismatic" and joint.parent_part_id == 302
    assert joint.axis[0] > 0.99
    assert joint.upper > 0.2
