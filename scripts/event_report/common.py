"""event_report.common: the report's constants (the monitor's modes, alarm levels and causes, thresholds) and
its one error type; every other module of the package imports from here."""

G = 9.80665
MODES = ['REST', 'ROCKING', 'BEYOND_TIPPING', 'COMMITTED', 'OVERTURNED']
LEVELS = {2: 'BEYOND_TIPPING', 3: 'COMMITTED', 4: 'OVERTURNED'}
# OverturnAlarm.cause (issue 51): how the item reached the level; the journal's names, the report's words
CAUSES = {0: 'rocking', 1: 'fell_off_support'}
CAUSE_CODES = {v: k for k, v in CAUSES.items()}
CAUSE_WORDS = {'fell_off_support': 'fell off its support'}
QUIET_THRESHOLD = 0.05   # m/s^2: the monitor's gravity_baseline/quiet_threshold; above it the ground shakes
DAMPING = 0.05
CAUGHT_UP = 1.0          # s: states within this of the newest input count as up to date (event end)
MAX_ITEM_FIGURES = 40    # theta/alpha figures: the most severe items first; the table lists all
JOURNAL_KINDS = ('alarm', 'probability_alarm', 'reset', 'stale', 'end')  # end: the shaking stopped (issue 29)
LEVEL_CODES = {v: k for k, v in LEVELS.items()}


class ReportError(Exception):
    """Bad input (a file that is missing or not what it should be): one line, exit status 2."""
