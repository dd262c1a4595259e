"""Touching at rest is not blocking (issue 11, item 2): links in contact in the loaded state (sibling fronts,
a door in its frame) do not collide, so the contact neither blocks the opening nor counts as a contact of
the moving part; but the part may not pass into them deeper than at rest (``rest_contact_penetration``)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from simcheck.certification import certify
from simcheck.criteria import rest_contact_penetration
from simcheck_rollout_factory import good_rollout
from thirdparty import FrontSpec, ObjectSpec, build_object


def _double_door(tmp_path, gap: float, hinge: str, front_t: float):
    spec = ObjectSpec("double_door", "cabinet", 0.8, 0.56, 0.78, elevation=0.1, gap=gap, front_t=front_t,
                      fronts=(FrontSpec("door_left", (0, 0.4, 0.1, 0.88), hinge=hinge),
                              FrontSpec("door_right", (0.4, 0.8, 0.1, 0.88), sign=-1, hinge=hinge)))
    return build_object(spec, tmp_path)


def test_doors_overlapping_1mm_at_rest_each_open_and_are_certified(tmp_path):
    """1 mm is shallower than the overlap filter's tolerance: PyBullet used to push them apart at load."""
    o = _double_door(tmp_path, -0.001, "back", 0.02)
    for f in o.fronts:
        t = certify(o.urdf, [f.task], images=False).tasks[0]
        assert t.status.value == "certified", t.reason
        c = {x.name: x for x in t.criteria}["rest_contact_penetration"]
        assert c.passed and c.value < 0.001


def test_a_door_whose_corner_sweeps_into_the_sibling_it_touches_is_blocked_and_says_so(tmp_path):
    """Hinged at the front face of an 8 cm panel, the back corner sweeps sqrt(0.4^2 + 0.08^2) - 0.4 = 7.9 mm
    past the free edge: into the touching sibling. Physically blocked: failed, naming the sibling."""
    o = _double_door(tmp_path, 0.0, "front", 0.08)
    t = certify(o.urdf, [o.fronts[0].task], images=False).tasks[0]
    assert t.status.value == "failed"
    assert "rest_contact_penetration: door_left_0 passed" in t.reason and "into door_right_1" in t.reason


def test_the_criterion_judges_the_recorded_excess():
    r = good_rollout()
    assert rest_contact_penetration(r).passed and rest_contact_penetration(r).value == 0.0   # nothing touched
    ex = np.zeros(r.n)
    ex[r.n // 2] = 0.004
    bad = dataclasses.replace(r, rest_contact_links=("door_b",), rest_contact_excess=ex, rest_contact_worst="door_b")
    c = rest_contact_penetration(bad)
    assert not c.passed and c.value == pytest.approx(0.004) and "4.0 mm into door_b" in c.detail
