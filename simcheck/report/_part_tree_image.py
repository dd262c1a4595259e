"""Each object's part tree with its joints, drawn like Fig. 3(c) of the paper (networkx + matplotlib).

Nodes are parts (labelled ``label id``), directed edges go parent -> child and carry the joint type
and, for an estimate, the contact score that chose the edge.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import networkx as nx
import numpy as np

from ._errors import ArtifactError
from ._figure import colour_of_label, new_figure, png_from_figure

__all__ = ["PartTree", "trees_from_scene_json", "png_of_part_trees"]

#: Edge colour per joint type.
_JOINT_COLOURS = {"fixed": "#555555", "prismatic": "#1f77b4", "revolute": "#d62728"}
#: Edge label per joint type (the report's legend spells them out).
_JOINT_LETTERS = {"fixed": "F", "prismatic": "P", "revolute": "R"}


@dataclass(frozen=True)
class PartTree:
    """Part tree of one object: ``name`` (e.g. "cabinet3"), ``category``, ``graph`` a networkx DiGraph
    (nodes: part ids with attr ``label``; edges parent -> child with ``type``, ``joint``, ``score``)."""

    name: str
    category: str
    graph: nx.DiGraph
    other_contacts: tuple[tuple[int, int, float | None], ...] = ()
    """Contacts between parts that are not tree edges: ``(part a, part b, score or None)``."""


def trees_from_scene_json(doc: Mapping, source: str) -> list[PartTree]:
    """Part trees of every object in a ``graph.json`` or ``truth.json`` dict.

    Reads ``objects[].parts[]`` (``id`` or ``part_id``, ``label``) and ``objects[].joints[]``
    (``parent_part_id``, ``child_part_id``, ``type``, ``name``, optional ``contact_score``); a joint whose
    parent is null (the object's root hanging from the world) adds no edge. ``objects[].contacts`` --
    graph.json's scored Eq. 1 contacts (``parent_part_id``, ``child_part_id``, ``score``) or truth.json's
    ``[a, b]`` pairs -- that are not tree edges become :attr:`PartTree.other_contacts`.
    """
    objects = doc.get("objects")
    if not isinstance(objects, list):
        raise ArtifactError(f"{source}: expected a list under 'objects'")
    trees = []
    for obj in objects:
        name = str(obj.get("name") or f"{obj.get('category', 'object')}{obj.get('id', '')}")
        g = nx.DiGraph()
        for part in obj.get("parts", []):
            pid = part.get("part_id", part.get("id"))
            if pid is None:
                raise ArtifactError(f"{source}: object {name}: a part has no id/part_id")
            g.add_node(int(pid), label=str(part.get("label", "")))
        for joint in obj.get("joints", []):
            parent, child = joint.get("parent_part_id"), joint.get("child_part_id")
            if parent is None or child is None:
                continue
            for pid in (parent, child):
                if int(pid) not in g:
                    raise ArtifactError(f"{source}: object {name}: joint {joint.get('name')!r} "
                                        f"names part {pid}, which the object does not have")
            score = joint.get("contact_score")
            g.add_edge(int(parent), int(child), type=str(joint.get("type", "?")),
                       joint=str(joint.get("name", "")), score=None if score is None else float(score))
        others = _other_contacts(obj.get("contacts", []), g)
        trees.append(PartTree(name, str(obj.get("category", "")), g, others))
    return trees


def _other_contacts(contacts, g: nx.DiGraph) -> tuple[tuple[int, int, float | None], ...]:
    """Undirected contacts (best score per pair) between parts of ``g`` that are not edges of ``g``."""
    best: dict[frozenset, float | None] = {}
    for c in contacts:
        if isinstance(c, Mapping):
            a, b, score = c.get("parent_part_id"), c.get("child_part_id"), c.get("score")
        else:
            (a, b), score = c, None
        if a is None or b is None or int(a) not in g or int(b) not in g:
            continue
        if g.has_edge(int(a), int(b)) or g.has_edge(int(b), int(a)):
            continue
        key = frozenset((int(a), int(b)))
        old = best.get(key)
        best[key] = score if old is None else (old if score is None else max(old, float(score)))
    return tuple((min(k), max(k), None if s is None else float(s)) for k, s in sorted(best.items(), key=str))


def _layout(g: nx.DiGraph) -> dict[int, np.ndarray]:
    """Layered top-down layout: roots on top, each child one layer below its parent."""
    depth: dict[int, int] = {}
    for root in [n for n in g.nodes if g.in_degree(n) == 0]:
        for node, d in nx.single_source_shortest_path_length(g, root).items():
            depth[node] = min(depth.get(node, d), d)
    for node in g.nodes:
        depth.setdefault(node, 0)
    nx.set_node_attributes(g, depth, "layer")
    pos = nx.multipartite_layout(g, subset_key="layer", align="horizontal")
    return {n: np.array([p[0], -p[1]]) for n, p in pos.items()}


def _widest_layer(g: nx.DiGraph) -> int:
    """Most parts at one depth of the tree."""
    if g.number_of_nodes() == 0:
        return 1
    roots = [n for n in g.nodes if g.in_degree(n) == 0] or [next(iter(g.nodes))]
    counts: dict[int, int] = {}
    for root in roots:
        for _, d in nx.single_source_shortest_path_length(g, root).items():
            counts[d] = counts.get(d, 0) + 1
    return max(counts.values())


#: Node and edge label size (points; 12.5 px at the figure's 90 dpi) and node area (points^2) that holds it.
_FONT_PT, _NODE_SIZE = 10, 1700


def _draw_tree(ax, tree: PartTree, title: str) -> None:
    g = tree.graph
    if g.number_of_nodes() == 0:
        ax.text(0.5, 0.5, "no parts", ha="center", va="center")
        ax.set_axis_off()
        return
    pos = _layout(g)
    colours = [colour_of_label(g.nodes[n]["label"]) for n in g.nodes]
    if tree.other_contacts:  # the contacts the tree did not keep, as in the paper's Fig. 3(b)
        und = nx.Graph()
        und.add_nodes_from(g.nodes)
        und.add_edges_from((a, b) for a, b, _ in tree.other_contacts)
        nx.draw_networkx_edges(und, pos, ax=ax, edge_color="#c8c8c8", style="dotted", width=0.9)
    nx.draw_networkx_nodes(g, pos, ax=ax, node_color=colours, node_size=_NODE_SIZE, edgecolors="black")
    for n in g.nodes:  # white text on dark nodes
        dark = sum(colour_of_label(g.nodes[n]["label"])) < 1.2
        nx.draw_networkx_labels(g, pos, ax=ax, font_size=_FONT_PT, font_color="white" if dark else "black",
                                labels={n: f"{g.nodes[n]['label']}\n{n}"})
    for u, v, data in g.edges(data=True):
        nx.draw_networkx_edges(g, pos, edgelist=[(u, v)], ax=ax, arrows=True, arrowsize=12,
                               edge_color=_JOINT_COLOURS.get(data["type"], "#9467bd"), width=2.0,
                               node_size=_NODE_SIZE)
    edge_labels = {(u, v): _JOINT_LETTERS.get(d["type"], d["type"])
                   + ("" if d["score"] is None else f" {d['score']:.2f}") for u, v, d in g.edges(data=True)}
    nx.draw_networkx_edge_labels(g, pos, edge_labels=edge_labels, ax=ax, font_size=_FONT_PT, rotate=False, label_pos=0.7,
                                 bbox={"boxstyle": "round", "fc": "white", "ec": "none", "alpha": 0.8})
    ax.set_title(title, fontsize=_FONT_PT + 1)
    ax.margins(0.2)
    ax.set_axis_off()


def png_of_part_trees(panels: Sequence[tuple[str, PartTree]], panel_in: float = 3.6) -> bytes:
    """One PNG with a tree per ``(title, tree)`` side by side (e.g. estimate beside truth); a panel is
    wider when a layer of its tree has many parts."""
    widest = max([_widest_layer(t.graph) for _, t in panels] + [1])
    fig = new_figure(max(panel_in, 1.5 * widest) * len(panels), panel_in + 0.6)
    for i, (title, tree) in enumerate(panels):
        _draw_tree(fig.add_subplot(1, len(panels), i + 1), tree, title)
    return png_from_figure(fig)
