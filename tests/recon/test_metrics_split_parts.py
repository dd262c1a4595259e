"""The metrics score a drawer recon split off a part labelled over several fronts as the true drawer it is
(recon.metrics.split_parts): its joint is compared, not counted missing, and a split the truth does not bear
out stays unmatched."""

from __future__ import annotations

import numpy as np

from recon.metrics import evaluate_object
from recon.metrics.joint_errors import JointMatch
from recon.metrics.objects import ObjectEstimate
from recon.metrics.split_parts import true_ids_of_new_parts
from recon.metrics.truth import TruthObject, TruthPart
from recon.model import JointEstimate, JointType
from recon.primitive import Primitive


def _box(centre, size):
    T = np.eye(4)
    T[:3, 3] = centre
    return Primitive("box", size, T)


def _drawer_joint(child, origin_z, upper=0.3):
    return JointEstimate(f"j{child}", JointType.PRISMATIC, 1, child, np.array([1.0, 0, 0]),
                         np.array([0.5, 0.0, origin_z]), 0.0, upper)


def _hollow_drawer(z):
    """A drawer's front (x 0.5-0.52) and back (x 0.05-0.07) boards centred at height ``z``: its box is hollow."""
    return _box([0.51, 0, z], [0.02, 0.75, 0.38]), _box([0.06, 0, z], [0.02, 0.7, 0.3])


BODY = _box([0.25, 0, 0.4], [0.5, 0.8, 0.8])
LOW = _box([0.28, 0, 0.2], [0.46, 0.75, 0.38])
TRUTH = TruthObject(1, "chest", "cabinet", np.eye(4), np.array([0.52, 0.8, 0.8]),
                    (TruthPart(1, "body", "body", np.eye(4), (BODY,)),
                     TruthPart(2, "drawer", "d2", np.eye(4), _hollow_drawer(0.2)),
                     TruthPart(3, "drawer", "d3", np.eye(4), _hollow_drawer(0.6))),
                    (JointEstimate("root", JointType.FIXED, None, 1, np.zeros(3), np.zeros(3)),
                     _drawer_joint(2, 0.2), _drawer_joint(3, 0.6)), ((1, 2), (1, 3)))


def _estimate(high_centre):
    """Part 2 labelled over both fronts and split by recon: part 2 (low) and new part 40 at ``high_centre``."""
    prims = (BODY, LOW, _box(high_centre, [0.46, 0.75, 0.38]))
    joints = (JointEstimate("root", JointType.FIXED, None, 1, np.zeros(3), np.zeros(3)), _drawer_joint(2, 0.2),
              _drawer_joint(40, high_centre[2]))
    return ObjectEstimate(1, "cabinet", prims, joints, {(1, 2): 1.0, (1, 40): 1.0}, part_ids=(1, 2, 40))


def test_a_split_off_drawer_is_scored_as_the_true_drawer_holding_its_centre():
    est = _estimate([0.28, 0, 0.61])             # inside the true drawer's box, in none of its boards
    assert true_ids_of_new_parts(TRUTH, est) == {40: 3}
    joints = {j.child_part_id: j for j in evaluate_object(TRUTH, est).joints}
    assert joints[3].match is JointMatch.MATCHED and joints[3].type_correct and joints[3].parent_correct


def test_a_split_the_truth_does_not_bear_out_stays_unmatched():
    est = _estimate([0.28, 0, 1.2])               # above the chest: inside no true part
    assert true_ids_of_new_parts(TRUTH, est) == {}
    joints = {j.child_part_id: j for j in evaluate_object(TRUTH, est).joints}
    assert joints[3].match is JointMatch.MISSING
