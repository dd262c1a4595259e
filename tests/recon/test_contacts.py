"""recon.contacts: Eq. 1 contacts against closed-form overlaps (Align, Dist, Cont)."""

import numpy as np
import pytest

from recon.contacts import contact_edge
from recon.primitive import Primitive

from recon_boxes import CFG, box, planes


@pytest.mark.parametrize("shift, expected", [(0.0, 1.0), (0.1, 0.5), (0.16, 0.2)])
def test_cont_is_the_overlapping_fraction_of_the_child_face(shift, expected):
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])                    # 1 x 1 slab
    child = box([0.3 + shift, -0.1, 0.74], [0.5 + shift, 0.1, 0.9])    # 0.2 x 0.2 block on it
    e = contact_edge(1, planes(top), 2, planes(child), CFG.contacts)
    assert e is not None and e.score == pytest.approx(expected, abs=1e-9)
    assert e.dist == pytest.approx(0.0, abs=1e-12) and e.align == pytest.approx(1.0)
    # the reverse direction divides by the slab's face: a small ratio
    r = contact_edge(2, planes(child), 1, planes(top), CFG.contacts)
    assert r is None or r.score < 0.05 + 1e-9


def test_no_contact_when_too_far_too_tilted_or_not_overlapping():
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])
    gap = box([-0.1, -0.1, 0.74 + 1.5 * CFG.contacts.theta_d], [0.1, 0.1, 0.9])
    tilted = box([-0.1, -0.1, 0.745], [0.1, 0.1, 0.9], rotvec=(0.4, 0, 0))   # 23 deg
    beside = box([0.6, -0.1, 0.74], [0.8, 0.1, 0.9])
    for child in (gap, tilted, beside):
        assert contact_edge(1, planes(top), 2, planes(child), CFG.contacts) is None
    near = box([-0.1, -0.1, 0.74 + 0.5 * CFG.contacts.theta_d], [0.1, 0.1, 0.9])
    assert contact_edge(1, planes(top), 2, planes(near), CFG.contacts) is not None


def test_leg_cylinder_cap_touches_the_top():
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])
    T = np.eye(4)
    T[:3, 3] = [0.4, 0.4, 0.35]
    leg = Primitive("cylinder", [0.06, 0.06, 0.7], T)
    e = contact_edge(1, planes(top), 2, planes(leg), CFG.contacts)
    assert e is not None and e.score == pytest.approx(1.0, abs=1e-6)
