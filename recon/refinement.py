"""Spatial refinement among parts (Alg. 1), top down over the part tree.

For each child (breadth first from the root): pair each child plane normal with the parent plane
normal it is nearly parallel to (|cos| >= ``refine_align``, sign matched), find the rotation that best
maps the child normals onto the parent normals (Eq. 5, Kabsch via scipy's ``Rotation.align_vectors``),
and rotate the child — with its subtree — about its centre. A rotation above ``refine_max_angle`` is
rejected as a bad pairing. Then the contact plane pair of the tree edge is made coincident by a
translation along the parent's normal (the paper keeps only the rotation; the translation is what
removes the remaining interpenetration or gap). ``interpenetration`` measures what it changes.
"""

from __future__ import annotations

import logging

import numpy as np
from scipy.spatial.transform import Rotation

from recon.config import ContactConfig, FittingConfig, RefinementConfig
from recon.contacts import contact_pairs
from recon.part_tree import PartTree
from recon.primitive import Primitive

__all__ = ["refine_rotation", "refine_parts", "interpenetration"]

log = logging.getLogger(__name__)


def refine_rotation(parent: Primitive, child: Primitive, config: RefinementConfig,
                    contacts: ContactConfig) -> np.ndarray:
    """(3, 3) rotation R (world) such that R @ child normals ≈ matched parent normals (Eq. 5)."""
    Np = np.stack([p.normal for p in parent.planes(contacts.cylinder_side_faces)])
    Nc = np.stack([c.normal for c in child.planes(contacts.cylinder_side_faces)])
    dots = Nc @ Np.T
    best = np.argmax(np.abs(dots), axis=1)
    cos = dots[np.arange(len(Nc)), best]
    keep = np.abs(cos) >= config.refine_align
    if keep.sum() < 1:
        return np.eye(3)
    X_p = Np[best[keep]] * np.sign(cos[keep])[:, None]
    X_c = Nc[keep]
    if np.linalg.matrix_rank(X_c, tol=1e-6) < 2:          # one direction: rotate it onto its partner
        rot, _ = Rotation.align_vectors(X_p[:1], X_c[:1])
    else:
        rot, _ = Rotation.align_vectors(X_p, X_c)
    return rot.as_matrix()


def _front_panel(child: Primitive, normal: np.ndarray, contacts: ContactConfig, fitting: FittingConfig) -> bool:
    """Is ``child`` a panel (thinnest extent below ``panel_ratio`` × the next) whose thin axis is along
    the contact plane's unit ``normal`` (3,) (|cos| >= ``theta_a``)?"""
    order = np.argsort(child.size)
    if child.size[order[0]] >= fitting.panel_ratio * child.size[order[1]]:
        return False
    thin = child.T_world_part[:3, int(order[0])]
    return bool(abs(float(thin @ normal)) >= contacts.theta_a)


def _rotate_about(T: np.ndarray, R: np.ndarray, centre: np.ndarray) -> np.ndarray:
    M = np.eye(4)
    M[:3, :3] = R
    M[:3, 3] = centre - R @ centre
    return M @ T


def refine_parts(prims: dict[int, Primitive], tree: PartTree,
                 config: RefinementConfig, contacts: ContactConfig, fitting: FittingConfig) -> dict[int, Primitive]:
    """Alg. 1 over one object's tree: {part_id: primitive} -> refined {part_id: primitive}."""
    out = dict(prims)
    for c in tree.top_down():
        p = tree.parent[c]
        sub = tree.subtree(c)
        R = refine_rotation(out[p], out[c], config, contacts)
        angle = Rotation.from_matrix(R).magnitude()
        if angle > config.refine_max_angle:
            log.info("part %d: refinement rotation %.1f deg rejected", c, np.degrees(angle))
            R = np.eye(3)
        if angle > 1e-9 and not np.allclose(R, np.eye(3)):
            M = _rotate_about(np.eye(4), R, out[c].center)
            for v in sub:
                out[v] = out[v].transformed(M)
        if tree.edges.get(c) is None:
            continue
        # translate onto the contact plane only when one plane pair is clearly the contact
        pairs = contact_pairs(out[p].planes(contacts.cylinder_side_faces),
                              out[c].planes(contacts.cylinder_side_faces), contacts)
        if not pairs:
            continue
        pairs.sort(key=lambda t: (-round(t[2], 3), t[4]))     # equal Cont: the closer pair
        best = pairs[0]
        rivals = [t for t in pairs[1:] if t[2] >= best[2] - config.snap_ambiguity
                  and abs(abs(float(out[p].planes(contacts.cylinder_side_faces)[t[0]].normal
                                    @ out[p].planes(contacts.cylinder_side_faces)[best[0]].normal)) - 1) > 1e-3]
        if rivals:
            log.debug("part %d: contact planes ambiguous, no translation", c)
            continue
        pp = out[p].planes(contacts.cylinder_side_faces)[best[0]]
        cp = out[c].planes(contacts.cylinder_side_faces)[best[1]]
        if not config.snap_front_panels and _front_panel(out[c], pp.normal, contacts, fitting):
            log.debug("part %d: a front panel keeps its measured face (no snap)", c)
            continue
        signed = float(np.mean(cp.polygon @ pp.normal + pp.d))
        if abs(signed) <= contacts.theta_d:
            M = np.eye(4)
            M[:3, 3] = -signed * pp.normal
            for v in sub:
                out[v] = out[v].transformed(M)
    return out


def interpenetration(parent: Primitive, child: Primitive) -> float:
    """Volume (m^3) shared by two primitives (exact boolean of their meshes, manifold3d)."""
    import trimesh

    try:
        inter = trimesh.boolean.intersection([parent.to_trimesh(), child.to_trimesh()], engine="manifold")
    except Exception:  # empty intersection may come back as an error from some engines
        return 0.0
    return float(abs(inter.volume)) if inter is not None and len(inter.faces) else 0.0
