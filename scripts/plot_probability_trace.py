#!/usr/bin/env python3
"""Live probability trace: P(beyond tipping), P(committed), P(overturned) of every uncertain item over
time, as the monitor published them (RockingState.p_*, 95 % Wilson band) in a bag, with the
probability alarms marked.

Record the bag during a replay or an event, e.g. the demo with the uncertain example catalogue:
  rosbag record -O event.bag /rocking_monitor/states /rocking_monitor/probability_alarms
  roslaunch rocking_monitor demo.launch catalogue:=$(rospack find rocking_monitor)/config/catalogue_uncertain_example.yaml
then:  scripts/plot_probability_trace.py event.bag --out trace.png
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("bag")
    p.add_argument("--monitor", default="/rocking_monitor", help="the monitor's namespace")
    p.add_argument("--out", default="probability_trace.png")
    p.add_argument("--items", nargs="*", default=None, help="only these item ids")
    a = p.parse_args()
    try:
        import rosbag
    except ImportError:
        sys.exit("plot_probability_trace: the rosbag Python module is missing (run with /usr/bin/python3)")
    states_topic, alarms_topic = a.monitor + "/states", a.monitor + "/probability_alarms"
    series, alarms, t0 = {}, [], None
    try:
        bag = rosbag.Bag(a.bag)
    except Exception as e:  # rosbag raises several types for a missing or broken file
        sys.exit("plot_probability_trace: %s: %s" % (a.bag, e))
    with bag:
        for topic, msg, _ in bag.read_messages(topics=[states_topic, alarms_topic]):
            if topic == states_topic:
                for s in msg.items:
                    if s.ensemble_size == 0 or (a.items is not None and s.id not in a.items):
                        continue
                    t = s.input_stamp.to_sec()
                    if t == 0.0:  # published before the first input sample
                        continue
                    row = series.setdefault(s.id, {"t": [], "n": s.ensemble_size,
                                                   "beyond tipping": [], "committed": [], "overturned": []})
                    row["t"].append(t)
                    for key, lp in (("beyond tipping", s.p_beyond_tipping), ("committed", s.p_committed),
                                    ("overturned", s.p_overturned)):
                        row[key].append((lp.probability, lp.lower, lp.upper))
            else:
                alarms.append(msg)
    if not series:
        sys.exit("plot_probability_trace: %s: no state of an uncertain item on %s (was the monitor running an "
                 "ensemble? record %s)" % (a.bag, states_topic, states_topic))
    # Times as the alarms give them: seconds since the sensor's first sample (the first sample's stamp
    # follows from any alarm; without one, from the first state, one sample late at most).
    if alarms:
        t0 = alarms[0].header.stamp.to_sec() - alarms[0].time_since_first_sample
    else:
        t0 = min(row["t"][0] for row in series.values())
    for row in series.values():
        row["t"] = [t - t0 for t in row["t"]]
    ids = sorted(series)
    fig, axes = plt.subplots(len(ids), 1, figsize=(8, 2.2 * len(ids) + 0.6), sharex=True, squeeze=False)
    colours = {"beyond tipping": "tab:orange", "committed": "tab:red", "overturned": "tab:purple"}
    for ax, item in zip([r[0] for r in axes], ids):
        row = series[item]
        for key, colour in colours.items():
            p_, lo, hi = zip(*row[key])
            ax.step(row["t"], p_, where="post", color=colour, label="P(%s)" % key)
            ax.fill_between(row["t"], lo, hi, step="post", color=colour, alpha=0.12)
        for m in alarms:
            if m.item_id == item:
                name = "committed" if m.level == 3 else "overturned"
                ax.axvline(m.time_since_first_sample, color=colours[name], ls=":", lw=1)
                ax.annotate(" alarm: P(%s) = %.2f" % (name, m.value.probability),
                            (m.time_since_first_sample, 0.62 if name == "committed" else 0.48),
                            fontsize=7, color=colours[name], ha="left", va="center")
        ax.set_ylim(-0.02, 1.02)
        ax.set_ylabel("probability")
        ax.set_title("%s (%d members; band: 95 %% Wilson interval)" % (item, row["n"]), fontsize=9, loc="left")
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=7, loc="upper left")
    axes[-1][0].set_xlabel("time since the sensor's first sample, s")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print("plot_probability_trace: wrote %s (%d items)" % (a.out, len(ids)))


if __name__ == "__main__":
    main()
