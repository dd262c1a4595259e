"""report.html: one self-contained page that tells the story of a demo run.

scan coloured by part -> reconstruction beside truth -> each object's part tree with its joints ->
reconstruction metrics -> per task the robot opening (key frames, joint opening over time against the
plan) and every certificate criterion with its value, threshold and margin.

    from simcheck.report import render_report
    render_report("out/demo")            # -> out/demo/report.html

Figures are matplotlib (Agg) PNGs inlined as data URIs; numbers carry ``data-key`` attributes naming
their source (``metrics.<path>``, ``cert.<task>.<criterion>.<field>``).
"""

from ._errors import ArtifactError, ReportError
from ._layout import DemoLayout
from ._render import render_report

__all__ = ["render_report", "DemoLayout", "ReportError", "ArtifactError"]
