"""Every command line turns an unexpected exception into exit code 3 and one line naming what failed;
``-v`` logs the traceback (scenes.outcome.internal_error)."""

import logging

import pytest

import recon.cli
import scenes.cli
import simcheck.cli
import simcheck.run  # noqa: F401 - imported before the patches, so its `from ... import` names stay real


def _boom(*args, **kwargs):
    raise RuntimeError("boom\nsecond line")


@pytest.mark.parametrize("main, module, name, argv, what", [
    (scenes.cli.main, "scenes.api", "make_scene", ["make", "kitchen", "--out", "OUT"], "running scenes make"),
    (recon.cli.main, "recon.scan", "read_scan", ["build", "s.ply", "--labels", "l.json", "--out", "OUT"],
     "reconstructing s.ply"),
    (simcheck.cli.main, "simcheck.certification", "certify",
     ["certify", "scene.urdf", "--task", "open-drawer:j", "--out", "OUT"], "certifying scene.urdf"),
])
def test_an_unexpected_exception_exits_3_with_one_line(main, module, name, argv, what, monkeypatch, capsys,
                                                       caplog, tmp_path):
    import importlib
    monkeypatch.setattr(importlib.import_module(module), name, _boom)
    if main is simcheck.cli.main:
        monkeypatch.setattr(importlib.import_module("simcheck.robot_spec_file"), "load_robot_spec", lambda s: None)
    argv = [str(tmp_path / "o") if a == "OUT" else a for a in argv]
    with caplog.at_level(logging.INFO):
        assert main(argv + ["-v"]) == 3
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if "internal error" in ln]
    assert lines == [f"{lines[0].split(':')[0]}: internal error while {what}: RuntimeError: boom "
                     "(run with -v for the traceback)"]
    assert any(r.exc_info for r in caplog.records)
