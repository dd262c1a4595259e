"""scenes.outcome: the task outcome vocabulary and the exit code of a run."""

import logging

import pytest

from scenes.outcome import Outcome, exit_code, internal_error

O = Outcome


def test_values_are_the_lowercase_strings_written_to_certificates():
    assert [o.value for o in Outcome] == ["certified", "failed", "not_planned", "unreachable", "unusable",
                                          "error", "timeout"]
    assert Outcome("not_planned") is O.NOT_PLANNED and str(O.CERTIFIED) == "certified"


def test_the_old_hyphenated_spelling_reads_as_not_planned():
    assert Outcome("not-planned") is O.NOT_PLANNED
    with pytest.raises(ValueError, match="maybe"):
        Outcome("maybe")


@pytest.mark.parametrize("outcomes, code", [
    ([], 0),
    ([O.CERTIFIED, O.CERTIFIED], 0),
    ([O.CERTIFIED, O.FAILED], 1),
    ([O.NOT_PLANNED], 1),
    ([O.UNREACHABLE, O.CERTIFIED], 1),
    ([O.TIMEOUT], 1),
    ([O.FAILED, O.UNUSABLE], 2),
    ([O.ERROR, O.UNUSABLE], 2),
    ([O.CERTIFIED, O.ERROR, O.FAILED], 3),
    (["certified", "failed"], 1),
])
def test_exit_code_table(outcomes, code):
    assert exit_code(outcomes) == code


def test_internal_error_is_one_line_and_logs_the_traceback(capsys, caplog):
    try:
        raise KeyError("link 'base'")
    except KeyError as exc:
        with caplog.at_level(logging.INFO, logger="prog"):
            assert internal_error("prog", "reading scene.urdf", exc) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "prog: internal error while reading scene.urdf: KeyError" in err
    assert "Traceback" not in err
    assert caplog.records and caplog.records[0].exc_info is not None
