"""Primitive shapes (box, cylinder, sphere) posed in the world: volume, inertia, surface samples,
distance of points to the surface, and their surface planes Π (Sec. II of the paper).

A primitive's frame is centred on the shape. ``size`` is always a (3,) float64 extent in that frame:

    box       (sx, sy, sz)            full edge lengths
    cylinder  (2r, 2r, length)        axis along the local z
    sphere    (2r, 2r, 2r)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from scenes.description import ShapeKind, SolidProperties

__all__ = ["PrimitiveKind", "Primitive", "SurfacePlane", "volume_weighted_centre"]


PrimitiveKind = ShapeKind
"""The primitive templates of Eq. 3 are :class:`scenes.description.ShapeKind` box, cylinder and sphere."""


@dataclass(frozen=True, eq=False)
class SurfacePlane:
    """A surface plane π = [n, d] with its outline polygon U (Sec. II): n·u + d = 0 on the plane.

    normal : (3,) float, unit, world frame, pointing out of the primitive
    d : float, metres
    polygon : (k, 3) float, world frame, metres, the outline's vertices in order
    """

    normal: np.ndarray
    d: float
    polygon: np.ndarray

    def transformed(self, T_new_world: np.ndarray) -> "SurfacePlane":
        """The same plane moved rigidly by ``T_new_world`` (4, 4)."""
        R, t = T_new_world[:3, :3], T_new_world[:3, 3]
        n = R @ self.normal
        return SurfacePlane(n, float(self.d - n @ t), self.polygon @ R.T + t)

    def isclose(self, other: "SurfacePlane", atol: float = 1e-6) -> bool:
        return (np.allclose(self.normal, other.normal, atol=atol) and abs(self.d - other.d) <= atol
                and self.polygon.shape == other.polygon.shape
                and np.allclose(self.polygon, other.polygon, atol=atol))


def volume_weighted_centre(primitives) -> np.ndarray:
    """(3,) float, metres, in the primitives' frame: the mean of their centres weighted by their volumes."""
    w = np.array([p.volume for p in primitives])
    c = np.array([p.T_world_part[:3, 3] for p in primitives])
    return (w[:, None] * c).sum(axis=0) / w.sum()


def _check_pose(T: np.ndarray, what: str) -> np.ndarray:
    T = np.asarray(T, dtype=np.float64)
    if T.shape != (4, 4):
        raise ValueError(f"{what} must be a (4, 4) pose, got shape {T.shape}")
    return T


@dataclass(frozen=True, eq=False)
class Primitive(SolidProperties):
    """A primitive shape posed in the world.

    kind : PrimitiveKind
    size : (3,) float, metres (see the module docstring for each kind)
    T_world_part : (4, 4) float, pose of the shape's centre frame in the world
    """

    kind: PrimitiveKind
    size: np.ndarray
    T_world_part: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "kind", PrimitiveKind(self.kind))
        size = np.asarray(self.size, dtype=np.float64).reshape(3)
        if not np.all(np.isfinite(size)) or np.any(size <= 0):
            raise ValueError(f"primitive size must be positive and finite, got {size}")
        object.__setattr__(self, "size", size)
        object.__setattr__(self, "T_world_part", _check_pose(self.T_world_part, "T_world_part"))

    # ----- scalar properties (radius, length, volume, inertia: SolidProperties) -----
    @property
    def center(self) -> np.ndarray:
        """(3,) world position of the shape's centre."""
        return self.T_world_part[:3, 3].copy()

    def transformed(self, T_new_world: np.ndarray) -> "Primitive":
        """The same shape moved rigidly by ``T_new_world`` (4, 4)."""
        return Primitive(self.kind, self.size, _check_pose(T_new_world, "T") @ self.T_world_part)

    def shrunk(self, margin: float, minimum: float = 1e-3) -> "Primitive":
        """The shape with every face moved inward by ``margin`` (m), extents floored at ``minimum``."""
        return Primitive(self.kind, np.maximum(self.size - 2.0 * margin, minimum), self.T_world_part)

    def with_pose(self, T_world_part: np.ndarray) -> "Primitive":
        return Primitive(self.kind, self.size, T_world_part)

    def isclose(self, other: "Primitive", atol: float = 1e-6) -> bool:
        return (self.kind is other.kind and np.allclose(self.size, other.size, atol=atol)
                and np.allclose(self.T_world_part, other.T_world_part, atol=atol))

    # ----- geometry -----
    def corners(self) -> np.ndarray:
        """(8, 3) world corners of the shape's bounding box in its own frame."""
        h = self.size / 2.0
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)
        return self.to_world(signs * h)

    def to_world(self, p_part: np.ndarray) -> np.ndarray:
        """(n, 3) part-frame points -> world."""
        return p_part @ self.T_world_part[:3, :3].T + self.T_world_part[:3, 3]

    def to_part(self, p_world: np.ndarray) -> np.ndarray:
        """(n, 3) world points -> part frame."""
        return (np.asarray(p_world, float) - self.T_world_part[:3, 3]) @ self.T_world_part[:3, :3]

    def contains(self, p_world: np.ndarray) -> np.ndarray:
        """(n,) bool: which world points lie inside the (closed) shape."""
        q = self.to_part(p_world)
        h = self.size / 2.0
        if self.kind is PrimitiveKind.BOX:
            return np.all(np.abs(q) <= h, axis=1)
        if self.kind is PrimitiveKind.CYLINDER:
            return (np.hypot(q[:, 0], q[:, 1]) <= self.radius) & (np.abs(q[:, 2]) <= h[2])
        return np.linalg.norm(q, axis=1) <= h[0]

    def surface_distance(self, p_world: np.ndarray) -> np.ndarray:
        """(n,) unsigned distance (m) from world points to the shape's surface (closed form)."""
        q = self.to_part(p_world)
        h = self.size / 2.0
        if self.kind is PrimitiveKind.BOX:
            return np.abs(_box_sdf(q, h))
        if self.kind is PrimitiveKind.CYLINDER:
            rho = np.hypot(q[:, 0], q[:, 1])
            q2 = np.stack([rho, q[:, 2]], axis=1)
            return np.abs(_box_sdf(q2, np.array([self.radius, h[2]])))
        return np.abs(np.linalg.norm(q, axis=1) - h[0])

    def sample_surface(self, n: int, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """Evenly (area-weighted) sampled surface points, h(M) of Eq. 3.

        Returns ``(points, face)``: (n, 3) float world points and (n,) int face index. Faces are
        the box's 6 sides (±x, ±y, ±z), the cylinder's 2 caps then 4 side quadrants, and the
        sphere's 8 octants; the index lets the fit tell observed faces from unobserved ones.
        """
        h = self.size / 2.0
        if self.kind is PrimitiveKind.BOX:
            areas = np.array([4 * h[1] * h[2], 4 * h[0] * h[2], 4 * h[0] * h[1]]).repeat(2)
            face = rng.choice(6, size=n, p=areas / areas.sum())
            q = rng.uniform(-1.0, 1.0, size=(n, 3)) * h
            axis = face // 2
            q[np.arange(n), axis] = np.where(face % 2 == 0, -1.0, 1.0) * h[axis]
        elif self.kind is PrimitiveKind.CYLINDER:
            r = self.radius
            areas = np.array([np.pi * r**2, np.pi * r**2, 2 * np.pi * r * self.length])
            kind = rng.choice(3, size=n, p=areas / areas.sum())
            phi = rng.uniform(0.0, 2 * np.pi, size=n)
            rad = np.where(kind < 2, r * np.sqrt(rng.uniform(0.0, 1.0, size=n)), r)
            z = np.where(kind == 0, -h[2], np.where(kind == 1, h[2], rng.uniform(-h[2], h[2], size=n)))
            q = np.stack([rad * np.cos(phi), rad * np.sin(phi), z], axis=1)
            face = np.where(kind < 2, kind, 2 + (phi // (np.pi / 2)).astype(int) % 4)
        else:
            v = rng.normal(size=(n, 3))
            q = v / np.linalg.norm(v, axis=1, keepdims=True) * h[0]
            face = (q[:, 0] > 0) * 4 + (q[:, 1] > 0) * 2 + (q[:, 2] > 0)
        return self.to_world(q), face.astype(int)

    def planes(self, cylinder_side_faces: int = 8) -> tuple[SurfacePlane, ...]:
        """The surface planes Π of the shape, exact faces, normals outward (world frame).

        Box: 6 rectangles. Cylinder: 2 cap polygons (``2 * cylinder_side_faces`` vertices) and
        ``cylinder_side_faces`` tangent rectangles standing for the curved side. Sphere: 6 tangent
        squares of side r (a sphere touches a plane in a patch only through noise).
        """
        h = self.size / 2.0
        R, t = self.T_world_part[:3, :3], self.T_world_part[:3, 3]
        out = []

        def add(n_part, poly_part):
            n = R @ n_part
            poly = poly_part @ R.T + t
            out.append(SurfacePlane(n, float(-n @ poly[0]), poly))

        if self.kind is PrimitiveKind.BOX:
            for axis in range(3):
                u, v = (axis + 1) % 3, (axis + 2) % 3
                for sign in (-1.0, 1.0):
                    n_part = np.zeros(3)
                    n_part[axis] = sign
                    quad = np.zeros((4, 3))
                    quad[:, axis] = sign * h[axis]
                    quad[:, u] = np.array([-1, 1, 1, -1]) * h[u]
                    quad[:, v] = np.array([-1, -1, 1, 1]) * h[v] * sign  # counter-clockwise seen from outside
                    add(n_part, quad)
        elif self.kind is PrimitiveKind.CYLINDER:
            r, k = self.radius, int(cylinder_side_faces)
            ang = np.linspace(0.0, 2 * np.pi, 2 * k, endpoint=False)
            ring = np.stack([r * np.cos(ang), r * np.sin(ang), np.zeros_like(ang)], axis=1)
            for sign in (-1.0, 1.0):
                cap = ring.copy()
                cap[:, 2] = sign * h[2]
                add(np.array([0.0, 0.0, sign]), cap if sign > 0 else cap[::-1])
            half = r * np.tan(np.pi / k)
            for i in range(k):
                a = 2 * np.pi * i / k
                n_part = np.array([np.cos(a), np.sin(a), 0.0])
                tang = np.array([-np.sin(a), np.cos(a), 0.0])
                c = r * n_part
                quad = np.array([c - half * tang + [0, 0, -h[2]], c + half * tang + [0, 0, -h[2]],
                                 c + half * tang + [0, 0, h[2]], c - half * tang + [0, 0, h[2]]])
                add(n_part, quad)
        else:
            r = h[0]
            for axis in range(3):
                u, v = (axis + 1) % 3, (axis + 2) % 3
                for sign in (-1.0, 1.0):
                    n_part = np.zeros(3)
                    n_part[axis] = sign
                    quad = np.zeros((4, 3))
                    quad[:, axis] = sign * r
                    quad[:, u] = np.array([-1, 1, 1, -1]) * r / 2
                    quad[:, v] = np.array([-1, -1, 1, 1]) * r / 2 * sign
                    add(n_part, quad)
        return tuple(out)

    def to_trimesh(self):
        """A ``trimesh.Trimesh`` of the shape in the world frame (for metrics and previews)."""
        import trimesh

        if self.kind is PrimitiveKind.BOX:
            return trimesh.creation.box(extents=self.size, transform=self.T_world_part)
        if self.kind is PrimitiveKind.CYLINDER:
            return trimesh.creation.cylinder(radius=self.radius, height=self.length,
                                             transform=self.T_world_part, sections=32)
        m = trimesh.creation.icosphere(subdivisions=3, radius=self.size[0] / 2.0)
        m.apply_transform(self.T_world_part)
        return m


def _box_sdf(q: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Signed distance of (n, k) points to an origin-centred box of half extents (k,)."""
    d = np.abs(q) - h
    outside = np.linalg.norm(np.maximum(d, 0.0), axis=1)
    inside = np.minimum(d.max(axis=1), 0.0)
    return outside + inside
