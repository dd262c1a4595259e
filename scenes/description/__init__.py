"""The scene description every partscene package imports: engine-free (numpy, scipy, yourdfpy, lxml).

* errors: :class:`PartsceneError` > :class:`InputError` > :class:`DescriptionError`;
* atomic writes (``write_text_atomic``, ...), URDF naming (``link_name``, ``joint_name``, ...), the label
  and category vocabulary (``PART_LABELS``, ``KNOWN_CATEGORIES``, ``LABEL_RGBA``, ...);
* poses: ``T_a_b`` (4, 4) float64 helpers (``T_inverse``, ``R_about``, ``T_from_xyz_rpy``, checks);
* :class:`Shape` (box / cylinder / sphere / mesh; a cylinder's size is (2r, 2r, length)), volume, inertia;
* :class:`SceneModel` (links, joints, limits, dynamics, inertials, visuals; ``T_world_link(link, q)``),
  read and written by :func:`read_urdf` / :func:`write_urdf`, the only URDF reader and writer;
* ``truth.json``: :data:`TRUTH_FORMAT`, :func:`read_truth_doc`, :func:`write_truth_doc`.
"""

from ._atomic import write_bytes_atomic, write_text_atomic, write_with_atomic
from ._errors import DescriptionError, InputError, PartsceneError
from ._model import Dynamics, Inertial, Joint, JointType, Limit, Link, SceneModel, joint_motion
from ._naming import WORLD_LINK, joint_name, link_name, object_name, parse_link_name
from ._poses import (ROTATION_ATOL, R_about, T_about, T_from_xyz_rpy, T_inverse, T_translation, check_pose,
                     check_rotation, pose, rot_x, rot_y, rot_z, transform_points, xyz_rpy_from_T)
from ._shape import Material, Shape, ShapeKind, mass_properties
from ._truth import TRUTH_FORMAT, check_truth_format, read_truth_doc, write_truth_doc
from ._urdf import read_urdf, urdf_text, urdf_xml, write_urdf
from ._vocabulary import (DEFAULT_RGBA, FRONT_CATEGORIES, KNOWN_CATEGORIES, KNOWN_LABELS, LABEL_RGBA, PART_LABELS,
                          SCENE_CATEGORIES)

__all__ = [
    "PartsceneError", "InputError", "DescriptionError",
    "write_text_atomic", "write_bytes_atomic", "write_with_atomic",
    "WORLD_LINK", "object_name", "link_name", "joint_name", "parse_link_name",
    "SCENE_CATEGORIES", "KNOWN_CATEGORIES", "FRONT_CATEGORIES", "PART_LABELS", "KNOWN_LABELS", "LABEL_RGBA",
    "DEFAULT_RGBA",
    "pose", "rot_x", "rot_y", "rot_z", "R_about", "T_about", "T_inverse", "T_translation", "T_from_xyz_rpy",
    "xyz_rpy_from_T", "transform_points", "check_pose", "check_rotation", "ROTATION_ATOL",
    "ShapeKind", "Material", "Shape", "mass_properties",
    "JointType", "Limit", "Dynamics", "Inertial", "Link", "Joint", "SceneModel", "joint_motion",
    "read_urdf", "urdf_text", "urdf_xml", "write_urdf",
    "TRUTH_FORMAT", "check_truth_format", "read_truth_doc", "write_truth_doc",
]
