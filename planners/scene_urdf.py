"""The scene URDF as the planners read it: :func:`scenes.description.read_urdf` (the project's one URDF
reader) with its problems raised as :class:`planners.errors.SceneURDFError` naming the file and element.

The model (:class:`scenes.description.SceneModel`) gives links with their collision shapes (what planning
checks) and visuals, joints with limits, and forward kinematics ``T_world_link(link, values)``.
"""

from __future__ import annotations

from pathlib import Path

from planners.errors import SceneURDFError
from scenes.description import DescriptionError, SceneModel, read_urdf

__all__ = ["read_scene_urdf"]


def read_scene_urdf(path) -> SceneModel:
    """Parse and check a scene URDF (one tree, known parents, finite numbers, limits on movable joints)."""
    path = Path(path)
    if not path.is_file():
        raise SceneURDFError(f"{path}: scene URDF not found")
    try:
        return read_urdf(path)
    except DescriptionError as e:
        raise SceneURDFError(str(e)) from e
