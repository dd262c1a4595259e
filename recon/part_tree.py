"""The object's part tree (Eq. 4): maximum spanning arborescence of the contact graph (Edmonds).

Nodes are parts, edges the Eq. 1 contacts weighted by their contact score. The template prior scales
an edge whose parent label the child's template does not expect by ``foreign_parent_penalty``. The
base part (``ROOT_LABELS``, else the largest part) is the root: its in-edges are removed. Parts that
touch nothing reachable from the root get a ``fallback_edge_weight`` edge from the root, so the tree
always spans every part; those parts are returned so the caller can report them.
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx
import numpy as np

from recon.config import ContactConfig, TreeConfig
from recon.model import ContactEdge, ObjectReconstruction
from recon.primitive import Primitive
from recon.templates import ROOT_LABELS, designed_neighbours, expected_contact, template_for

__all__ = ["PartTree", "UNCONTACTED_TREE_EDGE_SCORE", "choose_root", "contact_scores", "part_distances", "part_tree"]

UNCONTACTED_TREE_EDGE_SCORE = 0.05
"""Least score given (for the mAP ranking) to a tree edge the part tree made without an Eq. 1 contact
(one to a parent its template expects scores its near-parent weight when higher: :func:`contact_scores`)."""


@dataclass(frozen=True)
class PartTree:
    """root : part id; parent : {child id: parent id}; edges : {child id: the chosen ContactEdge or
    None for a fallback attachment}; isolated : part ids attached by a fallback edge."""

    root: int
    parent: dict
    edges: dict
    isolated: tuple[int, ...]

    def children(self, part_id: int) -> list[int]:
        return sorted(c for c, p in self.parent.items() if p == part_id)

    def top_down(self) -> list[int]:
        """Non-root part ids in breadth-first order from the root (Alg. 1's queue order)."""
        order, queue = [], list(self.children(self.root))
        while queue:
            c = queue.pop(0)
            order.append(c)
            queue.extend(self.children(c))
        return order

    def subtree(self, part_id: int) -> list[int]:
        out, stack = [], [part_id]
        while stack:
            v = stack.pop()
            out.append(v)
            stack.extend(self.children(v))
        return out


def choose_root(labels: dict[int, str], volumes: dict[int, float]) -> int:
    """The base part: the first of ROOT_LABELS present (largest if several), else the largest part."""
    for root_label in ROOT_LABELS:
        ids = [i for i, lab in labels.items() if lab == root_label]
        if ids:
            return max(ids, key=lambda i: (volumes[i], -i))
    return max(labels, key=lambda i: (volumes[i], -i))


def part_distances(prims: dict[int, Primitive]) -> dict[tuple[int, int], float]:
    """{(a, b): distance (m) from part b's corners and centre to part a's surface, min over them}."""
    out = {}
    for a, pa in prims.items():
        for b, pb in prims.items():
            if a != b:
                q = np.vstack([pb.corners(), pb.center[None]])
                out[(a, b)] = float(pa.surface_distance(q).min())
    return out


def part_tree(category: str, labels: dict[int, str], volumes: dict[int, float],
              contacts: tuple[ContactEdge, ...], config: TreeConfig, contact_config: ContactConfig,
              distances: dict[tuple[int, int], float] | None = None) -> PartTree:
    """Solve Eq. 4 for one object. ``labels``/``volumes`` : {part_id: label / m^3}.

    ``distances`` {(a, b): metres between parts}: a part gets an edge from the nearest part its template
    expects as parent — weighted ``near_parent_weight`` (fading to 0 at ``near_parent_distance``) when that
    part is close, else a fallback weight, or its Eq. 1 contact's weight when higher (a weak contact never
    counts less than none) — so a handle hangs from the nearest drawer or door rather than the root or a
    foreign part.
    """
    root = choose_root(labels, volumes)
    g = nx.DiGraph()
    g.add_nodes_from(labels)
    by_pair = {}
    for e in contacts:
        if e.child_part_id == root:
            continue
        tpl = template_for(category, labels[e.child_part_id])
        prior = 1.0 if tpl is None or labels[e.parent_part_id] in tpl.parents else config.foreign_parent_penalty
        w = e.score * prior * (1.0 - 0.01 * e.dist / max(contact_config.theta_d, 1e-9))
        g.add_edge(e.parent_part_id, e.child_part_id, weight=w)
        by_pair[(e.parent_part_id, e.child_part_id)] = e
    for v in labels:
        if v != root and not g.has_edge(root, v):
            g.add_edge(root, v, weight=config.fallback_edge_weight)
        tpl = template_for(category, labels[v])
        if v != root and distances and tpl is not None:
            # the root's fallback edge is no contact: the root may still be the near parent
            near = [(distances.get((u, v), np.inf), u) for u in labels if u != v and labels[u] in tpl.parents]
            if near:
                d, u = min(near)
                w = g.edges[u, v]["weight"] if g.has_edge(u, v) else 0.0
                if d < config.near_parent_distance:
                    # the template's parent is right there but Eq. 1 missed the contact or found a weak one
                    # (noise, a fit stretched by stray points): prefer it to a foreign parent, never to a
                    # stronger real contact with an expected parent; a weak contact never counts less than none
                    near_w = config.near_parent_weight * (1.0 - d / config.near_parent_distance)
                    g.add_edge(u, v, weight=max(w, near_w, 2 * config.fallback_edge_weight))
                elif np.isfinite(d) and (u, v) not in by_pair:
                    g.add_edge(u, v, weight=max(w, 2 * config.fallback_edge_weight))
    if len(labels) == 1:
        return PartTree(root, {}, {}, ())
    arb = nx.maximum_spanning_arborescence(g, attr="weight", preserve_attrs=True)
    parent, edges, isolated = {}, {}, []
    for p, c in arb.edges():
        parent[c] = p
        edges[c] = by_pair.get((p, c))
        if edges[c] is None:
            isolated.append(c)
    return PartTree(root, parent, edges, tuple(sorted(isolated)))


def contact_scores(obj: ObjectReconstruction, config: TreeConfig, weighted: bool = True
                   ) -> dict[tuple[int, int], float]:
    """{(min id, max id): score} of every estimated contact of ``obj`` (the scored edge list for the
    kinematic-structure mAP).

    The score of a pair is its best Eq. 1 Cont over both directions. ``weighted`` (default)
    multiplies it by the template prior ``config.foreign_parent_penalty`` when the templates expect no
    contact between the two labels (drawer–drawer, body–handle, leg–headboard; a bed's
    headboard–mattress is expected, :func:`recon.templates.expected_contact`), and also lists the tree
    edges the part tree made without an Eq. 1 contact: one to a parent the template expects scores the
    near-parent weight of Eq. 4 at the parts' distance (``near_parent_weight`` fading to 0 at
    ``near_parent_distance``, the weight :func:`part_tree` gave it; distance from the child's corners
    and centre to the parent's surface, final primitives), at least ``UNCONTACTED_TREE_EDGE_SCORE``,
    which any other such edge scores; a tree edge to an expected parent with a weaker Eq. 1 contact scores that
    near-parent weight too (as in Eq. 4, a weak contact never counts less than none). A pair of designed
    neighbours (:func:`recon.templates.designed_neighbours`:
    a bed's mattress and headboard, both children of its frame, so never a tree edge) that Eq. 1 missed
    scores the same near-parent weight at their distance (the nearer of either's corners and centre to the
    other's surface): depth noise, label bleed at their boundary and 3.5 cm voxels leave a ScanNet-style
    mattress's hidden end 2-4 cm short of the headboard's face, beyond ``theta_d``.
    ``weighted=False``: raw Eq. 1 contacts only.
    """
    labels = {p.part_id: p.label for p in obj.parts}
    out: dict[tuple[int, int], float] = {}
    for e in obj.contacts:
        key = (min(e.parent_part_id, e.child_part_id), max(e.parent_part_id, e.child_part_id))
        out[key] = max(out.get(key, 0.0), e.score)
    if not weighted:
        return out
    for (a, b), s in out.items():
        if not expected_contact(obj.category, labels.get(a, ""), labels.get(b, "")):
            out[(a, b)] = s * config.foreign_parent_penalty
    prims = {p.part_id: p.primitive for p in obj.parts}

    def near(a: int, b: int) -> float:          # the near-parent weight of b beside a (0 from near_parent_distance)
        q = np.vstack([prims[b].corners(), prims[b].center[None]])
        d = float(prims[a].surface_distance(q).min())
        return config.near_parent_weight * (1.0 - d / config.near_parent_distance)

    for p, c in obj.tree_edges():
        key = (min(p, c), max(p, c))
        tpl = template_for(obj.category, labels.get(c, ""))
        expected = tpl is not None and labels.get(p) in tpl.parents and p in prims and c in prims
        if key in out:
            if expected:            # a weak contact with an expected parent counts no less than none (Eq. 4)
                out[key] = max(out[key], near(p, c))
            continue
        out[key] = max(UNCONTACTED_TREE_EDGE_SCORE, near(p, c)) if expected else UNCONTACTED_TREE_EDGE_SCORE
    ids = sorted(i for i in prims if i in labels)
    for k, a in enumerate(ids):
        for b in ids[k + 1:]:
            if (a, b) not in out and designed_neighbours(obj.category, labels[a], labels[b]):
                score = max(near(a, b), near(b, a))
                if score > 0.0:
                    out[(a, b)] = score
    return out
