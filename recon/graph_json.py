"""``graph.json``: the scene contact graph, and reading it back into the same :class:`Reconstruction`.

Layout (format ``partscene.graph/1``; lengths in metres, angles in radians, world frame)::

    {"format": "partscene.graph/1", "seed": 0, "config": {ReconConfig field: value},
     "objects": [{"id", "category", "name", "T_world_object", "size", "supported_by", "proximal",
                  "root_part_id", "isolated_part_ids",
                  "parts": [{"part_id", "label", "link", "type", "size", "T_world_part", "score",
                             "candidate_scores", "n_points",
                             "surface_planes": [{"normal", "d", "polygon"}],
                             "shapes": [{"type", "size", "T_world_part"}]}],
                  "joints": [{"name", "type", "parent_part_id", "child_part_id", "axis", "origin",
                              "lower", "upper", "contact_score", "handle_part_id",
                              "uncertainty": {"axis_deg", "origin_m", "upper", "samples", "method",
                                              "side_undecided"}}],
                  "contacts": [{"parent_part_id", "child_part_id", "score", "align", "dist",
                                "parent_plane", "child_plane"}],
                  "scored_contacts": [{"part_ids": [a, b], "score"}]}],
     "supports": [[object id, supporter id | null]], "proximal": [[a, b]],
     "walls": [{"name": "wall0", "size": [thickness, length, height], "T_world_wall": 4x4, "n_points"}],
     "floor": {"height_m", "tilt_deg", "normal", "n_points"}, "T_world_scan": 4x4,
     "warnings": [...], "timings": {...}}

The world frame is the scan's, or the scan levelled on its floor when built with ``level_floor``
(``T_world_scan`` maps the scan's frame into it; identity otherwise). ``floor`` is the floor plane in
the world frame (:class:`recon.leveling.Floor`): ``normal`` (unit, up into the room), ``height_m`` its
offset from the origin along the normal (for a level floor, its z), ``tilt_deg`` the angle between the
normal and +z, ``n_points`` the background points it was fitted to (0: no floor points; z = 0 assumed).

A part's ``size`` follows :mod:`recon.primitive` (box extents; cylinder (2r, 2r, length along local
z); sphere (2r, 2r, 2r)). A part's ``shapes`` are its articulated-template shapes (a drawer's front and box, a body's carcass
panels; empty = the fitted primitive alone). A root joint has ``parent_part_id`` null (its parent is the world link). A movable joint's ``uncertainty``
(recon/joint_uncertainty.py) gives the RMS spread of its axis (deg), of its axis position perpendicular to
the axis (m) and of its upper limit over ``samples`` resamplings, and ``side_undecided`` (true: a handleless
door whose hinge side the scan does not decide, hinged at one edge with the other as likely; false for
drawers); absent on fixed joints. ``contacts`` are the Eq. 1 contacts; ``scored_contacts`` the object's
contact graph as scored for the kinematic mAP (:func:`recon.part_tree.contact_scores`: undirected, the Eq. 1
contacts weighted by the templates' priors, the part tree's edges and the designed neighbours Eq. 1
missed); reading the file back recomputes them.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from recon.config import ReconConfig
from recon.errors import ScanError
from recon.leveling import Floor
from recon.model import (ContactEdge, JointEstimate, JointUncertainty, ObjectReconstruction, PartFit,
                         Reconstruction, SceneGraph)
from recon.part_tree import contact_scores
from recon.primitive import Primitive, SurfacePlane
from recon.walls import Wall

__all__ = ["FORMAT", "graph_dict", "graph_json_string", "read_graph_json", "reconstruction_from_dict"]

FORMAT = "partscene.graph/1"


def _list(a) -> list:
    return np.asarray(a, dtype=np.float64).tolist()


def graph_dict(rec: Reconstruction) -> dict:
    """The graph.json document of ``rec`` as plain Python data."""
    prox: dict[int, list[int]] = {o.id: [] for o in rec.objects}
    for a, b in rec.graph.proximal:
        prox.setdefault(a, []).append(b)
        prox.setdefault(b, []).append(a)
    objects = []
    for o in rec.objects:
        objects.append({
            "id": o.id, "category": o.category, "name": o.name,
            "T_world_object": _list(o.T_world_object), "size": _list(o.size),
            "supported_by": o.supported_by, "proximal": sorted(prox.get(o.id, [])),
            "root_part_id": o.root_part_id, "isolated_part_ids": list(o.isolated_part_ids),
            "parts": [{
                "part_id": p.part_id, "label": p.label, "link": p.link,
                "type": p.primitive.kind.value, "size": _list(p.primitive.size),
                "T_world_part": _list(p.primitive.T_world_part),
                "score": p.score, "candidate_scores": dict(p.candidate_scores), "n_points": p.n_points,
                "surface_planes": [{"normal": _list(s.normal), "d": float(s.d), "polygon": _list(s.polygon)}
                                   for s in p.planes],
                "shapes": [{"type": q.kind.value, "size": _list(q.size), "T_world_part": _list(q.T_world_part)}
                           for q in p.shapes],
            } for p in o.parts],
            "joints": [{
                "name": j.name, "type": j.type.value, "parent_part_id": j.parent_part_id,
                "child_part_id": j.child_part_id, "axis": _list(j.axis), "origin": _list(j.origin),
                "lower": float(j.lower), "upper": float(j.upper), "contact_score": float(j.contact_score),
                "handle_part_id": j.handle_part_id,
                **({} if j.uncertainty is None else {"uncertainty": j.uncertainty.as_dict()}),
            } for j in o.joints],
            "contacts": [dataclasses.asdict(e) for e in o.contacts],
            "scored_contacts": [{"part_ids": [a, b], "score": float(v)}
                                for (a, b), v in sorted(contact_scores(o, rec.config.tree).items())],
        })
    return {
        "format": FORMAT, "seed": rec.seed, "config": rec.config.flat(),
        "objects": objects,
        "supports": [[a, b] for a, b in rec.graph.supports],
        "proximal": [[a, b] for a, b in rec.graph.proximal],
        "walls": [{"name": w.name, "size": _list(w.size), "T_world_wall": _list(w.T_world_wall),
                   "n_points": w.n_points} for w in rec.walls],
        **({} if rec.floor is None else {"floor": rec.floor.as_dict()}),
        "T_world_scan": _list(rec.T_world_scan),
        "warnings": list(rec.warnings), "timings": dict(rec.timings),
    }


def graph_json_string(rec: Reconstruction) -> str:
    return json.dumps(graph_dict(rec), indent=1)


def reconstruction_from_dict(doc: dict, source: str = "<dict>") -> Reconstruction:
    """Inverse of :func:`graph_dict`. Raises ScanError naming ``source`` on a malformed document."""
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise ScanError(f"{source}: not a {FORMAT} document (format={doc.get('format') if isinstance(doc, dict) else None!r})")
    try:
        config = ReconConfig.from_flat(doc.get("config", {}), ignore_unknown=True)
        objects = []
        for o in doc["objects"]:
            parts = tuple(PartFit(
                p["part_id"], p["label"], p["link"], Primitive(p["type"], p["size"], p["T_world_part"]),
                float(p["score"]), dict(p["candidate_scores"]), int(p["n_points"]),
                tuple(SurfacePlane(np.asarray(s["normal"], float), float(s["d"]), np.asarray(s["polygon"], float))
                      for s in p["surface_planes"]),
                tuple(Primitive(q["type"], q["size"], q["T_world_part"]) for q in p.get("shapes", ())))
                for p in o["parts"])
            joints = tuple(JointEstimate(j["name"], j["type"], j["parent_part_id"], j["child_part_id"],
                                         j["axis"], j["origin"], j["lower"], j["upper"], j["contact_score"],
                                         j.get("handle_part_id"),
                                         JointUncertainty.from_dict(j["uncertainty"]) if j.get("uncertainty")
                                         else None) for j in o["joints"])
            contacts = tuple(ContactEdge(**e) for e in o["contacts"])
            objects.append(ObjectReconstruction(
                o["id"], o["category"], o["name"], o["root_part_id"], parts, contacts, joints,
                tuple(o["isolated_part_ids"]), np.asarray(o["T_world_object"], float),
                np.asarray(o["size"], float), o["supported_by"]))
        graph = SceneGraph(tuple((a, b) for a, b in doc["supports"]), tuple((a, b) for a, b in doc["proximal"]))
        walls = tuple(Wall(w["name"], w["size"], w["T_world_wall"], int(w.get("n_points", 0)))
                      for w in doc.get("walls", ()))
        floor = Floor.from_dict(doc["floor"]) if doc.get("floor") else None
        T_world_scan = np.asarray(doc.get("T_world_scan", np.eye(4)), dtype=np.float64).reshape(4, 4)
    except (KeyError, TypeError, ValueError) as exc:
        raise ScanError(f"{source}: malformed {FORMAT} document ({type(exc).__name__}: {exc})") from exc
    return Reconstruction(tuple(objects), graph, tuple(doc.get("warnings", ())), config,
                          int(doc.get("seed", 0)), dict(doc.get("timings", {})), walls, floor, T_world_scan)


def read_graph_json(path: str | Path) -> Reconstruction:
    """Read a graph.json written by :meth:`Reconstruction.write` back into a Reconstruction."""
    path = Path(path)
    try:
        doc = json.loads(path.read_text())
    except FileNotFoundError:
        raise ScanError(f"{path}: graph file not found") from None
    except json.JSONDecodeError as exc:
        raise ScanError(f"{path}: not valid JSON ({exc})") from exc
    return reconstruction_from_dict(doc, str(path))
