"""recon.config: groups per stage, fields set by name, flat round trip, and the caller's config used."""

from __future__ import annotations

import ast
import dataclasses
import inspect

import pytest

import recon.config as config_module
from recon.config import ContactConfig, ReconConfig
from recon.metrics import estimate_from_reconstruction
from recon.pipeline import reconstruct_scan

def test_replace_sets_fields_of_any_group_and_leaves_the_rest():
    base = ReconConfig()
    cfg = base.replace(theta_d=0.01, refine=False, density=300.0)
    assert (cfg.contacts.theta_d, cfg.refinement.refine, cfg.urdf.density) == (0.01, False, 300.0)
    assert cfg.fitting == base.fitting and cfg.contacts.theta_a == base.contacts.theta_a
    assert base.contacts.theta_d == 0.025                        # frozen: the original is unchanged
    assert ReconConfig(contacts=ContactConfig(theta_d=0.01)).contacts == cfg.contacts
    # a group's name sets the whole group; ``walls`` is a group and its on/off field
    assert base.replace(clearance={"enabled": False}).clearance.enabled is False
    assert base.replace(walls=False).walls.walls is False
    assert base.replace(walls=dataclasses.replace(base.walls, wall_thickness=0.2)).walls.wall_thickness == 0.2

def test_unknown_field_names_are_refused_with_the_name():
    with pytest.raises(TypeError, match="'theta_x'"):
        ReconConfig().replace(theta_x=1.0)
    with pytest.raises(TypeError, match="'nope'"):
        ReconConfig.from_flat({"nope": 1})
    assert ReconConfig.from_flat({"nope": 1}, ignore_unknown=True) == ReconConfig()

def test_flat_round_trip_and_lists_become_tuples():
    cfg = ReconConfig().replace(theta_c=0.1, candidates=("box", "sphere"))
    flat = cfg.flat()
    groups = {g.name: getattr(cfg, g.name) for g in dataclasses.fields(ReconConfig)}
    names = {f.name for g, v in groups.items() if g not in config_module.NESTED for f in dataclasses.fields(v)}
    assert set(flat) == names | set(config_module.NESTED)
    assert flat["clearance"] == dataclasses.asdict(cfg.clearance)
    assert ReconConfig.from_flat(flat) == cfg
    assert ReconConfig.from_flat({**flat, "candidates": ["box", "sphere"]}) == cfg

def test_every_field_has_a_docstring():
    """Each group field is followed by a string saying what it means (and its unit)."""
    tree = ast.parse(inspect.getsource(config_module))
    for cls in (n for n in tree.body if isinstance(n, ast.ClassDef) and n.name != "ReconConfig"):
        body = cls.body
        for k, node in enumerate(body):
            if isinstance(node, ast.AnnAssign):
                nxt = body[k + 1] if k + 1 < len(body) else None
                assert isinstance(nxt, ast.Expr) and isinstance(nxt.value, ast.Constant) \
                    and isinstance(nxt.value.value, str), f"{cls.name}.{node.target.id} has no docstring"

def test_the_callers_config_reaches_the_stages_and_the_metrics(kitchen_scan, kitchen_rec):
    cfg = ReconConfig().replace(walls=False, template_shapes=False, handle_shapes=False, density=300.0,
                                clearance={"enabled": False})
    rec = reconstruct_scan(kitchen_scan[0], config=cfg, seed=0)
    assert rec.config == cfg and rec.walls == ()
    assert all(p.shapes == () for o in rec.objects for p in o.parts)
    # the metrics rank contacts with the reconstruction's own template prior
    scores = [{k: v for o in kitchen_rec.objects
               for k, v in estimate_from_reconstruction(o, kitchen_rec.config.replace(foreign_parent_penalty=w))
               .contact_scores.items()} for w in (0.0, 1.0)]
    foreign = [k for k in scores[1] if scores[0][k] != scores[1][k]]
    assert foreign and all(scores[0][k] == 0.0 for k in foreign)
