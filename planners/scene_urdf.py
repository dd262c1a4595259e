"""The scene URDF as the planners read it: :func:`scenes.description.read_urdf` (the project's one URDF
reader) with its problems raised as :class:`planners.errors.SceneURDFError` naming the file and element; and
the floor the robot stands on (:func:`scenes.description.read_scene_floor`: recon's graph.json beside it, else
z = 0).

The model (:class:`scenes.description.SceneModel`) gives links with their collision shapes (what planning
checks) and visuals, joints with limits, and forward kinematics ``T_world_link(link, values)``.
"""

from __future__ import annotations

from pathlib import Path

from planners.errors import SceneURDFError
from scenes.description import DescriptionError, SceneFloor, SceneModel, read_scene_floor, read_urdf

__all__ = ["read_scene_urdf", "read_floor"]


def read_scene_urdf(path) -> SceneModel:
    """Parse and check a scene URDF (one tree, known parents, finite numbers, limits on movable joints)."""
    path = Path(path)
    if not path.is_file():
        raise SceneURDFError(f"{path}: scene URDF not found")
    try:
        return read_urdf(path)
    except DescriptionError as e:
        raise SceneURDFError(str(e)) from e


def read_floor(path) -> SceneFloor:
    """The floor of the scene URDF at ``path`` (graph.json beside it; z = 0 without one)."""
    try:
        return read_scene_floor(path)
    except DescriptionError as e:
        raise SceneURDFError(str(e)) from e
