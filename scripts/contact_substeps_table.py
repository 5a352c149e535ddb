#!/usr/bin/python3
"""How many RK4 sub-steps the contact model needs (issue 28): decisions against a converged reference.

Runs rocking_sim --json (--fidelity adaptive, the node's default) for the first --items items of the
load-test catalogue (scripts/make_catalogue.py, seed 1: random geometry, mu_s 0.3-0.8, both planes)
under three real two-component records, at each --substeps and at two tight settings. A case is
converged when the reference (--reference sub-steps) and the check (--check) decide alike; on the
converged cases each setting's decisions (beyond tipping, committed, overturned, each plane's final
mode) are compared with the reference, as the accuracy policy does (docs/performance.md). Prints a
Markdown table, and on stderr each case a setting below the default (16) gets wrong where the default
is right: a faster default must have none (docs/performance.md, "Session 15").

usage: scripts/contact_substeps_table.py --sim build/devel/lib/rocking_monitor/rocking_sim
                                         [--records ../shared/records] [--items 300]
                                         [--substeps 4,8,12,16,32] [--reference 256] [--check 64]
"""
import argparse
import itertools
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

RECORDS = {  # name: (x component, y component), both horizontal
    "Kobe Takatori": ("kobe_1995/RSN1120_KOBE_TAK000.AT2", "kobe_1995/RSN1120_KOBE_TAK090.AT2"),
    "Landers Lucerne": ("landers_1992/RSN879_LANDERS_LCN260.AT2", "landers_1992/RSN879_LANDERS_LCN345.AT2"),
    "Northridge Newhall": ("northridge_1994/RSN1044_NORTHR_NWH090.AT2",
                           "northridge_1994/RSN1044_NORTHR_NWH360.AT2"),
}
TIMES = ("beyond_tipping_time_s", "committed_time_s", "overturn_time_s")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sim", required=True, help="rocking_sim binary")
    p.add_argument("--records", default=os.path.join(here, "..", "..", "shared", "records"))
    p.add_argument("--items", type=int, default=300)
    p.add_argument("--substeps", default="4,8,12,16,32")
    p.add_argument("--reference", type=int, default=256)
    p.add_argument("--check", type=int, default=64)
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    a = p.parse_args()
    settings = sorted({int(s) for s in a.substeps.split(",")} | {a.reference, a.check})
    for x, y in RECORDS.values():
        for f in (x, y):
            if not os.path.isfile(os.path.join(a.records, f)):
                sys.exit("contact_substeps_table: record not found: " + os.path.join(a.records, f))
    with tempfile.TemporaryDirectory() as tmp:
        catalogue = os.path.join(tmp, "catalogue.yaml")
        subprocess.run([sys.executable, os.path.join(here, "make_catalogue.py"), str(a.items), catalogue],
                       check=True)
        items = ["item%05d" % i for i in range(a.items)]

        def run(job):
            item, record, n = job
            x, y = RECORDS[record]
            out = subprocess.run([a.sim, "--catalogue", catalogue, "--item", item,
                                  "--record", os.path.join(a.records, x), "--record-y", os.path.join(a.records, y),
                                  "--fidelity", "adaptive", "--contact-substeps", str(n), "--json"],
                                 capture_output=True, text=True)
            if out.returncode != 0:
                sys.exit("contact_substeps_table: %s %s %d: %s" % (item, record, n, out.stderr.strip()[-300:]))
            j = json.loads(out.stdout)
            it = j["item"]
            decision = (it["beyond_tipping"], it["committed"], it["overturned"],
                        tuple(sorted((p, v["final_mode"]) for p, v in j["planes"].items())))
            return (item, record), n, decision, [it.get(t) for t in TIMES], j["cpu_time_s"]

        with ThreadPoolExecutor(a.jobs) as ex:
            results = list(ex.map(run, itertools.product(items, RECORDS, settings)))
    cases = {}
    for case, n, decision, times, cpu in results:
        cases.setdefault(case, {})[n] = (decision, times, cpu)
    converged = [c for c, r in cases.items() if r[a.reference][0] == r[a.check][0]]

    def times_off(c, n, tol):
        ta, tb = cases[c][n][1], cases[c][a.reference][1]
        return any((x is None) != (y is None) or (x is not None and abs(x - y) > tol) for x, y in zip(ta, tb))

    print("%d cases (%d items x %d records), %d converged (%d and %d sub-steps decide alike)\n"
          % (len(cases), a.items, len(RECORDS), len(converged), a.reference, a.check))
    print("| RK4 sub-steps per sample | decisions unlike the reference | of which the default (16) gets right "
          "| event times off by > 0.01 s | CPU, all cases (s) |")
    print("|---|---|---|---|---|")
    for n in settings:
        if n == a.reference:
            continue
        wrong = [c for c in converged if cases[c][n][0] != cases[c][a.reference][0]]
        default_right = [c for c in wrong if 16 in cases[c] and cases[c][16][0] == cases[c][a.reference][0]]
        late = [c for c in converged if c not in wrong and times_off(c, n, 0.01)]
        cpu = sum(r[n][2] for r in cases.values())
        print("| %d | %d | %d | %d | %.2f |" % (n, len(wrong), len(default_right), len(late), cpu))
        if n < 16:
            for c in default_right:
                print("  %d sub-steps wrong where 16 is right: %s under %s" % (n, c[0], c[1]), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
