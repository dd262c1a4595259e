"""The object-level baseline the paper compares against ([9]): each scanned object replaced *whole* by the
best-fitting model of a small fixed library (the ``scenes`` generators' objects), scaled anisotropically
to the object's gravity-aligned oriented box; no parts, joints as the template has them. It reads the same
scans as :func:`recon.reconstruct` and produces the same :class:`recon.metrics.ObjectEstimate` per object,
so both methods are scored by the same :func:`recon.metrics.evaluate_scene`.

    from recon.baseline import object_level_from_files
    result = object_level_from_files("scan.ply", "labels.json", seed=0)     # BaselineResult
    result.objects      # BaselineObject per labelled object: status, reason, template, score, box, estimate
    result.estimates    # ObjectEstimate of every replaced object
"""

from recon.baseline.fit import (BaselineConfig, BaselineObject, BaselineResult, BaselineStatus, fit_object,
                                object_level_from_files, reconstruct_object_level)
from recon.baseline.placement import ScannedBox, TemplatePlacement, scanned_box, yaw_candidates
from recon.baseline.templates import (Template, TemplateLibrary, TemplatePart, library_from_generators,
                                      template_from_object)

__all__ = ["BaselineConfig", "BaselineObject", "BaselineResult", "BaselineStatus", "fit_object",
           "object_level_from_files", "reconstruct_object_level", "ScannedBox", "TemplatePlacement",
           "scanned_box", "yaw_candidates", "Template", "TemplateLibrary", "TemplatePart",
           "library_from_generators", "template_from_object"]
