"""simcheck.bullet.c_output_logged: what C code writes to fd 1/2 inside the block is captured, block by
block (nested blocks and reused capture files included), and the terminal's descriptors come back."""

import os

import pytest

from simcheck.bullet import c_output_logged


def _write(fd: int, text: str) -> None:
    os.write(fd, text.encode())


def test_each_block_gets_only_its_own_output_even_nested_and_reused():
    for round_ in range(3):                 # later rounds reuse the capture files of the first
        with c_output_logged("outer") as outer:
            _write(1, f"out {round_}\n")
            with c_output_logged("inner") as inner:
                _write(2, "inner err\n")
            _write(2, "after\n")
        assert outer == [f"out {round_}\nafter"]
        assert inner == ["inner err"]
        with c_output_logged("short") as short:   # a shorter text than the file held before: no tail left over
            _write(1, "x")
        assert short == ["x"]


def test_the_descriptors_come_back_after_an_exception(capfd):
    with pytest.raises(RuntimeError):
        with c_output_logged("failing") as said:
            _write(1, "before the error\n")
            raise RuntimeError("boom")
    assert said == ["before the error"]
    _write(1, "to the terminal\n")
    assert "to the terminal" in capfd.readouterr().out


def test_a_forked_child_does_not_share_the_parents_capture_files():
    with c_output_logged("warm"):         # the parent now keeps a spare capture file
        _write(1, "parent\n")
    pid = os.fork()
    if pid == 0:                            # the child: its captures are its own
        with c_output_logged("child") as said:
            _write(1, "child\n")
        os._exit(0 if said == ["child"] else 1)
    with c_output_logged("parent") as said:
        _write(1, "parent again\n")
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0
    assert said == ["parent again"]
