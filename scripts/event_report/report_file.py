"""event_report.report_file: one report from a bag to a file: loading, the page, written atomically."""
import os
import sys

from .data import load_catalogue, merge_journal, read_bag, read_journal
from .html_page import render


def write_report(bag, out, catalogue=None, monitor=None, title=None, ended=None, journal=None, pair=None):
    data = read_bag(bag, monitor, pair)
    if journal:
        j = read_journal(journal)
        for t in j['warnings'] + j['errors']:
            sys.stderr.write('rocking_report: warning: %s\n' % t)
        merge_journal(data, j)
    cat = load_catalogue(catalogue) if catalogue else None
    import matplotlib
    matplotlib.use('Agg')
    page = render(data, cat, title, ended)
    tmp = out + '.part'
    with open(tmp, 'w', encoding='utf-8') as f:
        f.write(page)
    os.replace(tmp, out)  # a reader never sees half a report
    return out
