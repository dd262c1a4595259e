"""Part-level reconstruction: from a labelled scan to an interactive scene URDF (Zhang et al., Sec. II–III).

Pipeline (one module per product)::

    scan.py        read + validate scan.ply / scan.npz + labels.json            -> Scan
    leveling.py    optional: find the floor and the up direction               -> levelled Scan
    outliers.py    statistical outlier removal per part (flying pixels)
    bounding.py    robust oriented boxes (upright / free / principal axes)
    fitting.py     Eq. 3: best primitive per part (OBB candidates + ICP, observed-face score,
                   depth-noise-corrected box extents)                          -> PartFit
    completion.py  legs extended to their supports, handles back onto their mounts
    planes.py      surface planes Π: exact primitive faces (default) or RANSAC on the points
    contacts.py    Eq. 1: Align / Dist / Cont with shapely polygon intersection -> ContactEdge
    part_tree.py   Eq. 4: maximum spanning arborescence (Edmonds), root = base part, template prior
    refinement.py  Alg. 1: Kabsch rotation of each child onto its parent's planes, top down
    joints.py      articulated templates (templates.py): joint type, axis, origin, limits (sweeps)
    part_shapes.py template shapes: a drawer's box behind its front, a hollow carcass open at its fronts
    handle_shapes.py a handle as a gripper meets it: a bar at its outer extent on two posts (a knob:
                   cap on stem), measured off the mount face; the envelope box when unclear
    walls.py       walls of the room: vertical RANSAC planes of the background -> wall0, wall1, ... boxes
    scene_graph.py objects: support (floor / another object), proximity, upright pose
    scene_urdf.py  scene.urdf (yourdfpy);  graph_json.py  graph.json;  preview.py  preview.png
    output.py      atomic writing;  cli.py  ``recon build``;  open3d_engine.py  the open3d adapter

Python API::

    from recon import reconstruct, write_reconstruction, ReconConfig
    rec = reconstruct("scan.ply", "labels.json", config=ReconConfig(), level_floor=False, seed=0)
    write_reconstruction(rec, "out/") # scene.urdf + graph.json, atomically
    for obj in rec.objects:           # ObjectReconstruction
        obj.id, obj.category, obj.name, obj.root_part_id
        for part in obj.parts:        # PartFit
            part.part_id, part.label, part.link
            part.primitive.kind       # PrimitiveKind.BOX / CYLINDER / SPHERE
            part.primitive.size       # (3,) box extents | cylinder (2r, 2r, length along local z) | sphere (2r,)*3
            part.primitive.T_world_part   # (4, 4)
            part.primitive.to_trimesh(), part.primitive.sample_surface(n, rng)
            part.solids               # the URDF shapes: template shapes (drawer box, carcass panels)
                                      #   or (part.primitive,)
        obj.joints                    # JointEstimate: name, type, parent_part_id, child_part_id,
                                      #   axis (3,), origin (3,), lower, upper, contact_score
    recon.part_tree.contact_scores(obj, rec.config.tree)   # {(a, b): score} every Eq. 1 contact (for
                                      #   mAP); score = Cont x template prior (weighted=False: raw Cont)
        obj.tree_edges()              # ((parent, child), ...) the estimated part tree
    rec.graph.supports, rec.graph.proximal, rec.warnings
    rec.walls                         # Wall: name ("wall0"), size (thickness, length, height), T_world_wall

    read_graph_json("graph.json") -> Reconstruction     # the inverse of write_reconstruction (same model)

CLI: ``recon build SCAN --labels LABELS --out DIR [--level-floor] [--seed N] [-v|-q]``.
"""

import lazy_loader

# Names are imported on first use: importing recon (or a pure module such as recon.model) does not load
# open3d or matplotlib.
__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "pipeline": ["reconstruct"],
    "scan": ["read_scan", "Scan"],
    "graph_json": ["read_graph_json"],
    "output": ["write_reconstruction"],
    "config": ["ReconConfig"],
    "errors": ["ReconError", "ScanError", "ReconstructionError"],
    "primitive": ["Primitive", "PrimitiveKind", "SurfacePlane"],
    "model": ["PartFit", "ContactEdge", "JointEstimate", "JointType", "ObjectReconstruction", "SceneGraph",
              "Reconstruction"],
})
