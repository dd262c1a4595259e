"""The floor a scene stands on: the plane the robot's base stands on, gravity pulls against and the
ground plane of a simulation is put on.

recon writes the floor it estimated into ``graph.json`` beside ``scene.urdf`` (``"floor": {"height_m",
"tilt_deg", "normal", "n_points"}``, in the scene URDF's frame): a scan kept in its own frame (ScanNet-style:
the floor 4-7 cm off the origin, tilted about 1 deg) has its floor there, not at z = 0. Every other scene
(truth.urdf, a third-party URDF, a graph.json without a floor or with ``n_points`` 0) stands on its own
z = 0 plane, z up: :data:`LEVEL_FLOOR`.

Frames: the floor frame F has its z along the floor's normal (up, into the room), its origin the floor's
point nearest the scene frame's origin (``height_m * normal``) and its x, y the scene's turned by the floor's
tilt only (the shortest rotation taking +z onto the normal): :meth:`SceneFloor.T_scene_floor`, the inverse
of recon's levelling transform. For :data:`LEVEL_FLOOR` F is the scene frame itself.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from ._errors import DescriptionError

__all__ = ["SceneFloor", "LEVEL_FLOOR", "read_scene_floor", "R_onto_up", "FLOOR_FILE"]

FLOOR_FILE = "graph.json"
"""The file beside a scene URDF that holds its floor (recon's scene graph)."""

_UP = np.array([0.0, 0.0, 1.0])


def R_onto_up(normal) -> np.ndarray:
    """(3, 3) the shortest rotation taking the unit ``normal`` (3,) onto +z (a half turn about x when it is
    -z; the identity when it is +z)."""
    n = np.asarray(normal, dtype=np.float64).reshape(3)
    if n[2] < -1.0 + 1e-12:
        return np.diag([1.0, -1.0, -1.0])
    if n[0] == 0.0 and n[1] == 0.0:
        return np.eye(3)
    rot, _ = Rotation.align_vectors([_UP], [n])
    return rot.as_matrix()


@dataclass(frozen=True)
class SceneFloor:
    """A floor plane in a scene's frame (hashable: planners cache the robot's kinematics per floor).

    normal : (3,) unit, up (into the room), scene frame
    height_m : the plane's offset (m) from the scene frame's origin along ``normal`` (``normal · p =
        height_m`` on the floor; for a level floor, its z)
    source : where it was read ("" for :data:`LEVEL_FLOOR`)
    """

    normal: tuple[float, float, float] = (0.0, 0.0, 1.0)
    height_m: float = 0.0
    source: str = field(default="", compare=False)

    @property
    def level(self) -> bool:
        """The scene frame's own z = 0 plane, z up (the floor frame is the scene frame)."""
        return self.normal == (0.0, 0.0, 1.0) and self.height_m == 0.0

    @property
    def tilt_deg(self) -> float:
        """Angle (deg) between the normal and the scene frame's +z."""
        return math.degrees(math.acos(max(-1.0, min(1.0, self.normal[2]))))

    @property
    def T_scene_floor(self) -> np.ndarray:
        """(4, 4) the floor frame in the scene's frame (module docstring); the identity for a level floor."""
        T = np.eye(4)
        if not self.level:
            T[:3, :3] = R_onto_up(self.normal).T
            T[:3, 3] = self.height_m * np.asarray(self.normal)
        return T

    def gravity(self, g: float) -> np.ndarray:
        """(3,) gravity, m/s^2, scene frame: ``g`` against the floor's normal ((0, 0, -g) when level)."""
        return np.array([0.0, 0.0, -float(g)]) if self.level else -float(g) * np.asarray(self.normal)

    def height_of(self, points) -> np.ndarray:
        """(n,) signed height (m) of scene-frame ``points`` (n, 3) above the floor, along its normal."""
        return np.asarray(points, dtype=np.float64).reshape(-1, 3) @ np.asarray(self.normal) - self.height_m


LEVEL_FLOOR = SceneFloor()
"""The scene frame's z = 0 plane, z up: the floor of every scene without an estimated one."""


def read_scene_floor(scene_urdf: str | Path) -> SceneFloor:
    """The floor of the scene in ``scene_urdf``: ``graph.json`` beside it when that has a ``floor`` fitted to
    points (``n_points`` > 0), else :data:`LEVEL_FLOOR`.

    Raises:
        DescriptionError: graph.json exists but is not JSON, or its ``floor`` lacks a finite ``height_m`` or a
            finite, non-zero 3-vector ``normal`` pointing up (more up than down), or is tilted 45 deg or more
            (names the file and the field; rebuild the scene with ``recon build``).
    """
    path = Path(scene_urdf).parent / FLOOR_FILE
    if not path.is_file():
        return LEVEL_FLOOR
    try:
        doc = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise DescriptionError(f"{path}: cannot read the scene graph beside {Path(scene_urdf).name} ({exc}); "
                               "rebuild it with `recon build` or remove it") from None
    floor = doc.get("floor") if isinstance(doc, dict) else None
    if not floor:
        return LEVEL_FLOOR
    fix = "rebuild the scene with `recon build` (or remove the \"floor\" entry: the floor is then z = 0)"
    if not isinstance(floor, dict):
        raise DescriptionError(f"{path}: field 'floor' must be an object with height_m and normal; {fix}")
    if int(floor.get("n_points", 1) or 0) <= 0:
        return LEVEL_FLOOR                       # recon found no floor points: the frame's z = 0 was assumed
    try:
        n = np.asarray(floor["normal"], dtype=np.float64).reshape(3)
        h = float(floor["height_m"])
    except (KeyError, TypeError, ValueError):
        raise DescriptionError(f"{path}: field 'floor' needs 'height_m' (m) and 'normal' (3 numbers); {fix}") from None
    norm = float(np.linalg.norm(n))
    if not (np.isfinite(n).all() and math.isfinite(h) and norm > 1e-9):
        raise DescriptionError(f"{path}: field 'floor' has a non-finite height_m or a zero or non-finite normal "
                               f"({floor.get('normal')}); {fix}")
    n = n / norm
    if n[2] <= math.cos(math.radians(45.0)):
        raise DescriptionError(f"{path}: field 'floor.normal' {np.round(n, 3).tolist()} is "
                               f"{math.degrees(math.acos(max(-1.0, min(1.0, n[2])))):.1f} deg off +z: the robot "
                               "cannot stand on it; rebuild the scene with `recon build --level-floor` (or remove the "
                               "\"floor\" entry: the floor is then z = 0)")
    return SceneFloor(tuple(float(v) for v in n), h, str(path))
