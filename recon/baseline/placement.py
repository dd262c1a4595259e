"""Where the baseline puts a template: the scanned object's gravity-aligned oriented box, and the
anisotropic scaling that maps a template's bounds onto it.

Frames: ``T_world_box`` has its origin on the bottom face of the box at the footprint centre, z up,
x along one side of the footprint (for a placed template: its front normal). Units: metres, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from recon.model import JointEstimate
from recon.primitive import Primitive, PrimitiveKind

__all__ = ["ScannedBox", "scanned_box", "yaw_candidates", "TemplatePlacement"]

#: Fraction of points ignored at each end of every axis when measuring the box (outliers, label noise).
BOX_QUANTILE = 0.005


def _rz(yaw: float) -> np.ndarray:
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True, eq=False)
class ScannedBox:
    """A gravity-aligned oriented box. T_world_box : (4, 4) (bottom centre, yaw only); size : (3,) m."""

    T_world_box: np.ndarray
    size: np.ndarray

    @property
    def yaw(self) -> float:
        return float(np.arctan2(self.T_world_box[1, 0], self.T_world_box[0, 0]))


def scanned_box(points: np.ndarray, quantile: float = BOX_QUANTILE) -> ScannedBox:
    """The gravity-aligned box of an object's points: yaw from the minimum-area rectangle of the
    points' footprint (shapely), extents from the ``quantile`` / ``1 - quantile`` quantiles along the
    box axes (robust to a few outliers).

    points : (n, 3) float, world, metres, n >= 3 and not all on one vertical line
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    rect = shapely.minimum_rotated_rectangle(shapely.MultiPoint(p[:, :2]))
    corners = np.asarray(rect.exterior.coords)[:4] if rect.geom_type == "Polygon" else np.asarray(rect.coords)
    edge = corners[1] - corners[0] if len(corners) > 1 else np.array([1.0, 0.0])
    yaw = float(np.arctan2(edge[1], edge[0])) if np.linalg.norm(edge) > 0 else 0.0
    R = _rz(yaw)
    local = p @ R                                    # coordinates along the box axes (rotation only)
    lo = np.quantile(local, quantile, axis=0)
    hi = np.quantile(local, 1.0 - quantile, axis=0)
    size = np.maximum(hi - lo, 1e-3)
    centre = R @ np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]])
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = centre
    return ScannedBox(T, size)


def yaw_candidates(box: ScannedBox) -> tuple[ScannedBox, ...]:
    """The same box with its x axis turned by 0, 90, 180 and 270 degrees (extents swapped accordingly):
    which side is the front is not known from the footprint alone."""
    out = []
    for k in range(4):
        T = box.T_world_box.copy()
        T[:3, :3] = box.T_world_box[:3, :3] @ _rz(k * np.pi / 2)
        size = box.size[[1, 0, 2]] if k % 2 else box.size.copy()
        out.append(ScannedBox(T, size))
    return tuple(out)


@dataclass(frozen=True, eq=False)
class TemplatePlacement:
    """The affine map from a template's object frame onto a scanned box:

        p_world = T_world_box * ( scale * (p_template - anchor) )

    anchor : (3,) the template's bottom centre (bounds centre in x, y; bounds minimum in z)
    scale : (3,) per-axis scale, box size / template size
    """

    T_world_box: np.ndarray
    anchor: np.ndarray
    scale: np.ndarray

    @classmethod
    def onto(cls, template_bounds: np.ndarray, box: ScannedBox) -> "TemplatePlacement":
        lo, hi = np.asarray(template_bounds, dtype=np.float64)
        anchor = np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]])
        return cls(box.T_world_box, anchor, box.size / np.maximum(hi - lo, 1e-6))

    def points(self, p_template: np.ndarray) -> np.ndarray:
        """(n, 3) template-frame points -> (n, 3) world points."""
        q = (np.asarray(p_template, dtype=np.float64) - self.anchor) * self.scale
        return q @ self.T_world_box[:3, :3].T + self.T_world_box[:3, 3]

    def direction(self, d_template: np.ndarray) -> np.ndarray:
        """A template-frame direction -> the unit world direction of its image (a joint axis)."""
        v = self.T_world_box[:3, :3] @ (np.asarray(d_template, dtype=np.float64) * self.scale)
        return v / np.linalg.norm(v)

    def length_along(self, d_template: np.ndarray) -> float:
        """How much a unit length along a template-frame direction is stretched (a travel limit)."""
        d = np.asarray(d_template, dtype=np.float64)
        return float(np.linalg.norm(d / np.linalg.norm(d) * self.scale))

    def primitive(self, prim: Primitive) -> Primitive:
        """The template primitive scaled and placed: centre mapped by the affine map; each local axis
        keeps its direction and its extent is stretched by the scale along it (exact for boxes and
        cylinders aligned with the template's axes, which the generators' are); a cylinder's radius
        takes the geometric mean of the stretches across its axis, a sphere's the mean of all three."""
        R = prim.T_world_part[:3, :3]
        stretch = np.linalg.norm(self.scale[:, None] * R, axis=0)     # stretch of each local axis
        size = prim.size * stretch
        if prim.kind is PrimitiveKind.CYLINDER:
            r = np.sqrt(stretch[0] * stretch[1]) * prim.size[0]
            size = np.array([r, r, size[2]])
        elif prim.kind is PrimitiveKind.SPHERE:
            size = np.full(3, prim.size[0] * float(np.cbrt(np.prod(stretch))))
        T = np.eye(4)
        T[:3, :3] = self.T_world_box[:3, :3] @ R
        T[:3, 3] = self.points(prim.T_world_part[:3, 3][None])[0]
        return Primitive(prim.kind, size, T)

    def joint(self, j: JointEstimate, name: str, parent: int, child: int,
              handle: int | None) -> JointEstimate:
        """A template joint carried onto the scan's part ids (axis, origin and travel mapped)."""
        stretch = self.length_along(j.axis) if j.type.value == "prismatic" else 1.0
        return JointEstimate(name, j.type, parent, child, self.direction(j.axis) if j.type.value != "fixed"
                             else np.zeros(3), self.points(np.asarray(j.origin)[None])[0], j.lower * stretch,
                             j.upper * stretch, handle_part_id=handle)
