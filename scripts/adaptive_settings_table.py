#!/usr/bin/python3
"""What the adaptive model's speed settings cost in decisions (issue 28): the contact model's RK4
sub-steps and the hold time before it hands back to the rocking model, against a converged reference.

Runs rocking_sim --json for the first --items items of the load-test catalogue (scripts/make_catalogue.py,
seed 1: random geometry, mu_s 0.3-0.8, both planes) under three real two-component records. The
reference is the full contact model (--fidelity contact) at --reference sub-steps, checked at --check:
a case is converged when the two decide alike. Each variant of the node's default (--fidelity adaptive,
16 sub-steps, hold 0.1 s) is compared with the reference on the converged cases, decision by decision
(beyond tipping, committed, overturned, each plane's final mode), as the accuracy policy does
(docs/performance.md). Prints a Markdown table, and on stderr each case a variant gets wrong where the
default is right: a faster default must have none (docs/performance.md, "Session 15").

usage: scripts/adaptive_settings_table.py --sim build/devel/lib/rocking_monitor/rocking_sim
                                         [--records ../shared/records] [--items 300]
                                         [--substeps 4,8,12,16,32] [--hold-times 0.05,0.02,0]
                                         [--reference 256] [--check 64]
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
DEFAULT = "adaptive, 16 sub-steps, hold 0.1 s"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sim", required=True, help="rocking_sim binary")
    p.add_argument("--records", default=os.path.join(here, "..", "..", "shared", "records"))
    p.add_argument("--items", type=int, default=300)
    p.add_argument("--substeps", default="4,8,12,16,32", help="adaptive, hold 0.1 s, these sub-steps")
    p.add_argument("--hold-times", default="", help="adaptive, 16 sub-steps, these hold times (s)")
    p.add_argument("--reference", type=int, default=256)
    p.add_argument("--check", type=int, default=64)
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    a = p.parse_args()
    variants = {"reference": ["--fidelity", "contact", "--contact-substeps", str(a.reference)],
                "check": ["--fidelity", "contact", "--contact-substeps", str(a.check)]}
    for n in sorted({int(s) for s in a.substeps.split(",") if s} | {16}):
        label = DEFAULT if n == 16 else "adaptive, %d sub-steps, hold 0.1 s" % n
        variants[label] = ["--fidelity", "adaptive", "--contact-substeps", str(n)]
    for h in sorted({float(s) for s in a.hold_times.split(",") if s}, reverse=True):
        if h != 0.1:
            variants["adaptive, 16 sub-steps, hold %g s" % h] = ["--fidelity", "adaptive", "--hold-time", repr(h)]
    for x, y in RECORDS.values():
        for f in (x, y):
            if not os.path.isfile(os.path.join(a.records, f)):
                sys.exit("adaptive_settings_table: record not found: " + os.path.join(a.records, f))
    with tempfile.TemporaryDirectory() as tmp:
        catalogue = os.path.join(tmp, "catalogue.yaml")
        subprocess.run([sys.executable, os.path.join(here, "make_catalogue.py"), str(a.items), catalogue],
                       check=True)
        items = ["item%05d" % i for i in range(a.items)]

        def run(job):
            item, record, label = job
            x, y = RECORDS[record]
            out = subprocess.run([a.sim, "--catalogue", catalogue, "--item", item,
                                  "--record", os.path.join(a.records, x), "--record-y", os.path.join(a.records, y),
                                  "--json"] + variants[label], capture_output=True, text=True)
            if out.returncode != 0:
                sys.exit("adaptive_settings_table: %s %s %s: %s" % (item, record, label, out.stderr.strip()[-300:]))
            j = json.loads(out.stdout)
            it = j["item"]
            decision = (it["beyond_tipping"], it["committed"], it["overturned"],
                        tuple(sorted((p, v["final_mode"]) for p, v in j["planes"].items())))
            return (item, record), label, decision, [it.get(t) for t in TIMES], j["cpu_time_s"]

        with ThreadPoolExecutor(a.jobs) as ex:
            results = list(ex.map(run, itertools.product(items, RECORDS, variants)))
    cases = {}
    for case, label, decision, times, cpu in results:
        cases.setdefault(case, {})[label] = (decision, times, cpu)
    converged = [c for c, r in cases.items() if r["reference"][0] == r["check"][0]]

    def right(c, label):
        return cases[c][label][0] == cases[c]["reference"][0]

    def times_off(c, label, tol):
        ta, tb = cases[c][label][1], cases[c]["reference"][1]
        return any((x is None) != (y is None) or (x is not None and abs(x - y) > tol) for x, y in zip(ta, tb))

    print("%d cases (%d items x %d records), %d converged (the contact model at %d and %d sub-steps decides "
          "alike)\n" % (len(cases), a.items, len(RECORDS), len(converged), a.reference, a.check))
    print("| model | decisions unlike the reference | of which the default gets right "
          "| event times off by > 0.01 s | CPU, all cases (s) |")
    print("|---|---|---|---|---|")
    for label in variants:
        if label == "reference":
            continue
        wrong = [c for c in converged if not right(c, label)]
        default_right = [c for c in wrong if right(c, DEFAULT)]
        late = [c for c in converged if right(c, label) and times_off(c, label, 0.01)]
        cpu = sum(r[label][2] for r in cases.values())
        name = "**%s (default)**" % label if label == DEFAULT else label
        if label == "check":
            name = "contact model, %d sub-steps (check)" % a.check
        print("| %s | %d | %d | %d | %.2f |" % (name, len(wrong), len(default_right), len(late), cpu))
        if label not in ("check", DEFAULT):
            for c in default_right:
                print("  %s: wrong where the default is right: %s under %s" % (label, c[0], c[1]), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
