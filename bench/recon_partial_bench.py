"""Partial views of single shapes through recon: ``python -m bench.recon_partial_bench [--seeds N]``.

Issue 12, item 2. Each case is one primitive (a one-part object with no floor points) whose scan shows
only some of its faces: ``n`` points sampled uniformly (by area) on the faces seen from one corner
(``faces`` = 1, 2 or 3 of the box's faces; for a cylinder its seen half side and one cap), isotropic
Gaussian noise of ``sigma`` metres, a random pose (a rotation drawn uniformly from SO(3) and a random
position, the shape's lowest point above the floor, so that no stage moves it). For every seed the shape
is fitted alone (:func:`recon.fitting.fit_part`) and through the whole pipeline
(:func:`recon.pipeline.reconstruct_scan`), and the volumetric IoU of the fit with the true shape is
printed (min / median over the seeds) with the fitted kind and extents.
"""

from __future__ import annotations

import argparse
import sys
from typing import NamedTuple

import numpy as np
from scipy.spatial.transform import Rotation

from recon.primitive import Primitive, PrimitiveKind

__all__ = ["PartialCase", "CASES", "partial_view_points", "partial_view_scan", "primitive_iou", "main"]


class PartialCase(NamedTuple):
    """One shape of the issue: its category, part label, kind, size (see recon.primitive) and seen faces."""

    name: str
    category: str
    label: str
    kind: str
    size: tuple[float, float, float]
    faces: int


CASES = (
    PartialCase("cube 0.5 m, 3 faces", "cabinet", "body", "box", (0.5, 0.5, 0.5), 3),
    PartialCase("cube 0.5 m, 2 faces", "cabinet", "body", "box", (0.5, 0.5, 0.5), 2),
    PartialCase("cube 0.5 m, 1 face", "cabinet", "body", "box", (0.5, 0.5, 0.5), 1),
    PartialCase("board 0.6 x 0.4 x 0.02 m, 3 faces", "table", "top", "box", (0.6, 0.4, 0.02), 3),
    PartialCase("cylinder 0.03 x 0.7 m, half side + cap", "table", "leg", "cylinder", (0.03, 0.03, 0.7), 3),
)


def partial_view_points(case: PartialCase, seed: int, n: int = 2000, sigma: float = 0.003
                        ) -> tuple[Primitive, np.ndarray, np.ndarray]:
    """(true primitive, (n, 3) noisy world points on its seen faces, (n, 3) their outward unit normals
    as a scanner gives them: the true surface's) for ``case`` and ``seed``.

    Box: the faces -z, then -x, then -y of the box's frame (the first ``faces`` of them; one corner's
    faces). Cylinder: the half of its side facing -x and its -z cap. Then the random pose.
    """
    rng = np.random.default_rng(seed)
    T = np.eye(4)
    T[:3, :3] = Rotation.random(random_state=rng.integers(1 << 31)).as_matrix()
    true0 = Primitive(case.kind, case.size, np.eye(4))
    samples, face = true0.sample_surface(40 * n, rng)
    if case.kind == "box":
        keep = np.isin(face, (4, 0, 2)[:case.faces])      # face index = 2 * axis + (side > 0)
        nrm = np.eye(3)[face // 2] * np.where(face % 2 == 1, 1.0, -1.0)[:, None]
    else:
        keep = (face == 0) | ((face >= 2) & (samples[:, 0] < 0))
        radial = samples * [1.0, 1.0, 0.0]
        nrm = np.where((face == 0)[:, None], [0.0, 0.0, -1.0],
                       radial / np.maximum(np.linalg.norm(radial, axis=1, keepdims=True), 1e-12))
    idx = rng.choice(np.flatnonzero(keep), n, replace=False)
    pts = samples[idx] + rng.normal(0.0, sigma, (n, 3))
    nrm = nrm[idx]
    low = float(np.min((true0.corners() @ T[:3, :3].T)[:, 2]))
    T[:3, 3] = [rng.uniform(-2, 2), rng.uniform(-2, 2), 0.5 - low + rng.uniform(0, 0.5)]
    true = true0.transformed(T)
    return true, pts @ T[:3, :3].T + T[:3, 3], nrm @ T[:3, :3].T


def partial_view_scan(case: PartialCase, seed: int, n: int = 2000, sigma: float = 0.003):
    """(true primitive, :class:`recon.scan.Scan`) of ``case``: one object (id 1) with one part (id 10)."""
    from recon.scan import scan_from_arrays

    true, pts, nrm = partial_view_points(case, seed, n, sigma)
    props = {"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2], "nx": nrm[:, 0], "ny": nrm[:, 1], "nz": nrm[:, 2],
             "object_id": np.ones(len(pts), int), "part_id": np.full(len(pts), 10)}
    labels = [{"id": 1, "category": case.category, "parts": [{"id": 10, "label": case.label}]}]
    return true, scan_from_arrays(props, labels)


def primitive_iou(a: Primitive, b: Primitive, n: int = 200_000, seed: int = 0) -> float:
    """Volumetric IoU of two primitives: their intersection estimated from ``n`` uniform samples inside
    each (the mean of the two estimates), over the union of their exact volumes."""
    rng = np.random.default_rng(seed)

    def inside(p: Primitive) -> np.ndarray:
        q = rng.uniform(-0.5, 0.5, (n, 3)) * p.size
        if p.kind is not PrimitiveKind.BOX:        # rejection from the bounding box
            q = q[p.contains(p.to_world(q))]
        return p.to_world(q)

    inter = 0.5 * (a.volume * b.contains(inside(a)).mean() + b.volume * a.contains(inside(b)).mean())
    return float(inter / (a.volume + b.volume - inter))


def run(case: PartialCase, seed: int) -> tuple[float, str, np.ndarray, float, str, np.ndarray, tuple]:
    """(IoU alone, kind, size, IoU through the pipeline, kind, size, warnings) for one seed."""
    from recon.config import ReconConfig
    from recon.fitting import fit_part
    from recon.pipeline import reconstruct_scan

    true, scan = partial_view_scan(case, seed)
    part = scan.objects[0].parts[0]
    _, alone, _, _ = fit_part(part.points, ReconConfig().fitting, seed=seed, normals=part.normals)
    rec = reconstruct_scan(scan, seed=seed)
    piped = rec.objects[0].parts[0].primitive
    return (primitive_iou(true, alone), alone.kind.value, alone.size, primitive_iou(true, piped),
            piped.kind.value, piped.size, rec.warnings)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.recon_partial_bench", description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1 (each a new pose and new points)")
    ap.add_argument("--case", default=None, help="only the cases whose name contains this")
    ap.add_argument("-v", "--verbose", action="store_true", help="one line per seed")
    args = ap.parse_args(argv)
    print(f"{'case':42s} {'alone min/med':>14s} {'pipeline min/med':>17s}  kinds (pipeline)")
    for case in CASES:
        if args.case and args.case not in case.name:
            continue
        rows = [run(case, s) for s in range(args.seeds)]
        a = np.array([r[0] for r in rows])
        p = np.array([r[3] for r in rows])
        kinds = {k: sum(r[4] == k for r in rows) for k in sorted({r[4] for r in rows})}
        print(f"{case.name:42s} {a.min():6.3f}/{np.median(a):6.3f} {p.min():8.3f}/{np.median(p):7.3f}  {kinds}")
        if args.verbose:
            for s, r in enumerate(rows):
                print(f"   seed {s}: alone {r[0]:.3f} {r[1]} {np.round(r[2], 3)}  pipeline {r[3]:.3f} {r[4]} "
                      f"{np.round(r[5], 3)}  {len(r[6])} warnings")
    return 0


if __name__ == "__main__":
    sys.exit(main())
