"""Every threshold of the reconstruction, named once, with its meaning and unit, grouped by stage.

``ReconConfig`` holds one frozen group per stage; a stage function takes the groups it reads (most only
its own), never the whole config. Lengths in metres, angles in radians, mass in kg.

Field names are unique across groups, so a field can be set by name::

    config = ReconConfig().replace(theta_d=0.01, refine=False)       # any fields, any groups
    config = ReconConfig(contacts=ContactConfig(theta_d=0.01))       # or one group built whole
    config = ReconConfig().replace(clearance={"enabled": False})     # a group by its name
    config.contacts.theta_d                                          # read through its group
    ReconConfig.from_flat(config.flat()) == config                   # {field: value} round trip

The symbols of the paper (Sections II–III of Zhang et al., part-level scene reconstruction) are kept:
``theta_a``, ``theta_d``, ``theta_c`` of Eq. 1. Why a value is what it is: docs/decisions.md (recon).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field

__all__ = ["ReconConfig", "ScanConfig", "LevelingConfig", "FittingConfig", "CoverageConfig", "CompletionConfig", "ContactConfig",
           "TreeConfig", "RefinementConfig", "HandleConfig", "JointConfig", "ShapeConfig", "SceneConfig",
           "WallConfig", "UrdfConfig", "JointUncertaintyConfig", "ClearanceConfig"]


@dataclass(frozen=True)
class ScanConfig:
    """Reading and cleaning the scan (scan.py, outliers.py)."""

    min_part_points: int = 20
    """A part with fewer points is skipped with a warning naming it (too few to fit a primitive);
    ``recon build --min-part-points``."""
    handle_min_part_points: int = 4
    """... but a handle or knob is kept from this many points (at ScanNet density a handle shows 9-14, the
    sparsest 4-7): its bar is placed on its mount's face where its points are (handle_shapes.py); its
    points are one cluster (label_fragments.py). Why 4: docs/decisions.md ("Sparse parts")."""
    front_split_bin: float = 0.01
    """A drawer/door part's points are binned this high (m) along the vertical to find the horizontal
    gaps (dividers) between several fronts under one label (front_split.py)."""
    front_split_min_gap: float = 0.012
    """... a gap is at least this tall (m) ..."""
    front_split_density: float = 0.15
    """... its bins hold at most this fraction of the median count of the part's occupied bins ..."""
    front_split_min_height: float = 0.08
    """... and leaves at least this much (m) of front above and below it."""
    max_scene_extent: float = 60.0
    """A scan whose bounding box is larger than this (m) is refused: it is almost surely millimetres."""
    outlier_neighbors: int = 16
    """Statistical outlier removal (flying pixels): neighbours considered per point."""
    outlier_std_ratio: float = 3.0
    """... a point is an outlier when its mean neighbour distance exceeds the cloud's mean by this
    many standard deviations."""
    fragment_link_spacings: float = 8.0
    """A handle's (knob's, leg's) points closer than this many times the point spacing (median nearest-neighbour
    distance) of its object, or of its own points when sparser, are linked; its largest linked cluster is
    the handle (label_fragments.py) ..."""
    fragment_min_share: float = 0.34
    """... and so is any other cluster of at least this share of its points; smaller ones are a
    segmentation's label fragments and leave the part."""
    normal_neighbours: int = 48
    """A scan without normals: each part's normals are its local planes through this many of its
    nearest points, oriented away from its object's centre (estimated_normals.py)."""


@dataclass(frozen=True)
class LevelingConfig:
    """The floor of a scan, its frame and its scale (leveling.py, frame_checks.py)."""

    floor_ransac_distance: float = 0.02
    """RANSAC inlier distance (m) of the floor plane."""
    floor_candidates: int = 6
    """Largest planes of the background tried as the floor."""
    floor_min_points: int = 200
    """A floor is a background plane of at least this many points; with fewer the frame's z = 0 is
    assumed, with a warning."""
    floor_max_points: int = 30000
    """The background is subsampled to this many points for the floor's RANSAC."""
    max_floor_tilt_deg: float = 10.0
    """A floor more than this (deg) off the scan's xy plane: the scan is refused as not z-up or upside
    down, unless ``level_floor`` (which rotates it level)."""
    min_floor_tilt_deg: float = 0.25
    """A floor tilted less than this (deg) is taken as level (normal +z): about what a noisy floor
    resolves (the realistic scans of the level kitchen, bedroom and office 0 measure 0.006-0.016 deg,
    ScanNet-style ones are within 0.01 deg of their true ~1 deg), and a hinge tilted by such noise
    swings a door at rest in physics."""
    floor_offset_warning: float = 0.01
    """An output in the scan's frame whose floor is more than this (m) off z = 0, or tilted, is written
    with a warning (planners and simcheck put the robot and the ground plane on z = 0)."""


@dataclass(frozen=True)
class FittingConfig:
    """Eq. 3: the best primitive per part (fitting.py); also what counts as a thin panel."""

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
    """ICP's pose is kept only if it lowers the score by this fraction (on noisy scans ICP otherwise
    trades a few degrees of yaw for a fraction of a millimetre of score)."""
    icp_candidate_ratio: float = 2.0
    """Only candidates whose unaligned score is within this factor of the best one are ICP-aligned."""
    noise_floor: float = 0.003
    """Depth noise (m, robust σ across a box's best-seen face) below which extents are not corrected."""
    edge_tail_fraction: float = 0.02
    """Fraction of a box's points at each end of its best-seen axis that decide whether that end is a
    noise tail (pulled in by the noise correction) or a rim of side faces (kept)."""
    rim_min_extent: float = 0.3
    """... and only for boxes this wide (m) along both other axes (table tops, bed frames), not handles."""
    front_edge_density: float = 0.5
    """A noisy vertical panel's (door / drawer front's) edges along its face lie where the density of its
    front-face points along that axis falls to this fraction of the face's central density (the
    half-maximum of a blurred step); label bleed beyond the true edge is about a third of that density."""
    front_edge_bin_points: int = 20
    """... the density profile's bins hold this many points at the face's central density (at least
    ``front_edge_min_bin`` wide): fewer make the edge noisy, more blur it."""
    front_edge_min_bin: float = 0.006
    """... smallest bin width (m) of that profile."""
    front_edge_max_trim: float = 0.03
    """... an edge moves in from the 0.2 / 99.8 percentile extent by at most this (m); a deeper drop in
    density is occlusion (a mattress in front of a headboard's lower half), not the panel's edge."""
    front_edge_trim_spacings: float = 2.5
    """... or, for a front by its label (a door, a drawer: a board whose edges stand free in its frame), by at
    most this many times the spacing of the face's points (their median nearest-neighbour distance), when that
    is more: a scanner blurs an edge over a few of its samples (voxels, a segmentation's boundary bleed), so a
    coarse scan's edge lies farther in from its outermost points. Other panels keep ``front_edge_max_trim``: a
    headboard's lower edge is hidden by its mattress (docs/decisions.md, "A door's or drawer's edge trim")."""
    front_edge_tail_density: float = 0.1
    """... and from the extent where that density first reaches this fraction of the face's: points
    scattered farther out (flying pixels, label bleed from far) would spend the trim before the edge."""
    front_edge_min_points: int = 150
    """... a front face with fewer points keeps the percentile extents."""
    front_max_tilt: float = 0.2
    """A front (door, drawer front) stands: one of its in-plane axes is within this (rad) of the vertical;
    a board tilted further is measured as a slab, not given a front's board behind its face."""
    front_thickness: float = 0.018
    """Thickness (m) of a noisy vertical panel (door / drawer front): its seen face is the median of that
    face's points and the panel extends this far behind it (18 mm board, as ``carcass_wall``)."""
    normals_frame_cone: float = 0.26
    """A box candidate is also built along the directions its points' normals cluster in (within this
    angle, rad, 15 deg) ..."""
    normals_frame_min_angle: float = 0.17
    """... when that frame differs from the minimum-volume box's by more than this (rad, 10 deg)."""
    seen_face_band: float = 0.02
    """A box seen on several faces: the points (normals along an axis) within this (m) of an end of that
    axis are the face there; it is placed at their median (fitting._seen_faces)."""
    seen_face_max_turn: float = 0.3
    """... and only if the normals of those points turn by at most this (the change of their in-plane
    component, fitted linearly, across the face): a cylinder's side is not a face."""
    slab_edge_band: float = 0.02
    """A slab's (board's, table top's) edge points lie within this (m) of its outline in its plane; its
    points farther in are its seen face's only (fitting._slab_box)."""
    slab_min_cut: float = 0.003
    """... the edge points counted lie at least this (m) behind the seen face (on a clean scan 2.5σ is
    about 0 and the face's own points would count as edge points at depth 0)."""
    slab_min_turn: float = 0.01
    """... on a clean scan a slab's box is turned onto its face only when tilted off it by more than this
    (rad); otherwise only its thickness is measured."""
    slab_max_tilt: float = 0.2
    """... the slab's box is turned onto the plane of its seen face by at most this (rad)."""
    slab_hidden_fraction: float = 0.05
    """... a slab whose interior points reach deeper than 2.5σ behind its seen face in this share or more
    shows its other face too: its thickness is measured as a box's, not from its edges."""
    min_face_points: int = 12
    """The opposite face needs this many points (and a fifth of the best face's) to join a noise estimate."""
    coverage_distance: float = 0.02
    """A primitive surface sample is 'seen' when a scan point lies within this distance (m)."""
    min_face_coverage: float = 0.25
    """A primitive face with a smaller seen fraction counts as unobserved and is left out of the
    Eq. 3 score (cameras miss faces against walls, floors and each other)."""
    point_term_weight: float = 1.0
    """Weight of the scan-to-primitive mean distance (m) added to the Eq. 3 score, so that leaving
    unobserved faces out can never reward a primitive that does not explain the points."""
    small_part_points: int = 400
    """Parts with fewer points get only candidates aligned with their object's base part (their own
    bounding box is too noisy to orient them)."""
    box_preference: float = 0.1
    """A cylinder or sphere wins only if its score is lower than the best box's by this fraction."""
    box_labels: tuple[str, ...] = ("body", "drawer", "door")
    """Parts with these labels are fitted with box candidates only: a carcass and the drawers and doors that
    move in its rectangular openings are boxes and boards, whatever Eq. 3 prefers on noisy points (a 7 cm
    drawer front under 2 cm of depth noise, or a carcass seen on its top and sides, lies nearer a
    cylinder's curve than a box's edges)."""
    candidates: tuple[str, ...] = ("box", "cylinder_x", "cylinder_y", "cylinder_z", "sphere")
    """Candidate templates M^c: box, a cylinder along each box axis, sphere."""
    base_tilt_tolerance: float = 0.009
    """An object's base part (its body) fitted as a box tilted off the up direction its points' normals
    show (:func:`recon.object_up.measured_up`) by more than this (rad, 0.5 deg; estimated normals
    resolve 0.1-0.3 deg on the realistic scans) is refitted along that up direction without ICP: a body
    that is not one box (a carcass on a narrower plinth) is tilted by the minimum-volume box and ICP,
    and the parts refined onto it and the upright correction then move its fronts (pipeline.py)."""
    base_yaw_tolerance: float = 0.009
    """... and turned off the yaw the planes of its object's large vertical faces show
    (:func:`recon.object_yaw.measured_yaw`) by more than this (rad, 0.5 deg) and 2 standard errors of that
    yaw: Eq. 3 does not fix a noisy carcass's yaw (its score varies by 3 % over +-4 deg on a realistic
    scan), and Alg. 1 turns every front onto it."""
    yaw_consensus: float = 0.035
    """Face planes of one object whose yaws (modulo 90 deg) agree within this (rad, 2 deg) are taken as
    faces of one rigid box frame (:func:`recon.object_yaw.measured_yaw`); an opened door, the strip of a
    round leg, a box fitted across a leg's corners do not join them."""
    post_face_min_points: int = 4
    """A post's (leg's) face is placed at the median of the points whose normals point out of it when it has
    this many (recon.post_section; at ScanNet density a 4 cm leg shows 6-60 points a face)."""
    post_axial_share: float = 0.7
    """... a post whose horizontal normals lie within 18 deg of its base's axes in this share or more has a
    box section (about 1 on a box leg, 0.4 on a round one), else a round one."""
    post_min_slenderness: float = 2.0
    """... a part whose points stand less than this many times its section's width tall is no post (a
    pedestal table's foot disc) and keeps its Eq. 3 fit."""
    panel_ratio: float = 0.3
    """A part whose thinnest extent is below this fraction of the next one is a panel (a door or drawer
    front): its thin axis is the opening's normal (fitting, joints and refinement read it)."""


@dataclass(frozen=True)
class CoverageConfig:
    """Whether each fitted shape covers its points (coverage.py); a part outside a bound is warned about."""

    coverage_near_distance: float = 0.02
    """A point is covered when it lies inside the part's primitive or within this (m) of its surface, or
    within ``coverage_noise_sigmas`` times its part's depth noise when that is more."""
    coverage_noise_sigmas: float = 2.0
    """A noisier scan's points are covered within this many standard deviations of its part's depth noise:
    their robust spread across the face of their own oriented box that most of their normals show
    (recon.depth_noise), not across the fitted shape, which must not widen its own tolerance."""
    coverage_noise_min_points: int = 30
    """A part's depth noise is measured from this many points up (fewer: ``coverage_near_distance`` alone)."""
    coverage_noise_face_points: int = 12
    """The opposite face of a part's points' box joins the noise measure from this many points up."""
    coverage_min_extent: float = 0.02
    """The points' oriented box is at least this (m) along each axis (a face seen alone has no depth)."""
    max_mean_surface_distance: float = 0.05
    """Mean distance (m) from the part's points to its primitive's surface, at most this (a headboard
    fitted as a cylinder: 57-65 mm; well fitted parts of realistic scans: at most 43 mm)."""
    min_near_fraction: float = 0.5
    """Share of the part's points covered, at least this (realistic scans' depth noise, label bleed and
    outliers leave 60-100 % of a well fitted part's points within 2 cm)."""
    max_volume_ratio: float = 2.5
    """Volume of the Eq. 3 primitive over the volume of its points' oriented box, at most this (a
    cylinder around a half-seen leg reaches about 2)."""


@dataclass(frozen=True)
class CompletionConfig:
    """Parts extended or placed where the scan missed them (completion.py)."""

    completion_reach: float = 0.3
    """Legs are extended to a surface above / below them, and hidden legs placed, at most this far (m)."""
    hidden_face_points: int = 12
    """A box end whose part has fewer points with normals out of it (cos > 0.8) was not seen: a bed frame's
    rail under its mattress (completion.complete_reaching_parts); as ``FittingConfig.min_face_points``."""


@dataclass(frozen=True)
class ContactConfig:
    """Surface planes Π and the Eq. 1 contact test (planes.py, contacts.py); every stage that asks
    whether two faces touch uses these tolerances."""

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


@dataclass(frozen=True)
class TreeConfig:
    """Eq. 4: the part tree from the contact graph (part_tree.py)."""

    foreign_parent_penalty: float = 0.2
    """Template prior: an edge whose parent label is not one the child's template expects (a handle
    under a body instead of its drawer) has its contact score multiplied by this (also in the mAP
    ranking of :func:`recon.part_tree.contact_scores`)."""
    near_parent_distance: float = 0.1
    """A part with no Eq. 1 contact, or only a weak one, to a parent its template expects is hung from the
    nearest such part closer than this (m) (noisy scans break contacts by a few centimetres; a fit stretched by
    label fragments touches its parent over a sliver)."""
    near_parent_weight: float = 0.3
    """Edge weight of that attachment at zero distance (below the contact scores of real contacts)."""
    fallback_edge_weight: float = 1e-6
    """Weight of the root -> part edge given to parts that touch nothing (they are reported)."""


@dataclass(frozen=True)
class RefinementConfig:
    """Alg. 1: children rotated and moved onto their parents' planes (refinement.py)."""

    refine: bool = True
    """Run Alg. 1 (off only to measure what it does)."""
    refine_align: float = 0.9
    """Plane normals with |cos| above this are paired for the Kabsch rotation (cos 26°)."""
    refine_max_angle: float = 0.35
    """A refinement rotation larger than this (rad) is rejected as a bad pairing."""
    snap_ambiguity: float = 0.05
    """A child is translated onto its parent's contact plane only if no plane pair along another
    direction has a contact score within this of the best pair's (else the snap is ambiguous)."""
    snap_front_panels: bool = False
    """Translate a front panel (door, drawer front: a child thinner than ``panel_ratio`` of its other
    extents, parallel to the contact plane) onto its body's face. Off: the panel's seen face (the median
    of thousands of points) is better measured than the body's front plane, which label bleed from the
    fronts pushes out."""


@dataclass(frozen=True)
class HandleConfig:
    """A handle as the shapes a gripper meets (handle_shapes.py)."""

    handle_shapes: bool = True
    """Write a handle as a bar on two posts (a knob: a cap on its stem) instead of the one box
    enveloping it down to its mount."""
    handle_bleed_margin: float = 0.008
    """Handle points within this (m) of their mount's face are the front's own surface (label bleed)
    or its depth noise; they do not measure the bar."""
    handle_face_window: float = 0.04
    """The mount's points within this (m) of its fitted face, and within the handle's reach plus this
    along it, show where the face behind the handle was seen (their median height)."""
    handle_min_points: int = 15
    """A handle needs this many points clear of the face for a bar/knob; else it keeps its envelope."""
    handle_extent_percentile: float = 2.0
    """A handle's extents along the face come from the [p, 100 - p] percentiles (%) of its points clear
    of the face (widened by 1 / (1 - 2p/100))."""
    handle_middle_percentile: float = 10.0
    """A horizontal bar's middle across it (up the face) is the mean of this and the opposite percentile
    (%) of its points (the top face seen from above pulls their median up); a vertical bar's is their
    median (see ``recon.handle_shapes._middle_across``)."""
    handle_outer_percentile: float = 90.0
    """A bar's outer face lies at most at this percentile (%) of its points' heights off the face ..."""
    handle_outer_noise: float = 1.28
    """... less this many σ of depth noise (σ: spread of the mount's points about the face seen; 1.28 =
    the 90 % quantile of a normal): a bar seen mostly from the front has its median point on its outer
    face, not at its centre."""
    handle_max_thickness: float = 0.018
    """A bar's thickness (m, across it and out from the face) and a knob cap's depth, at most this:
    bars are 10-16 mm; a wider measure is lateral noise and label bleed."""
    handle_knob_max_length: float = 0.08
    """A handle shorter than this (m) along the face in every direction is a knob (cap on a stem), else
    a bar on two posts (bars are 10-35 cm long, knobs 3-5 cm across)."""
    handle_knob_max_diameter: float = 0.05
    """A knob cap's diameter (m) at most this."""
    handle_post_width: float = 0.012
    """Diameter (m) of a bar's standoff posts and a knob's stem (hidden behind the bar: a typical value)."""
    handle_post_inset: float = 0.015
    """A bar's posts stand this far (m) in from its ends."""
    handle_min_standoff: float = 0.008
    """The bar's (cap's) inner face must stand at least this far (m) off the face, room for posts (a
    stem); else the handle keeps its envelope."""
    handle_min_post: float = 0.002
    """... and the posts (stem) down to the mount's fitted face at least this long (m): a mount fitted in
    front of the bar (a noise-thickened front) leaves the handle its envelope."""


@dataclass(frozen=True)
class JointConfig:
    """Joint type, axis, origin and limits (joints.py); the swept-collision test of the limits."""

    drawer_travel_fraction: float = 0.8
    """Drawer upper limit = this × the drawer box's depth, estimated as the body's depth along the
    drawer axis minus ``drawer_back_clearance`` (a closed drawer's box is hidden from the camera)."""
    rail_drawer_depth: float = 0.45
    """Depth (m) of a drawer in a parent thinner than the object behind it (a table's apron): the
    object's reach behind the parent's face, at most this (a desk drawer's depth; the box is unseen)."""
    drawer_back_clearance: float = 0.025
    """Back panel plus the gap behind a drawer box (m); also where a drawer's template box ends."""
    door_max_angle: float = 1.75
    """A door hinge's stop (rad, 100°; furniture hinges open 95–110°); the swept-collision test
    stops the door earlier when it would hit its body, a neighbour or a wall."""
    door_drop_angle: float = 1.5707963267948966
    """The stop (rad, 90°) of a door that opens downward (hinged about a horizontal axis below its centre:
    an oven's or a dishwasher's door, a drop-down flap): it opens to horizontal, the shelf a rack or a
    tray rolls out onto, and its stay or hinge stops it there (:func:`recon.joints.door_stop`)."""
    swing_step: float = 0.035
    """Angular / travel sampling step (rad or m) of the collision sweep."""
    sweep_clearance: float = 0.015
    """The moving part is shrunk by this (m, each side) when swept for collisions."""
    sweep_min_points: int = 5
    """A swept pose collides when at least this many foreign scan points fall inside it."""
    sweep_bleed: float = 0.03
    """Scan points within this distance (m) of the moving parts at rest are not obstacles: they are
    the parts' own surface with a neighbour's label (label bleed) or depth noise."""
    obstacle_spacing: float = 0.02
    """Other objects' primitives are sampled about this densely (m) as obstacles of the sweeps."""
    hinge_edge_band: float = 0.02
    """Points within this (m) of a door's hinge edge, across it, show where the door meets its carcass
    (hinge_depth.py): the carcass's side face behind an overlay door, its front face beside an inset one
    (and, when the hinge edge shows too few points, the carcass's faces at the door's other edges)."""
    hinge_edge_trim: float = 0.03
    """... leaving out this much (m) at each end of the hinge edge (the carcass's top and bottom panels)."""
    hinge_edge_min_points: int = 10
    """... and only when at least this many of the door's and of the carcass's points are there."""
    door_max_thickness: float = 0.1
    """The thickest door (m) looked for behind a front face (a refrigerator's door with its liner)."""
    hinge_depth_tolerance: float = 0.015
    """A door measured thicker than the front's board by at most this (m) keeps the board's back face: the
    measurement's own spread at the seam (label bleed; figures: docs/decisions.md, thick doors)."""
    hinge_depth_p_value: float = 0.001
    """... and a thicker door only when its carcass's points at the hinge edge rule out, at this significance
    (likelihood ratio, chi-square with 1 dof), every onset of its side face a door that thin would show
    (the depth noise modelled; recon/hinge_depth.py, docs/decisions.md, thick doors)."""
    hinge_clearance_p_value: float = 0.05
    """The carcass's side face at a door's hinge edge may begin as deep as the deepest onset its points do not
    rule out at this significance (likelihood ratio, chi-square with 1 dof): the door's ``HingeDepth.clearance``,
    which the joint's stated uncertainty covers (recon/hinge_depth.py)."""
    hinge_side_margin: float = 0.03
    """A door without a handle is hinged at the edge nearer its body's edge; when the two edges' distances
    to the body's edges differ by less than this (m, about what a scan's edges are off by) the side is
    undecided and a warning says so."""


@dataclass(frozen=True)
class ShapeConfig:
    """Articulated-template shapes: a drawer's box, a hollow carcass (part_shapes.py)."""

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


@dataclass(frozen=True)
class SceneConfig:
    """The scene contact graph: support, proximity, upright poses (scene_graph.py)."""

    support_distance: float = 0.05
    """An object whose bottom is within this (m) of the floor / a top surface is supported by it."""
    base_bottom_tolerance: float = 0.02
    """An object standing above its support has its base part extended down onto it (what it stands on
    is not seen: feet, a plinth, a hidden bottom edge) when the base's bottom is within this (m) of the
    object's lowest point; otherwise the whole object moves down (scene_graph.resting_on)."""
    proximal_distance: float = 0.3
    """Objects whose footprints are closer than this (m) are proximal."""
    max_upright_tilt: float = 0.2
    """An object's tilt (rad) below this is corrected to upright by its support refinement."""


@dataclass(frozen=True)
class WallConfig:
    """Walls of the room from the background points (walls.py)."""

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


@dataclass(frozen=True)
class UrdfConfig:
    """What scene.urdf says beyond the geometry: mass, joint limits and dynamics (scene_urdf.py)."""

    density: float = 600.0
    """kg/m^3 of every part (particle board); mass = density × the volume of its shapes."""
    joint_effort: float = 100.0
    """URDF <limit effort> (N or N·m)."""
    joint_velocity: float = 1.0
    """URDF <limit velocity> (m/s or rad/s)."""
    joint_damping: float = 1.0
    """URDF <dynamics damping> of movable joints (N·s/m or N·m·s/rad)."""
    joint_friction: float = 0.1
    """URDF <dynamics friction> of movable joints (N or N·m); a flap's or drop-down door's is its stay's
    (scene_urdf.py), larger."""
    gravity: float = 9.81
    """m/s^2 along the floor's normal: what a flap's stay holds (scene_urdf.py)."""
    collision_clearance: float = 0.003
    """Movable parts and their children get collision boxes shrunk by this (m, each side), so they
    do not start in contact with their body or siblings in simulation."""


@dataclass(frozen=True)
class JointUncertaintyConfig:
    """The bootstrap of each movable joint's estimate (joint_uncertainty.py)."""

    samples: int = 10
    """Resamplings per movable joint (0 = no uncertainty written)."""
    limit_samples: int = 3
    """... of which this many also re-run the upper limit's collision sweep (the costly step)."""
    max_points: int = 1500
    """A part's points are subsampled (seeded) to at most this many before resampling."""
    obstacle_margin: float = 0.1
    """Obstacle points farther (m) than this beyond the joint's parts' reach are left out of its sweeps."""
    drawer_travel_prior: float = 0.05
    """σ (m) of a drawer's travel that no scan shows: its box is hidden behind its front, and the travel is
    ``drawer_travel_fraction`` of the body's depth (the scenes' drawers travel 0.8 of their own box, which
    can be centimetres shallower). Added in quadrature to the bootstrap spread of a drawer's upper limit."""
    door_stop_prior: float = 0.09
    """σ (rad) of a door's stop when no obstacle limits its swing: the hinge's stop is not seen; the
    estimate assumes ``door_max_angle`` or ``door_drop_angle`` (furniture hinges stop at 92-110 deg, σ of a uniform 0.3 rad
    range). Added in quadrature to the bootstrap spread of such a door's upper limit."""


@dataclass(frozen=True)
class ClearanceConfig:
    """How the clearance stage (clearance.py) keeps the scene's links apart at q = 0. Lengths in metres."""

    enabled: bool = True
    """Cut overlapping shapes apart (off only to measure what the stage does)."""
    moving_gap: float = 0.0
    """Gap left between shapes that move relative to each other (a door and its carcass). The URDF's
    collision shapes of moving parts are also shrunk by ``UrdfConfig.collision_clearance``; touching
    solids therefore start that far apart in an engine."""
    tolerance: float = 1e-6
    """Overlaps up to this are left alone (rounding of the written file)."""
    report_overlap: float = 5e-4
    """A pair still overlapping by more than this after the stage is reported with a warning."""
    min_keep_fraction: float = 0.25
    """A cut never leaves less than this fraction of the shape's extent along the cut axis."""
    wall_max_shift: float = 0.2
    """A fitted wall moves back (out of the room) at most this far to clear an object."""
    max_passes: int = 4
    """Passes over the overlapping pairs (a cut can only shrink a shape, so few are needed)."""
    contact_distance: float = 0.005
    """Links whose shapes come this close at q = 0 are in contact at rest: scene.srdf lists them
    (``disable_collisions``) for planners that read one (fronts hang 2-3 mm off their carcass)."""


@dataclass(frozen=True)
class ReconConfig:
    """One frozen group per stage (see the module docstring for how to set a field by name)."""

    scan: ScanConfig = field(default_factory=ScanConfig)
    leveling: LevelingConfig = field(default_factory=LevelingConfig)
    fitting: FittingConfig = field(default_factory=FittingConfig)
    coverage: CoverageConfig = field(default_factory=CoverageConfig)
    completion: CompletionConfig = field(default_factory=CompletionConfig)
    contacts: ContactConfig = field(default_factory=ContactConfig)
    tree: TreeConfig = field(default_factory=TreeConfig)
    refinement: RefinementConfig = field(default_factory=RefinementConfig)
    handles: HandleConfig = field(default_factory=HandleConfig)
    joints: JointConfig = field(default_factory=JointConfig)
    shapes: ShapeConfig = field(default_factory=ShapeConfig)
    scene: SceneConfig = field(default_factory=SceneConfig)
    walls: WallConfig = field(default_factory=WallConfig)
    urdf: UrdfConfig = field(default_factory=UrdfConfig)
    joint_uncertainty: JointUncertaintyConfig = field(default_factory=JointUncertaintyConfig)
    clearance: ClearanceConfig = field(default_factory=ClearanceConfig)

    def flat(self) -> dict:
        """{field name: value} over every group, except that the groups of ``NESTED`` stay one
        {group name: {field: value}} entry each (the ``config`` of graph.json)."""
        out = {f.name: getattr(getattr(self, g), f.name) for g, f in _FIELDS if g not in NESTED}
        out.update({g: dataclasses.asdict(getattr(self, g)) for g in NESTED})
        return out

    def replace(self, **fields) -> "ReconConfig":
        """A copy with the named fields (of any groups) set; a group's name sets the whole group (a
        group object or a {field: value} mapping). An unknown name raises TypeError."""
        unknown = sorted(set(fields) - set(_GROUP_OF) - set(_GROUPS))
        if unknown:
            raise TypeError(f"ReconConfig has no field {', '.join(map(repr, unknown))}")
        whole = {g: v if not isinstance(v, Mapping) else _GROUPS[g](**v)
                 for g, v in fields.items() if _is_group(g, v)}
        groups: dict[str, dict] = {}
        for name, value in fields.items():
            if not _is_group(name, value):
                groups.setdefault(_GROUP_OF[name], {})[name] = value
        out = dataclasses.replace(self, **whole)
        return dataclasses.replace(out, **{g: dataclasses.replace(getattr(out, g), **kw) for g, kw in groups.items()})

    @classmethod
    def from_flat(cls, fields: Mapping, *, ignore_unknown: bool = False) -> "ReconConfig":
        """The config with ``fields`` (as :meth:`flat` writes them) set over the defaults (lists become
        tuples); unknown names raise TypeError unless ``ignore_unknown``."""
        known = set(_GROUP_OF) | set(_GROUPS)
        kw = {k: v for k, v in fields.items() if not ignore_unknown or k in known}
        kw = {k: tuple(v) if isinstance(v, list) else v for k, v in kw.items()}
        return cls().replace(**kw)


NESTED = ("joint_uncertainty", "clearance")
"""Groups written nested in graph.json (their field names are generic: ``samples``, ``enabled``)."""
_GROUPS = {g.name: g.default_factory for g in dataclasses.fields(ReconConfig)}
"""{group name: its dataclass}."""
_FIELDS = tuple((g, f) for g, cls in _GROUPS.items() for f in dataclasses.fields(cls))
"""(group name, dataclasses.Field) of every field, in declaration order."""
_GROUP_OF = {f.name: g for g, f in _FIELDS}
"""{field name: its group's name in ReconConfig}."""
assert len(_GROUP_OF) == len(_FIELDS), "a ReconConfig field name is used in two groups"


def _is_group(name: str, value) -> bool:
    """Whether ``name=value`` in :meth:`ReconConfig.replace` sets a whole group (``walls`` is both a
    group and its on/off field: a WallConfig or a mapping sets the group, a bool the field)."""
    return name in _GROUPS and (name not in _GROUP_OF or isinstance(value, (_GROUPS[name], Mapping)))
