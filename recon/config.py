"""Every threshold of the reconstruction, named once, with its meaning and unit.

``ReconConfig`` is frozen; build a variant with ``dataclasses.replace(config, theta_d=0.01)``.
The symbols of the paper (Sections II–III of Zhang et al., part-level scene reconstruction) are kept:
``theta_a``, ``theta_d``, ``theta_c`` of Eq. 1.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ReconConfig"]


@dataclass(frozen=True)
class ReconConfig:
    """Thresholds and constants of every stage. Lengths in metres, angles in radians, mass in kg."""

    # --- input validation (scan.py) ---
    min_part_points: int = 20
    """A part with fewer points is skipped with a warning naming it (too few to fit a primitive)."""
    max_scene_extent: float = 60.0
    """A scan whose bounding box is larger than this (m) is refused: it is almost surely millimetres."""

    outlier_neighbors: int = 16
    """Statistical outlier removal (flying pixels): neighbours considered per point."""
    outlier_std_ratio: float = 3.0
    """... a point is an outlier when its mean neighbour distance exceeds the cloud's mean by this
    many standard deviations."""

    # --- primitive fitting, Eq. 3 (fitting.py) ---
    min_thickness: float = 0.01
    """Smallest box/cylinder extent (m): flat or collinear parts are thickened to this."""
    upright_tolerance: float = 0.15
    """Use the yaw-only (gravity-aligned) box when its volume is within (1 + this) of the free 3D one."""
    surface_samples: int = 600
    """Points sampled on each candidate primitive's surface, h(M) of Eq. 3."""
    fit_max_points: int = 3000
    """Part clouds larger than this are subsampled (seeded) for fitting."""
    icp_max_distance: float = 0.05
    """ICP correspondence radius (m)."""
    icp_iterations: int = 30
    """ICP iteration cap per candidate."""
    icp_min_improvement: float = 0.05
    """ICP's pose is kept only if it lowers the score by this fraction: on noisy scans ICP otherwise
    trades a few degrees of yaw for a fraction of a millimetre of score."""
    icp_candidate_ratio: float = 2.0
    """Only candidates whose unaligned score is within this factor of the best one are ICP-aligned."""
    noise_floor: float = 0.003
    """Depth noise (m, robust σ across a box's best-seen face) below which extents are not corrected."""
    edge_tail_fraction: float = 0.02
    """Fraction of a box's points at each end of its best-seen axis that decide whether that end is a
    noise tail (pulled in by the noise correction) or a rim of side faces (kept)."""
    rim_min_extent: float = 0.3
    """... and only for boxes this wide (m) along both other axes (table tops, bed frames), not handles."""
    min_face_points: int = 12
    """The opposite face needs this many points (and a fifth of the best face's) to join a noise estimate."""
    coverage_distance: float = 0.02
    """A primitive surface sample is 'seen' when a scan point lies within this distance (m)."""
    min_face_coverage: float = 0.25
    """A primitive face with a smaller seen fraction counts as unobserved and is left out of the
    Eq. 3 score (cameras miss faces against walls, floors and each other)."""
    point_term_weight: float = 1.0
    """Weight of the scan-to-primitive mean distance added to the Eq. 3 score, so that leaving
    unobserved faces out can never reward a primitive that does not explain the points."""
    small_part_points: int = 400
    """Parts with fewer points get only candidates aligned with their object's base part (their own
    bounding box is too noisy to orient them)."""
    box_preference: float = 0.1
    """A cylinder or sphere wins only if its score is lower than the best box's by this fraction."""
    candidates: tuple[str, ...] = ("box", "cylinder_x", "cylinder_y", "cylinder_z", "sphere")
    """Candidate templates M^c: box, a cylinder along each box axis, sphere."""

    completion_reach: float = 0.3
    """Legs are extended (completion.py) to a surface above / below them at most this far (m)."""

    # --- surface planes and contacts, Eq. 1 (planes.py, contacts.py) ---
    planes: str = "exact"
    """Where the planes Π of the contact test come from: "exact" primitive faces or "ransac" planes
    of the part's points (the paper's way); see planes.py."""
    ransac_planes: int = 6
    """At most this many RANSAC planes per part."""
    ransac_distance: float = 0.01
    """RANSAC inlier distance (m)."""
    ransac_min_fraction: float = 0.05
    """A RANSAC plane needs at least this fraction of the part's points."""
    cylinder_side_faces: int = 8
    """A cylinder's side is represented by this many tangent rectangles (planes of Π)."""
    theta_a: float = 0.97
    """Align: |n_p · n_c| must reach this (cos 14°); 1 is parallel."""
    theta_d: float = 0.025
    """Dist: mean distance (m) from the child polygon's vertices to the parent plane, at most this."""
    theta_c: float = 0.05
    """Cont: intersection area / child polygon area, at least this."""
    foreign_parent_penalty: float = 0.2
    """Template prior: an edge whose parent label is not one the child's template expects (a handle
    under a body instead of its drawer) has its contact score multiplied by this in the tree."""
    near_parent_distance: float = 0.1
    """A part with no Eq. 1 contact to a parent its template expects is hung from the nearest such
    part closer than this (m) (noisy scans break contacts by a few centimetres)."""
    near_parent_weight: float = 0.3
    """Edge weight of that attachment at zero distance (below the contact scores of real contacts)."""
    fallback_edge_weight: float = 1e-6
    """Weight of the root -> part edge given to parts that touch nothing (they are reported)."""

    # --- joints (joints.py) ---
    density: float = 600.0
    """kg/m^3 of every part (particle board); mass = density × primitive volume."""
    drawer_travel_fraction: float = 0.8
    """Drawer upper limit = this × the drawer box's depth, estimated as the body's depth along the
    drawer axis minus ``drawer_back_clearance`` (a closed drawer's box is hidden from the camera)."""
    panel_ratio: float = 0.3
    """A drawer/door whose thinnest extent is below this fraction of the next one is a front panel:
    its thin axis tells the opening's normal."""
    drawer_back_clearance: float = 0.025
    """Back panel plus the gap behind a drawer box (m)."""
    door_max_angle: float = 1.75
    """A door hinge's stop (rad, 100°; furniture hinges open 95–110°); the swept-collision test
    stops the door earlier when it would hit its body, a neighbour or a wall."""
    swing_step: float = 0.035
    """Angular / travel sampling step (rad or m/rad) of the collision sweep."""
    sweep_clearance: float = 0.015
    """The moving part is shrunk by this (m, each side) when swept for collisions."""
    sweep_min_points: int = 5
    """A swept pose collides when at least this many foreign scan points fall inside it."""
    sweep_bleed: float = 0.03
    """Scan points within this distance (m) of the moving parts at rest are not obstacles: they are
    the parts' own surface with a neighbour's label (label bleed) or depth noise."""
    obstacle_spacing: float = 0.02
    """Other objects' primitives are sampled about this densely (m) as obstacles of the sweeps."""
    joint_effort: float = 100.0
    """URDF <limit effort> (N or N·m)."""
    joint_velocity: float = 1.0
    """URDF <limit velocity> (m/s or rad/s)."""
    joint_damping: float = 1.0
    """URDF <dynamics damping> of movable joints (N·s/m or N·m·s/rad)."""
    joint_friction: float = 0.1
    """URDF <dynamics friction> of movable joints (N or N·m)."""

    # --- articulated-template shapes (part_shapes.py) ---
    template_shapes: bool = True
    """Give drawers their box and bodies with fronts a hollow carcass (else every part is its one
    fitted primitive)."""
    carcass_wall: float = 0.018
    """Panel thickness (m) of a hollow carcass (18 mm particle board)."""
    front_depth_tolerance: float = 0.04
    """A drawer/door front opens its carcass face only when its outer face lies at most this deep (m)
    inside the body's face (an inset front is flush; noise moves it a centimetre or two)."""
    drawer_wall: float = 0.012
    """Wall thickness (m) of a drawer box."""
    drawer_gap: float = 0.005
    """Clearance (m) between a drawer box and the carcass panels around it."""
    drawer_box_height: float = 0.7
    """A drawer box's height as a fraction of the room behind its front."""

    # --- refinement, Alg. 1 (refinement.py) ---
    refine: bool = True
    """Run Alg. 1 (off only to measure what it does)."""
    refine_align: float = 0.9
    """Plane normals with |cos| above this are paired for the Kabsch rotation (cos 26°)."""
    refine_max_angle: float = 0.35
    """A refinement rotation larger than this (rad) is rejected as a bad pairing."""
    snap_ambiguity: float = 0.05
    """A child is translated onto its parent's contact plane only if no plane pair along another
    direction has a contact score within this of the best pair's (else the snap is ambiguous)."""
    collision_clearance: float = 0.003
    """Movable parts and their children get collision boxes shrunk by this (m, each side), so they
    do not start in contact with their body or siblings in simulation."""

    # --- scene contact graph (scene_graph.py) ---
    support_distance: float = 0.05
    """An object whose bottom is within this (m) of the floor / a top surface is supported by it."""
    proximal_distance: float = 0.3
    """Objects whose footprints are closer than this (m) are proximal."""
    max_upright_tilt: float = 0.2
    """An object's tilt (rad) below this is corrected to upright by its support refinement."""

    # --- walls from the background (walls.py) ---
    walls: bool = True
    """Fit the room's walls to the background points and put them in scene.urdf / graph.json."""
    wall_floor_margin: float = 0.05
    """Background points below this height (m) are floor, not wall."""
    wall_ransac_distance: float = 0.05
    """RANSAC inlier distance (m) of a wall plane (walls are far from the camera: their depth noise is
    centimetres; the plane's offset is then the median of its inliers)."""
    wall_max_planes: int = 8
    """At most this many RANSAC planes are tried."""
    wall_min_fraction: float = 0.03
    """A wall plane needs at least this fraction of the (subsampled) background points ..."""
    wall_min_points: int = 200
    """... and at least this many."""
    wall_max_points: int = 30000
    """The background is subsampled (seeded) to this many points for RANSAC."""
    wall_max_tilt: float = 0.1
    """|n_z| of a wall plane's unit normal at most this (vertical within ~6°)."""
    wall_min_length: float = 0.5
    """A wall spans at least this (m) along the floor and up."""
    wall_merge_distance: float = 0.25
    """Parallel wall planes closer than this (m) are one wall."""
    wall_thickness: float = 0.1
    """Thickness (m) of a wall box, placed behind its plane (outside the room)."""

    # --- floor levelling (leveling.py) ---
    floor_ransac_distance: float = 0.02
    """RANSAC inlier distance (m) of the floor plane."""
    floor_candidates: int = 4
    """Largest planes tried as the floor."""
