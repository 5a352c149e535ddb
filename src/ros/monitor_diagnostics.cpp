// RockingMonitor's diagnostics: one status per sensor (samples received, dropped, rejected,
// bridged; processing time) and one for the catalogue (items per mode, transforms, alarms).
#include "rocking_monitor/ros/monitor.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

#include "rocking_monitor/integrate/solver_settings.hpp"

namespace rocking_monitor::live {
namespace {

using core::ItemMode;

}  // namespace

void RockingMonitor::sensor_diagnostics(std::size_t i, diagnostic_updater::DiagnosticStatusWrapper& st) {
  const Sensor& s = sensors_[i];
  const core::SampleTiming::Counters& c = s.timing.counters();
  const std::uint64_t dropped = c.duplicates + c.out_of_order + s.zero_stamps;
  const std::uint64_t rejected = s.rejected_nonfinite + s.rejected_limit;
  const core::StampPlausibility::Counters& pc = s.plausibility.counters();
  if (s.received == 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no data yet");
  else if (s.overloaded)
    st.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "overload: lag beyond ~max_lag, shedding markers, tf, states");
  else if (stale(s))
    st.summary(diagnostic_msgs::DiagnosticStatus::ERROR, s.plausibility.held() > 0
                   ? "stale: items frozen, new time base awaiting ~rebase_samples consistent samples"
                   : "stale: items frozen, no sample for more than ~max_gap");
  else if (s.mean_dt > 0.0 && s.last_processing_s > s.mean_dt)
    st.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "processing slower than the sample rate");
  else if (dropped + rejected > 0 || c.gaps > 0 || pc.rejected > 0 || s.lost_in_transport > 0)
    st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "samples dropped, rejected, lost or gaps");
  else st.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  // Beside whatever else holds (stale, overload): two sources feed the stream, and a person must find
  // the second (issue 52 item 3). mergeSummary keeps both messages at ERROR, replaces a lower one.
  if (s.conflicting > 0)
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::ERROR,
                    "samples marked conflicting by the bridge (two sources disagree): not stepped, gaps in their place");
  st.add("topic", s.spec.topic);
  st.add("received", s.received);
  st.add("accepted", c.accepted);
  st.add("dropped duplicate stamp", c.duplicates);
  st.add("dropped out-of-order stamp", c.out_of_order);
  st.add("dropped zero stamp", s.zero_stamps);
  st.add("rejected non-finite", s.rejected_nonfinite);
  st.add("rejected beyond max_abs_acceleration", s.rejected_limit);
  st.add("data gaps (not bridged)", c.gaps);
  st.add("conflicting samples (marked by the bridge), not stepped", s.conflicting);
  st.add("last conflicting sample (stamp)", std::to_string(s.last_conflicting_stamp.toSec()));  // to the microsecond
  st.add("longest gap (s)", c.longest_gap);
  st.add("resets (time jumped back)", s.resets);
  st.add("rejected implausible stamp", pc.rejected);
  st.add("rejected stamp ahead of the clock (of those)", pc.rejected_future);
  st.add("re-stamped from their sequence and stepped (of those)", pc.restamped);
  st.add("last rejected jump (s)", pc.last_rejected_jump);
  st.add("held for a new time base", s.plausibility.held());
  st.add("new time base adopted, items continued", pc.rebased_forward);
  st.add("earlier time base adopted, items restarted", pc.rebased_backward);
  st.add("stale", stale(s) ? "true" : "false");
  st.add("lost in transport", s.lost_in_transport);
  st.add("clock offset, node clock - stamp, min (s)", s.min_offset_s);
  st.add("lag (s)", s.lag_s);
  st.add("lag, max (s)", s.max_lag_s);
  st.add("backlog, queue wait (s)", s.backlog_s);
  st.add("backlog, queue wait max (s)", s.max_backlog_s);
  st.add("overload", s.overloaded ? "true" : "false");
  st.add("overload episodes", s.overload_episodes);
  st.add("mean sample period (s)", s.mean_dt);
  st.add("processing per sample, last (s)", s.last_processing_s);
  st.add("processing per sample, max (s)", s.max_processing_s);
  st.add("processing per sample, mean (s)", s.processed > 0 ? s.total_processing_s / s.processed : 0.0);
  st.add("processing / sample period", s.mean_dt > 0.0 ? s.last_processing_s / s.mean_dt : 0.0);
  st.add("item-samples deferred (at rest, overturned, or rocking with nothing to report)", s.deferred);
  st.add("gravity baseline (m/s^2)", std::to_string(s.baseline.baseline().x()) + " " +
                                        std::to_string(s.baseline.baseline().y()) + " " +
                                        std::to_string(s.baseline.baseline().z()));
}

void RockingMonitor::catalogue_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  // From the batches' summaries (no sync); the adaptive models' counters below are read as they
  // stand: deferred samples are inside the scene and change no choice of model.
  std::array<int, 5> counts{};
  int without_tf = 0, invalid = 0, on_contact = 0;
  std::uint64_t skipped = 0;
  for (Item& it : items_) {
    skipped += it.samples_without_transform;
    const core::ItemSummary& sm = summary(it);
    ++counts[static_cast<int>(sm.mode)];
    if (!it.has_rotation) ++without_tf;
    bool valid = true;
    for (int p = 0; p < sm.planes; ++p) {
      valid = valid && sm.plane[p].violations == 0;
      on_contact += sm.plane[p].model == core::ActiveModelName::Contact;
    }
    invalid += !valid;
  }
  if (without_tf > 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, std::to_string(without_tf) + " items without transform");
  else if (counts[4] > 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, std::to_string(counts[4]) + " items overturned");
  else st.summary(diagnostic_msgs::DiagnosticStatus::OK, "monitoring " + std::to_string(items_.size()) + " items");
  st.add("items", items_.size());
  st.add("shard (k/n of the catalogue)", shard_);
  std::size_t ensembles = 0, members = 0;
  double ensemble_s = 0.0;
  for (const Item& it : items_)
    if (it.ensemble) {
      ++ensembles;
      members += static_cast<std::size_t>(it.ensemble->size());
      ensemble_s += it.ensemble_s;
    }
  std::uint64_t samples = 0;
  for (const Sensor& s : sensors_) samples += s.processed;
  st.add("items with an ensemble (uncertain parameters)", ensembles);
  st.add("ensemble members stepped per sample", members);
  // Summed over threads: the CPU the ensembles cost per input sample (part of the processing time).
  st.add("ensemble stepping per sample, mean (s)", samples > 0 ? ensemble_s / static_cast<double>(samples) : 0.0);
  for (int m = 0; m < 5; ++m) st.add(core::to_string(static_cast<ItemMode>(m)), counts[m]);
  st.add("pure-rocking model not valid now", invalid);
  st.add("items without transform", without_tf);
  st.add("item-samples skipped for want of a transform", skipped);
  st.add("alarms published", alarms_published_.load());
  // Off the per-sample path (timers, same thread): what publishing costs besides the stepping.
  st.add("states publication, mean (s)", states_cost_.mean());
  st.add("states publication, max (s)", states_cost_.max_s);
  st.add("states publications", states_cost_.count);
  st.add("markers and tf publication, mean (s)", markers_cost_.mean());
  st.add("markers and tf publication, max (s)", markers_cost_.max_s);
  st.add("markers and tf publications", markers_cost_.count);
  st.add("markers and tf publications shed (overload)", shed_markers_);
  st.add("states publications shed (overload)", shed_states_);
  st.add("method", core::to_string(options_.solver.method));
  st.add("fidelity", core::to_string(options_.fidelity));
  st.add("item planes on the contact model now", on_contact);
  if (options_.fidelity == core::Fidelity::Adaptive) {
    int ruled_out = 0;
    long outside = 0;
    for (const Item& it : items_) {
      for (int p = 0; p < it.monitor->plane_count(); ++p) {
        const core::AdaptiveModel* pa = it.monitor->plane(static_cast<core::Plane>(p)).adaptive();
        if (pa == nullptr) continue;  // no mu_s: pure rocking
        const core::AdaptiveModel& a = *pa;
        ruled_out += a.initial_reason() == core::SwitchReason::SceneRulesOutContact;
        outside = std::max(outside, a.outcome().samples_outside_scene);
      }
    }
    st.add("item planes whose friction rules out the contact model in the scene envelope", ruled_out);
    st.add("input samples outside the scene envelope", outside);
    if (outside > 0 && without_tf == 0)
      st.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                      "input outside ~scene_envelope: pre-check guarantee void, margins apply");
  }
}

}  // namespace rocking_monitor::live
