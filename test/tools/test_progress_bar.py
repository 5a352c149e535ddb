#!/usr/bin/python3
"""scripts/progress_bar.py (issue 53): the calibration and fragility scripts' tqdm bar is drawn only
when stderr is a terminal and not --quiet. Off a terminal nothing is written; on a pseudo-terminal
(os.openpty) the bar reaches done/total. Only the counts are checked, never a rate or a time."""
import io
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from progress_bar import add_quiet_flag, progress_bar  # noqa: E402


def read_all(master):
    """Everything the pty holds once its writer has closed. One os.read returns only what has
    arrived so far (CI saw the first redraw alone), so read until the pty reports its end
    (EIO on Linux once the slave is closed and drained)."""
    chunks = []
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:
            break
        if not chunk:
            break
        chunks.append(chunk)
    return b"".join(chunks).decode()


def draw(stream, quiet=False):
    """Runs a 3-step bar with sys.stderr set to stream."""
    old = sys.stderr
    sys.stderr = stream
    try:
        with progress_bar(3, "demo: members", quiet=quiet) as bar:
            for _ in range(3):
                bar.update(1)
    finally:
        sys.stderr = old


class ProgressBar(unittest.TestCase):
    def test_off_a_terminal_nothing_is_written(self):
        stream = io.StringIO()  # a pipe, a log: not a terminal
        draw(stream)
        self.assertEqual(stream.getvalue(), "")

    def test_on_a_terminal_the_bar_reaches_done_over_total(self):
        master, slave = os.openpty()
        try:
            with open(slave, "w", closefd=True) as tty:
                draw(tty)
            text = read_all(master)
        finally:
            os.close(master)
        self.assertIn("demo: members", text)
        self.assertIn("3/3", text)

    def test_quiet_on_a_terminal_writes_nothing(self):
        master, slave = os.openpty()
        try:
            with open(slave, "w", closefd=True) as tty:
                draw(tty, quiet=True)
                tty.write("end\n")
            text = read_all(master)
        finally:
            os.close(master)
        self.assertEqual(text.strip(), "end")

    def test_quiet_flag(self):
        import argparse
        ap = argparse.ArgumentParser()
        add_quiet_flag(ap)
        self.assertTrue(ap.parse_args(["--quiet"]).quiet)
        self.assertFalse(ap.parse_args([]).quiet)


if __name__ == "__main__":
    unittest.main()
