"""Where each artifact of a demo directory lives (written by :mod:`simcheck.demo`, read by the report).

::

    DEMO_DIR/
      truth/            truth.urdf, truth.json, scan.ply, scan.npz, labels.json (scenes.make_scene)
      scene.urdf        the reconstruction (recon)
      graph.json        its contact graph and part trees (recon)
      metrics.json      reconstruction metrics against truth.json (recon.metrics)
      certificate.json  one entry per task, planned on scene.urdf, executed on truth/truth.urdf (simcheck)
      rollouts/         the recorded executions simcheck saved, one file per task
      demo.json         the pipeline log: each stage's status, seconds and message
      report.html       this renderer's output
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["DemoLayout"]


@dataclass(frozen=True)
class DemoLayout:
    """Paths of the artifacts of one demo directory ``root``."""

    root: Path

    @property
    def truth_dir(self) -> Path:
        return self.root / "truth"

    @property
    def truth_json(self) -> Path:
        return self.truth_dir / "truth.json"

    @property
    def truth_urdf(self) -> Path:
        return self.truth_dir / "truth.urdf"

    @property
    def scan_ply(self) -> Path:
        return self.truth_dir / "scan.ply"

    @property
    def scan_npz(self) -> Path:
        return self.truth_dir / "scan.npz"

    @property
    def labels_json(self) -> Path:
        return self.truth_dir / "labels.json"

    @property
    def scene_urdf(self) -> Path:
        return self.root / "scene.urdf"

    @property
    def graph_json(self) -> Path:
        return self.root / "graph.json"

    @property
    def metrics_json(self) -> Path:
        return self.root / "metrics.json"

    @property
    def certificate_json(self) -> Path:
        return self.root / "certificate.json"

    @property
    def rollouts_dir(self) -> Path:
        return self.root / "rollouts"

    @property
    def demo_json(self) -> Path:
        return self.root / "demo.json"

    @property
    def report_html(self) -> Path:
        return self.root / "report.html"
