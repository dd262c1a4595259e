"""The scene description every partscene package imports: engine-free (numpy, scipy, yourdfpy, lxml).

* errors: :class:`PartsceneError` > :class:`InputError` > :class:`DescriptionError`;
* atomic writes (``write_text_atomic``, ...), URDF naming (``link_name``, ``joint_name``, ...), the label
  and category vocabulary (``PART_LABELS``, ``KNOWN_CATEGORIES``, ``LABEL_RGBA``, ...);
* poses: ``T_a_b`` (4, 4) float64 helpers (``T_inverse``, ``R_about``, ``T_from_xyz_rpy``, checks);
* :class:`Shape` (box / cylinder / sphere / mesh; a cylinder's size is (2r, 2r, length)), volume, inertia;
* :class:`SceneModel` (links, joints, limits, dynamics, inertials, visuals; ``T_world_link(link, q)``),
  read and written by :func:`read_urdf` / :func:`write_urdf`, the only URDF reader and writer;
* the stay of a flap or a drop-down door (:func:`stay_friction`: the joint friction that holds it against
  gravity; a scan does not show it);
* the floor a scene stands on: :func:`read_scene_floor` (recon's graph.json beside the URDF) ->
  :class:`SceneFloor` (``T_scene_floor``, gravity), :data:`LEVEL_FLOOR` (z = 0, z up) when there is none;
* ``truth.json``: :data:`TRUTH_FORMAT`, :func:`read_truth_doc`, :func:`write_truth_doc`, and the document as
  checked, typed objects: :func:`read_true_scene` -> :class:`TrueScene` (objects, parts, joints, contacts).
"""

import lazy_loader

# Names are imported on first use: the error classes and naming load no numpy, so a command line that
# imports its package's errors stays quick.
__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "_errors": ["PartsceneError", "InputError", "DescriptionError"],
    "_atomic": ["write_text_atomic", "write_bytes_atomic", "write_with_atomic"],
    "_naming": ["WORLD_LINK", "object_name", "link_name", "joint_name", "parse_link_name", "file_stem"],
    "_vocabulary": ["SCENE_CATEGORIES", "KNOWN_CATEGORIES", "FRONT_CATEGORIES", "PART_LABELS", "KNOWN_LABELS",
                    "LABEL_RGBA", "DEFAULT_RGBA"],
    "_poses": ["pose", "rot_x", "rot_y", "rot_z", "R_about", "T_about", "T_inverse", "T_translation",
               "T_from_xyz_rpy", "xyz_rpy_from_T", "transform_points", "check_pose", "check_rotation",
               "ROTATION_ATOL"],
    "_shape": ["ShapeKind", "Material", "SolidProperties", "Shape", "shape_volume", "shape_inertia",
               "mass_properties"],
    "_model": ["JointType", "Limit", "Dynamics", "Inertial", "Link", "Joint", "SceneModel", "joint_motion"],
    "_urdf": ["MAX_NAME_LENGTH", "read_urdf", "urdf_text", "urdf_xml", "xml_text", "round_numbers", "write_urdf", "LENGTH_DECIMALS",
              "SIGNIFICANT_DIGITS"],
    "_stays": ["STAY_HOLD", "STAY_MAX_TILT_DEG", "gravity_torque", "stay_friction", "with_stays"],
    "_floor": ["SceneFloor", "LEVEL_FLOOR", "read_scene_floor", "R_onto_up", "FLOOR_FILE"],
    "_truth": ["TRUTH_FORMAT", "check_truth_format", "read_truth_doc", "write_truth_doc", "shape_from_truth",
               "truth_shape_dict"],
    "_truth_scene": ["TruePart", "TrueJoint", "TrueObject", "TrueWall", "TrueScene", "true_scene_from_doc", "read_true_scene"],
})
