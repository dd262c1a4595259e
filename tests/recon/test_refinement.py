"""recon.refinement: Alg. 1 removes a leg's tilt and interpenetration."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.contacts import contact_edges
from recon.part_tree import part_tree
from recon.primitive import Primitive
from recon.refinement import interpenetration, refine_parts

from recon_boxes import CFG, box, planes


def test_refinement_removes_tilt_and_interpenetration_of_a_leg():
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec([0.06, -0.04, 0.0]).as_matrix()     # ~4 deg off vertical
    T[:3, 3] = [0.4, 0.4, 0.35 + 0.012]                                  # sunk 12 mm into the top
    leg = Primitive("box", [0.05, 0.05, 0.7], T)
    prims = {1: top, 2: leg}
    edges = contact_edges({i: planes(p) for i, p in prims.items()}, CFG.contacts)
    tree = part_tree("table", {1: "top", 2: "leg"}, {1: top.volume, 2: leg.volume}, edges, CFG.tree, CFG.contacts)
    assert tree.parent == {2: 1}
    before = interpenetration(top, leg)
    out = refine_parts(prims, tree, CFG.refinement, CFG.contacts, CFG.fitting)
    after = interpenetration(out[1], out[2])
    assert before > 1e-5 and after < 0.05 * before
    R = out[2].T_world_part[:3, :3]
    assert np.max(np.abs(np.abs(R) - np.eye(3))) < 1e-6                  # leg axes parallel to the top's
    assert out[2].corners()[:, 2].max() == pytest.approx(0.7, abs=1e-6)  # cap on the underside
    assert out[1].isclose(top)                                           # the root does not move
