"""event_report: the parts of scripts/rocking_report, the post-event report (issue 53: one 958-line file
became this package). One concept per module, each importing only those above it in this list:

    common       constants (modes, levels, causes, thresholds) and ReportError
    data         the bag, the alarm journal and the catalogue, read into plain Python data
    analysis     the ground motion and its spectrum, the Housner periods, the items' outcomes, health
    figures      the matplotlib figures, embedded as PNG
    html_page    the self-contained HTML page
    report_file  one report from a bag to a file
    recorder     the --node mode: an event's bag and report written when it ends

scripts/rocking_report parses the command line and re-exports the names its tests use.
"""
