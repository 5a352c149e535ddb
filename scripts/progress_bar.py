"""progress_bar: done/total, rate and time left on stderr for the calibration and fragility scripts'
long loops of rocking_experiments runs (issue 53), drawn by tqdm (python3-tqdm).

Only on a terminal: a log, a pipe, ctest or a Slurm job gets nothing, so what those record stays as it
was; --quiet turns it off on a terminal too. It writes to stderr only: stdout and the written files
are byte-identical with or without it.
"""
import sys


class _NoBar:
    """What the loops call when nothing is shown (not a terminal, or --quiet)."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def update(self, n=1):
        pass

    def set_postfix_str(self, s=""):
        pass

    def close(self):
        pass


def add_quiet_flag(ap):
    ap.add_argument("--quiet", action="store_true", help="no progress bar on a terminal (never one off it)")


def progress_bar(total, desc, quiet=False, unit="run"):
    """A context manager with update(n) and close(): a tqdm bar on a terminal's stderr, else one that draws nothing."""
    if quiet or not sys.stderr.isatty():
        return _NoBar()
    # imported only when a bar is drawn: off a terminal the scripts do not need python3-tqdm at all
    from tqdm import tqdm
    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, dynamic_ncols=True)
