"""The shared progress bar: on stderr, silent when quiet or when stderr is not a terminal."""
import io
import sys

import pytest

from exudyn_worm.progress import ProgressBar, ProgressEnabled


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def _Run(quiet, stream, monkeypatch):
    monkeypatch.setattr(sys, 'stderr', stream)
    with ProgressBar(total=4, desc='work', unit='case', quiet=quiet) as bar:
        for _ in range(4):
            bar.update(1)
    return stream.getvalue()


def test_drawn_on_a_terminal(monkeypatch):
    text = _Run(None, _Terminal(), monkeypatch)
    assert 'work' in text and '4/4' in text and 'case' in text


@pytest.mark.parametrize('quiet, stream', [(None, io.StringIO()), (True, _Terminal())], ids=['not-a-tty', 'quiet'])
def test_silent(quiet, stream, monkeypatch):
    assert _Run(quiet, stream, monkeypatch) == ''


def test_forced_on_and_stdout_untouched(monkeypatch, capsys):
    text = _Run(False, io.StringIO(), monkeypatch)
    assert '4/4' in text and capsys.readouterr().out == ''


def test_enabled_rule(monkeypatch):
    monkeypatch.setattr(sys, 'stderr', io.StringIO())
    assert ProgressEnabled(None) is False and ProgressEnabled(False) is True and ProgressEnabled(True) is False
