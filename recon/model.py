"""The reconstruction's artifacts: frozen dataclasses of float64 arrays, one per stage's product.

    PartFit              one part replaced by its best primitive (Eq. 3) with its planes Π
    ContactEdge          a directed parent -> child contact that satisfies Eq. 1, with its score
    JointEstimate        one joint of the part tree (fixed / prismatic / revolute), world frame
    ObjectReconstruction one object: parts, contact edges, joints (the part tree), pose, support
    SceneGraph           inter-object supporting and proximal relations
    Reconstruction       the whole scene (written by :func:`recon.output.write_reconstruction`)

Frames: ``T_a_b`` is the (4, 4) pose of b in a; everything here is in the world frame, metres: the scan's
frame (z up, the floor at ``Reconstruction.floor``, which may be a few cm off z = 0 and tilted), or with
``level_floor`` the levelled one (the floor z = 0). "Up" below means the floor's normal.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from recon.config import ReconConfig
from recon.hinge_depth import HingeDepth
from recon.primitive import Primitive, SurfacePlane
from scenes.description import JointType

__all__ = ["JointType", "PartFit", "ContactEdge", "JointUncertainty", "JointEstimate", "ObjectReconstruction",
           "SceneGraph", "Reconstruction"]


@dataclass(frozen=True, eq=False)
class PartFit:
    """One part replaced by its best-aligned primitive (Eq. 3).

    part_id, label : from labels.json; link : URDF link name (scenes.description.link_name)
    primitive : the winning primitive (type, size, T_world_part)
    score : float, metres, the Eq. 3 score of the winner (lower is better)
    candidate_scores : {candidate name: score} of every candidate tried
    n_points : number of scan points of the part
    planes : the surface planes Π of the primitive (world frame)
    shapes : the part's articulated-template shapes (a drawer's front + box, a body's carcass panels;
        part_shapes.py), world frame; empty = the primitive alone (see :attr:`solids`)
    """

    part_id: int
    label: str
    link: str
    primitive: Primitive
    score: float
    candidate_scores: dict
    n_points: int
    planes: tuple[SurfacePlane, ...]
    shapes: tuple[Primitive, ...] = ()

    @property
    def solids(self) -> tuple[Primitive, ...]:
        """The part's geometry as URDF shapes: its template shapes, else its fitted primitive."""
        return tuple(self.shapes) or (self.primitive,)

    def transformed(self, T_new_world: np.ndarray) -> "PartFit":
        """The part moved rigidly by ``T_new_world`` (4, 4): primitive, planes and shapes."""
        return replace(self, primitive=self.primitive.transformed(T_new_world),
                       planes=tuple(q.transformed(T_new_world) for q in self.planes),
                       shapes=tuple(q.transformed(T_new_world) for q in self.shapes))

    def isclose(self, other: "PartFit", atol: float = 1e-6) -> bool:
        return (self.part_id == other.part_id and self.label == other.label and self.link == other.link
                and self.primitive.isclose(other.primitive, atol) and len(self.solids) == len(other.solids)
                and all(a.isclose(b, atol) for a, b in zip(self.solids, other.solids)))


@dataclass(frozen=True)
class ContactEdge:
    """A directed contact parent -> child satisfying Eq. 1 for at least one plane pair.

    score : max over plane pairs of Cont (contact area ratio, 0..1); the Eq. 4 edge weight
    align : |n_p · n_c| of the best pair; dist : its Dist (m)
    parent_plane, child_plane : indices into the parts' ``planes`` of the best pair
    """

    parent_part_id: int
    child_part_id: int
    score: float
    align: float
    dist: float
    parent_plane: int
    child_plane: int


@dataclass(frozen=True)
class JointUncertainty:
    """How sure the reconstruction is of one movable joint (recon/joint_uncertainty.py).

    axis_deg : RMS angle (degrees) between the axis re-estimated from resampled data and the estimate
    origin_m : RMS distance (m) of the re-estimated axis point from the estimated axis line,
        perpendicular to the axis (for a drawer: where its front is, across its travel); for a door, with what
        the scan leaves undecided across and behind it in quadrature (recon/joint_uncertainty.py)
    upper : RMS deviation of the re-estimated upper limit (m for prismatic, rad for revolute)
    samples : number of resamplings they were measured over; method : how (e.g. "bootstrap")
    side_undecided : a door's hinge side is a guess: it has no handle and its two edges lie as near its
        body's edges, so the scan gives no reason to hinge it at one edge rather than the other (the other
        edge is as likely: a robust certificate samples both)
    """

    axis_deg: float
    origin_m: float
    upper: float
    samples: int
    method: str
    side_undecided: bool = False

    def as_dict(self) -> dict:
        return {"axis_deg": float(self.axis_deg), "origin_m": float(self.origin_m), "upper": float(self.upper),
                "samples": int(self.samples), "method": str(self.method), "side_undecided": bool(self.side_undecided)}

    @classmethod
    def from_dict(cls, d: dict) -> "JointUncertainty":
        return cls(float(d["axis_deg"]), float(d["origin_m"]), float(d["upper"]), int(d["samples"]),
                   str(d["method"]), bool(d.get("side_undecided", False)))


@dataclass(frozen=True, eq=False)
class JointEstimate:
    """A joint of the part tree, in the world frame at the scanned (closed) state.

    name : URDF joint name (scenes.description.joint_name of the child)
    type : JointType
    parent_part_id : None for the object's root (its parent is the ``world`` link)
    axis : (3,) unit, world frame; a positive joint value opens (zeros for fixed joints)
    origin : (3,) a point on the axis, world frame, metres (the hinge line for doors)
    lower, upper : metres or radians; lower = 0 is the scanned state
    contact_score : Cont of the tree edge (0 for the root and for parts that touch nothing)
    handle_part_id : the handle moved by this joint, or None
    uncertainty : JointUncertainty of a movable joint, None when not estimated (fixed joints)
    hinge_depth : a door's :class:`recon.hinge_depth.HingeDepth` (where its hinge lies across its thickness)
        and hinge_side_undecided : its hinge side is a guess (no handle, both edges as near its body's edges),
        as the joint stage found them from all the scan points; for :mod:`recon.joint_uncertainty`, not
        written to graph.json (what they leave open is in ``uncertainty``)
    """

    name: str
    type: JointType
    parent_part_id: int | None
    child_part_id: int
    axis: np.ndarray
    origin: np.ndarray
    lower: float = 0.0
    upper: float = 0.0
    contact_score: float = 0.0
    handle_part_id: int | None = None
    uncertainty: JointUncertainty | None = None
    hinge_depth: HingeDepth | None = None
    hinge_side_undecided: bool = False

    def __post_init__(self):
        object.__setattr__(self, "type", JointType(self.type))
        object.__setattr__(self, "axis", np.asarray(self.axis, dtype=np.float64).reshape(3))
        object.__setattr__(self, "origin", np.asarray(self.origin, dtype=np.float64).reshape(3))

    def transformed(self, T_new_world: np.ndarray) -> "JointEstimate":
        """The joint moved rigidly by ``T_new_world`` (4, 4): axis rotated, origin moved."""
        R = T_new_world[:3, :3]
        return replace(self, axis=R @ self.axis, origin=R @ self.origin + T_new_world[:3, 3])

    def isclose(self, other: "JointEstimate", atol: float = 1e-6) -> bool:
        return (self.name == other.name and self.type is other.type
                and self.parent_part_id == other.parent_part_id
                and self.child_part_id == other.child_part_id
                and np.allclose(self.axis, other.axis, atol=atol)
                and np.allclose(self.origin, other.origin, atol=atol)
                and abs(self.lower - other.lower) <= atol and abs(self.upper - other.upper) <= atol)


@dataclass(frozen=True, eq=False)
class ObjectReconstruction:
    """One object rebuilt from its parts.

    id, category, name : from labels.json; name = scenes.description.object_name
    root_part_id : the base part (fixed to the world)
    parts : PartFit per reconstructed part (refined poses)
    contacts : every directed edge satisfying Eq. 1 (the graph the tree was chosen from)
    joints : one per part: the root's fixed joint to the world, then one per tree edge
    isolated_part_ids : parts that touched nothing; fixed to the root and reported
    T_world_object : (4, 4) object frame: bottom centre, x = front normal, z = the floor's normal
    size : (3,) extent in the object frame, metres
    supported_by : id of the supporting object, or None for the floor
    """

    id: int
    category: str
    name: str
    root_part_id: int
    parts: tuple[PartFit, ...]
    contacts: tuple[ContactEdge, ...]
    joints: tuple[JointEstimate, ...]
    isolated_part_ids: tuple[int, ...]
    T_world_object: np.ndarray
    size: np.ndarray
    supported_by: int | None = None

    def part(self, part_id: int) -> PartFit:
        for p in self.parts:
            if p.part_id == part_id:
                return p
        raise KeyError(f"object {self.name}: no part {part_id}")

    def transformed(self, T_new_world: np.ndarray) -> "ObjectReconstruction":
        """The object moved rigidly by ``T_new_world`` (4, 4): parts, joints and frame."""
        return replace(self, parts=tuple(p.transformed(T_new_world) for p in self.parts),
                       joints=tuple(j.transformed(T_new_world) for j in self.joints),
                       T_world_object=T_new_world @ self.T_world_object)

    def primitives(self) -> dict[int, Primitive]:
        """{part_id: fitted primitive} (for metrics: Chamfer / IoU)."""
        return {p.part_id: p.primitive for p in self.parts}

    def tree_edges(self) -> tuple[tuple[int, int], ...]:
        """(parent_part_id, child_part_id) of every non-root joint (the estimated part tree)."""
        return tuple((j.parent_part_id, j.child_part_id) for j in self.joints
                     if j.parent_part_id is not None)


@dataclass(frozen=True)
class SceneGraph:
    """Inter-object relations of the scene contact graph.

    supports : ((child object id, supporter object id or None = floor), ...)
    proximal : ((object id a, object id b), ...) with a < b
    """

    supports: tuple[tuple[int, int | None], ...] = ()
    proximal: tuple[tuple[int, int], ...] = ()


@dataclass(frozen=True, eq=False)
class Reconstruction:
    """The reconstructed scene (the return value of :func:`recon.reconstruct`).

    objects : ObjectReconstruction per labelled object, in labels.json order
    graph : the scene-level contact graph
    warnings : human-readable problems met on the way (each names its object / part)
    config : the ReconConfig used; seed : the seed used
    timings : {stage: seconds}
    walls : :class:`recon.walls.Wall` fitted to the background (links ``wall0``, ``wall1``, ...)
    floor : :class:`recon.leveling.Floor`, the floor plane in the output's frame (the scan's, or the
        levelled one with ``level_floor``); None when unknown (a graph.json written before it existed)
    T_world_scan : (4, 4) the output's frame from the scan's: identity, or the levelling rotation and shift
    """

    objects: tuple[ObjectReconstruction, ...]
    graph: SceneGraph
    warnings: tuple[str, ...]
    config: ReconConfig
    seed: int = 0
    timings: dict = field(default_factory=dict)
    walls: tuple = ()
    floor: object = None
    T_world_scan: np.ndarray = field(default_factory=lambda: np.eye(4))

    def object(self, object_id: int) -> ObjectReconstruction:
        for o in self.objects:
            if o.id == object_id:
                return o
        raise KeyError(f"no object {object_id} in the reconstruction")

    def joints(self) -> tuple[JointEstimate, ...]:
        return tuple(j for o in self.objects for j in o.joints)
