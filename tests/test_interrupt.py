"""Ctrl-C and SIGTERM recorded (``flexbeam.interrupt``): a sweep raises them between batches, a run that keeps what it
computed ends at its next step boundary.

SIGTERM used to raise wherever it landed: inside a history's NetCDF write it could leave xarray's file lock taken,
and the store's next write waited for it forever -- ``flexbeam sweep --histories`` hung on ``kill`` (found by an
exploratory run: 3 of 3 hung; 1 of 2 here before the change, 0 of 3 after).
"""

from __future__ import annotations

import os
import signal

import pytest

from flexbeam.interrupt import ctrl_c_flag


class _Terminated(BaseException):
    pass


def _raise_terminated(signum, frame):
    raise _Terminated


@pytest.fixture
def term_handler():
    """SIGTERM raising, as the CLI's sigterm_as_interrupt makes it; Ctrl-C Python's default (a suite started in the
    background, ``cmd &`` or nohup, inherits SIGINT ignored)."""
    term = signal.signal(signal.SIGTERM, _raise_terminated)
    ctrl_c = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, term)
        signal.signal(signal.SIGINT, ctrl_c)


def test_sigterm_is_recorded_inside_and_raised_by_its_handler_when_delivered(term_handler):
    with ctrl_c_flag() as hit:
        assert not hit
        os.kill(os.getpid(), signal.SIGTERM)  # (delivered at once to the main thread: no exception here)
        os.kill(os.getpid(), signal.SIGINT)  # the first signal is the one kept
        assert hit and hit.signum == signal.SIGTERM
        with pytest.raises(_Terminated):
            hit.deliver()
    assert signal.getsignal(signal.SIGTERM) is _raise_terminated  # restored
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_ctrl_c_is_recorded_and_delivered_as_keyboard_interrupt(term_handler):
    with ctrl_c_flag() as hit:
        os.kill(os.getpid(), signal.SIGINT)
        assert hit.signum == signal.SIGINT
        with pytest.raises(KeyboardInterrupt):
            hit.deliver()


def test_sigterm_keeps_its_default_action_where_no_python_handler_takes_it():
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
    with ctrl_c_flag():
        assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL


def test_a_sigterm_handler_that_returns_lets_the_sweep_go_on():
    seen = []
    previous = signal.signal(signal.SIGTERM, lambda s, f: seen.append(s))
    try:
        with ctrl_c_flag() as hit:
            os.kill(os.getpid(), signal.SIGTERM)
            assert hit and seen == []  # recorded, not yet handled
            hit.deliver()  # the handler runs, returns: no exception, the flag cleared
            assert seen == [signal.SIGTERM] and not hit
    finally:
        signal.signal(signal.SIGTERM, previous)


def test_a_second_signal_goes_to_its_handler_at_once_when_asked(term_handler):
    """``second_raises`` (a run that keeps what it computed, ``--keep-interrupted``): the first Ctrl-C is recorded,
    the second raises KeyboardInterrupt where it lands -- a run inside a long compiled call or a slow output is
    stopped by a user who presses twice; the first SIGTERM is recorded, the second goes to the CLI's handler."""
    with ctrl_c_flag(second_raises=True) as hit:
        os.kill(os.getpid(), signal.SIGINT)
        assert hit.signum == signal.SIGINT and hit.cause() == "Ctrl-C"
        with pytest.raises(KeyboardInterrupt):
            os.kill(os.getpid(), signal.SIGINT)
    with ctrl_c_flag(second_raises=True) as hit:
        os.kill(os.getpid(), signal.SIGTERM)
        assert hit.cause() == "SIGTERM"
        with pytest.raises(_Terminated):
            os.kill(os.getpid(), signal.SIGTERM)
    with ctrl_c_flag() as hit:  # (a sweep's: the second is recorded too, and raised between batches)
        os.kill(os.getpid(), signal.SIGINT)
        os.kill(os.getpid(), signal.SIGINT)
        assert hit.signum == signal.SIGINT
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
