#pragma once

#include <algorithm>
#include <chrono>
#include <limits>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <diagnostic_updater/update_functions.h>
#include <geometry_msgs/AccelStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/Bool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>
#include <tbb/task_arena.h>

#include "rocking_monitor/CriterionExceedance.h"
#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/ProbabilityAlarm.h"
#include "rocking_monitor/RockingStateArray.h"
#include "rocking_monitor/SampleHistory.h"
#include "rocking_monitor/motion/gravity_baseline.hpp"
#include "rocking_monitor/monitoring/alarm_journal.hpp"
#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/item_summary.hpp"
#include "rocking_monitor/monitoring/monitor_batch.hpp"
#include "rocking_monitor/monitoring/state_snapshot.hpp"
#include "rocking_monitor/motion/sample_timing.hpp"
#include "rocking_monitor/motion/stamp_plausibility.hpp"
#include "rocking_monitor/ros/catalogue.hpp"

namespace rocking_monitor::live {

/// The fields every alarm message shares: stamp, the item's frame, id and description.
template <class Alarm>
Alarm alarm_for(const core::ItemSpec& spec, const ::ros::Time& stamp) {
  Alarm m;
  m.header.stamp = stamp;
  m.header.frame_id = spec.frame;
  m.item_id = spec.id;
  m.description = spec.description;
  return m;
}

/// The live monitor (thin ROS layer over core::ItemMonitor): subscribes to every sensor of the
/// catalogue, rotates each sample into each item's frame with tf2, removes gravity with a tracked
/// at-rest baseline, steps the items with dt from the header stamps and publishes states, criterion
/// changes, overturn alarms, diagnostics, markers and tf. Used by the node and the nodelet.
class RockingMonitor {
 public:
  RockingMonitor(::ros::NodeHandle nh, ::ros::NodeHandle pnh);
  ~RockingMonitor();

  /// Reads parameters and the catalogue, sets up topics. False (after a ROS_FATAL naming the item and
  /// field or the parameter) on bad configuration.
  bool init();

 private:
  void log_initial_models() const;
  struct Item {
    CatalogueItem entry;
    std::unique_ptr<core::ItemMonitor> monitor;
    std::vector<core::ItemSpec> members;         // drawn once at init (uncertain items only)
    std::unique_ptr<core::ItemEnsemble> ensemble;  // the members under the same samples
    double ensemble_s = 0.0;  // wall time spent stepping the members, s (diagnostics: the ensemble's cost)
    std::size_t sensor = 0;
    bool has_rotation = false;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // item <- sensor
    ::ros::Time stamp;           // input stamp of the last step while not ready (else the sensor's stepped_stamp)
    std::uint64_t samples_without_transform = 0;
    bool ready = false;          // stepped in the current sample
    std::size_t slot = 0;        // its place in its sensor's items (and batch)
    // The summary revision each publication last sent (kUnsent: fill in full next time); the
    // publications refill only items whose summary changed (issue 28).
    static constexpr std::uint32_t kUnsent = 0xffffffffu;
    std::uint32_t states_revision = kUnsent, changes_revision = kUnsent, markers_revision = kUnsent;
    core::ItemSummary summary;   // read from the monitor while its sensor has no batch (before the first step)
  };
  struct Sensor {
    SensorSpec spec;
    ::ros::Subscriber sub;
    core::GravityBaseline baseline;
    core::SampleTiming timing;
    // Issue 19: stamps checked before they step anything; candidates for a new time base are held
    // here (sized ~rebase_samples at init) and replayed once the base is confirmed.
    core::StampPlausibility plausibility;
    struct Held { ::ros::Time stamp; Eigen::Vector3d reading; };
    std::vector<Held> held;
    std::size_t held_count = 0;
    // Every sample dropped for its stamp since the last one stepped (rejected or in a held run), in
    // arrival order: re-stamped from their sequence when the next good stamp shows they were in order.
    std::vector<Held> suspects;
    std::size_t suspect_count = 0;
    ::ros::Time last_input_clock;     // node clock when the last sample was stepped (stale check)
    bool stale_journaled = false;     // a stale period of this sensor is open in the journal
    bool stale_now = false;           // stale(), evaluated once per states publication
    bool stale_in_changes = false;    // stale_now as ~state_changes last sent it
    double stale_from = 0.0;          // its start: stamp of the last sample before it, s since 1970
    double lag_s = 0.0, max_lag_s = 0.0;  // (node clock - stamp) of the last sample stepped minus its minimum, s
    double min_offset_s = 0.0;        // minimum of node clock - stamp so far (clock offset + transport), s
    bool have_min_offset = false;
    double backlog_s = 0.0, max_backlog_s = 0.0;  // node clock at processing - at arrival, s (queue wait)
    std::uint64_t overload_episodes = 0;
    std::uint64_t lost_in_transport = 0;  // missing periods at the nominal rate, from the stamps
    std::uint64_t received_at_last_step = 0;
    double min_dt = 0.0;              // shortest step between stamps seen, s (nominal period check)
    bool overloaded = false;
    std::vector<std::size_t> items;
    std::string frame;                // frame of the last message
    bool have_first = false;          // a first sample is stored, models not started yet
    // The models run on seconds since the first sample of the run, from integer-nanosecond stamp
    // differences: exact to 1e-16 s relative where seconds since 1970 in a double keep 0.1 us.
    ::ros::Time epoch;                // stamp of the first sample of the run
    double last_t = 0.0;              // s since epoch of the last accepted sample
    double first_t = 0.0;             // s since epoch of the stored first sample (0)
    Eigen::Vector3d first_a = Eigen::Vector3d::Zero();
    double dt_nominal = 0.0;
    std::uint64_t received = 0, rejected_nonfinite = 0, rejected_limit = 0, zero_stamps = 0, resets = 0;
    // Issue 52 item 3: samples the bridge marked as conflicting (infinite variance), not stepped: a
    // gap at their place; the last one's stamp for /diagnostics.
    std::uint64_t conflicting = 0;
    ::ros::Time last_conflicting_stamp;
    double last_processing_s = 0.0, max_processing_s = 0.0, total_processing_s = 0.0, mean_dt = 0.0;
    std::uint64_t processed = 0;
    ::ros::Time last_stamp;
    std::unique_ptr<diagnostic_updater::TopicDiagnostic> topic_diag;
    double min_freq = 0.0, max_freq = 0.0;
    // The sensor's items stepped together (issue 12); null after their models were (re)made or
    // (re)started, rebuilt before the next step. Inputs in each item's frame, sized once.
    std::unique_ptr<core::MonitorBatch> batch;
    std::vector<double> in_x, in_y, in_z;   // m/s^2
    std::vector<double> gains;              // each item's catalogue input_gain, dimensionless
    std::vector<std::uint8_t> in_ready;     // the item steps this sample
    // Each item's rotation (item <- sensor), contiguous: the per-sample rotation reads 72 B per item
    // instead of a cache miss into each Item. Filled when the item becomes ready.
    std::vector<Eigen::Matrix3d> rotations;
    // Every item has its transform and is started: in_ready and Item::ready stay as they are until
    // the batch is rebuilt (a restart), so the per-sample readiness check over the items is skipped.
    bool all_ready = false;
    bool has_ensembles = false;             // some item is uncertain (its members step after the batch)
    ::ros::Time stepped_stamp;              // stamp of the last sample whose items were stepped
    std::uint64_t deferred = 0;             // item-samples deferred by the batch (quiet)
    // Issue 29: input quiet (|a| below ~event_quiet_threshold) since this stamp, s since 1970 (NaN: not quiet).
    double quiet_from = std::numeric_limits<double>::quiet_NaN();
    // Issue 29 part 2: stamp of the last sample stepped from the bridge's history (zero: not catching
    // up); live samples up to it were stepped already: dropped and counted until a later one arrives.
    ::ros::Time caught_up_to;
    std::uint64_t caught_up_dropped = 0;
    // Input time its items were frozen through (data gaps not bridged, a restart's gap) since the node
    // started or they were re-armed, s: OverturnAlarm.frozen_s (a redundant pair's consumers prefer 0).
    double frozen_s = 0.0;
  };

  bool load_parameters();
  // load_parameters()'s checks, in order: false after a ROS_FATAL naming the parameter.
  bool check_scene_and_ensemble(double scene_h, double scene_v, int substeps);
  bool resolve_threads();
  bool parse_solver_choices(const std::string& method, const std::string& model, const std::string& fidelity,
                            const std::string& solid);
  bool parse_baseline_mode(const std::string& baseline);
  bool check_positive_parameters() const;
  // init()'s steps, in order (load_catalogue false after a ROS_FATAL).
  bool load_catalogue(XmlRpc::XmlRpcValue& sensors, XmlRpc::XmlRpcValue& items, Catalogue& cat);
  void add_sensors(const Catalogue& cat);
  void add_items(const Catalogue& cat);
  static geometry_msgs::TransformStamped pose_transform(const CatalogueItem& entry);
  void publish_static_poses(tf2_msgs::TFMessage& statics);
  void advertise_outputs(const XmlRpc::XmlRpcValue& sensors, const XmlRpc::XmlRpcValue& items);
  void add_diagnostics();
  void subscribe_sensors();
  void start_timers();
  void log_startup() const;
  void on_imu(std::size_t sensor, const ::ros::MessageEvent<sensor_msgs::Imu const>& msg);
  void on_accel(std::size_t sensor, const ::ros::MessageEvent<geometry_msgs::AccelStamped const>& msg);
  void skip_conflicting(std::size_t sensor, const std_msgs::Header& header);
  void update_overload(Sensor& s);
  static double queue_wait(const ::ros::Time& receipt);
  bool shedding_states() const;
  void on_sample(std::size_t sensor, const std_msgs::Header& header, const Eigen::Vector3d& reading);
  void step_sample(std::size_t sensor, const std_msgs::Header& header, const Eigen::Vector3d& reading,
                   std::chrono::steady_clock::time_point wall_start);
  // step_sample's steps (monitor_sample_path.cpp)
  bool admit_stamp(Sensor& s, const std_msgs::Header& header, core::SampleTiming::Verdict& verdict, double& dt);
  void count_lost_in_transport(Sensor& s, double stamp_dt);
  void ready_items(Sensor& s, double t, const Eigen::Vector3d& a, const ::ros::Time& stamp);
  void step_items(Sensor& s, const Eigen::Vector3d& a, double dt);
  void publish_sample_events(Sensor& s, const ::ros::Time& stamp);
  void finish_sample(Sensor& s, const ::ros::Time& stamp, std::chrono::steady_clock::time_point wall_start);
  void replay_held(std::size_t sensor, const std_msgs::Header& header);
  bool restamp_suspects(std::size_t sensor, const std_msgs::Header& header);
  static double nominal_period(const Sensor& s);
  bool stale(const Sensor& s) const;  // no sample stepped for > max_gap of the node's clock, or a base pending
  void start_items(Sensor& s, double t, const Eigen::Vector3d& a);
  bool lookup_rotation(Item& item, const std::string& sensor_frame);
  ::ros::Time input_stamp(const Item& item) const {
    return item.ready ? sensors_[item.sensor].stepped_stamp : item.stamp;
  }
  void publish_events(Item& item, const core::ItemEvents& events, const ::ros::Time& stamp);
  void publish_crossings(Item& item, const core::EnsembleEvents& events, const ::ros::Time& stamp);
  // A sample's alarms are journaled first (lines kept, not yet written), then one write and one fsync,
  // then published: one fsync per sample instead of one per alarm (10,000 items alarm within seconds).
  // The write, the fsync and the publication run on the journal's thread (AlarmJournal::sync_async):
  // the sample path does not wait for the disk (~1 ms a sample in the strongest shaking).
  struct PendingLog {
    bool error = false;  // ROS_ERROR, else ROS_WARN
    std::string text;
  };
  struct AlarmBatch {  // one sample's alarms, handed to the journal's thread
    std::vector<OverturnAlarm> alarms;
    std::vector<ProbabilityAlarm> probability_alarms;
    std::vector<PendingLog> logs;
  };
  void publish_alarm_batch(const AlarmBatch& batch, const std::string& journal_error);  // the journal's thread
  std::vector<OverturnAlarm> pending_alarms_;
  std::vector<ProbabilityAlarm> pending_probability_alarms_;
  std::vector<PendingLog> pending_logs_;
  // A sample's first kAlarmLinesPerSample alarms get a log line each; the rest one summary line with
  // their counts (10,000 items alarm within seconds: 27,000 lines on /rosout were most of the burst's
  // cost). Every alarm is still journaled and published.
  static constexpr std::size_t kAlarmLinesPerSample = 10;
  std::size_t unlogged_overturned_ = 0, unlogged_committed_ = 0, unlogged_beyond_ = 0, unlogged_probability_ = 0;
  void publish_pending_alarms();
  void make_models(Item& item);  // the nominal ItemMonitor and, for an uncertain item, its ensemble
  void rebuild_batch(Sensor& s);
  void sync_items();  // applies the batches' deferred samples: before anything reads the items
  void reset_all(const std::string& why);
  void on_state_timer(const ::ros::TimerEvent&);
  void publish_states();
  void on_startup_timer(const ::ros::WallTimerEvent&);
  bool on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response&);
  /// ~set_upright (issue 29): the items on their side were set upright again: they restart at rest
  /// where they are (the event and the journal unchanged; a later shaking alarms them again).
  bool on_set_upright(std_srvs::Trigger::Request&, std_srvs::Trigger::Response&);
  const core::ItemSummary& summary(Item& item);  // the batch's, without a sync (else read from the monitor)
  void fill_state(const Item& item, const core::ItemSummary& summary, RockingState& out) const;
  void fill_ensemble(const Item& item, RockingState& out) const;
  static void fill_plane(const core::PlaneSummary& plane, PlaneState& out);
  void publish_state_changes(const ::ros::Time& newest);
  void publish_markers_and_tf();
  void sensor_diagnostics(std::size_t sensor, diagnostic_updater::DiagnosticStatusWrapper& stat);
  void catalogue_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& stat);

  ::ros::NodeHandle nh_, pnh_;
  core::ItemMonitor::Options options_;
  core::GravityBaseline::Config baseline_config_;
  core::SampleTiming::Config timing_config_;
  core::StampPlausibility::Config plausibility_config_;
  // Overload (issue 19 part 3): past ~max_lag the node sheds markers and tf, then (after
  // ~max_lag more) thins ~states to 1 Hz, before input has to wait.
  double max_lag_ = 0.5;
  bool restamp_in_sequence_ = true;  // ~restamp_in_sequence: bad-stamped samples in sequence are re-stamped
  bool overload_ = false;
  ::ros::WallTime overload_since_;
  std::uint64_t shed_markers_ = 0, shed_states_ = 0;  // publications skipped while overloaded
  ::ros::Time last_shed_states_;
  ::ros::Publisher overload_pub_;
  double max_abs_acceleration_ = 50.0;
  double state_rate_ = 20.0;
  // Full ~states carry every item: at most this many item-states per second (their rate is thinned
  // for large catalogues; ~state_changes keeps state_rate). 0: no limit.
  double state_items_per_s_ = 50000.0;
  int full_state_every_ = 1;           // state timer ticks per full ~states message
  std::uint64_t state_ticks_ = 0;
  ::ros::Publisher state_changes_pub_;
  RockingStateArray changes_msg_;      // reused: its items' strings keep their capacity
  int state_queue_size_ = 10;  // ~states messages kept per subscriber while it lags
  bool publish_markers_ = true, publish_tf_ = true;
  int threads_ = 1;
  std::string shard_ = "1/1";
  int ensemble_size_ = 32;        // members per uncertain item (issue 13)
  int ensemble_seed_ = 1;         // global seed of the members' Latin hypercube
  double alarm_probability_ = 0.5;  // P(committed) / P(overturned) alarm threshold  // this monitor's part of the catalogue: shard k of n by hash of the id
  double marker_rate_ = 5.0;
  ::ros::Time last_marker_time_;
  std::unique_ptr<tbb::task_arena> arena_;
  std::string marker_frame_suffix_ = "/body";

  std::vector<Sensor> sensors_;
  std::vector<Item> items_;
  std::vector<std::string> screening_names_;

  ::ros::Publisher states_pub_, criteria_pub_, alarms_pub_, markers_pub_, probability_alarms_pub_;
  ::ros::ServiceServer reset_srv_, upright_srv_;
  ::ros::Timer state_timer_;
  ::ros::WallTimer startup_timer_;
  ::ros::Time last_tf_stamp_;
  RockingStateArray states_msg_;  // reused: sized once
  ::ros::Time last_now_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  // Items' rotations are looked up once (static mounting): once every item has one, the listener
  // is stopped, so that the node no longer takes its own 10,000 body transforms back in at 5 Hz.
  std::size_t items_without_rotation_ = 0;
  // Markers and tf: messages kept and refilled in place (20,000 markers, 10,000 transforms each time);
  // tf is published on /tf as tf2_ros::TransformBroadcaster does, from the kept message.
  visualization_msgs::MarkerArray markers_msg_;
  tf2_msgs::TFMessage tf_msg_;
  ::ros::Publisher tf_pub_;
  // The catalogue's poses on /tf_static, latched, in one message. Not tf2_ros::StaticTransformBroadcaster:
  // it looks each new child frame up in the message it holds, O(n^2): 1.6 s at start for 10,000 items.
  ::ros::Publisher tf_static_pub_;
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
  std::atomic<std::uint64_t> alarms_published_{0};  // counted on the journal's thread
  // Wall time of the publication off the per-sample path (timers): ~states, and markers with tf.
  struct Cost {
    double total_s = 0.0, max_s = 0.0;
    std::uint64_t count = 0;
    void add(double s) { total_s += s; max_s = std::max(max_s, s); ++count; }
    double mean() const { return count > 0 ? total_s / static_cast<double>(count) : 0.0; }
  };
  Cost states_cost_, markers_cost_;

  // The alarm journal (issue 19, part 2; docs/journal.md, ros/monitor_journal.cpp): every alarm,
  // probability alarm, reset and stale period is appended (fsync'd) before it is published; on start
  // the open event's alarms are read back, their levels marked alarmed in the items, and sent to every
  // new subscriber of ~alarms / ~probability_alarms.
  std::string journal_path_;         // ~journal; "" = off (events kept in memory only)
  double journal_window_ = 3600.0;   // ~journal_window, s of the node's clock
  core::AlarmJournal journal_;
  std::string journal_status_;       // why the journal is not on file, if it is not
  std::atomic<std::uint64_t> journal_errors_{0};  // also counted on the journal's thread
  std::uint64_t journal_repeats_ = 0, journal_relatched_ = 0;
  std::vector<OverturnAlarm> event_alarms_;                // the open event's, in journal order
  std::vector<ProbabilityAlarm> event_probability_alarms_;
  bool load_journal_parameters();
  void open_journal();
  double journal_clock(const ::ros::Time& fallback) const;
  /// Journals an alarm of item `it` (fills m.event_id, m.sequence); false: a repeat within the open
  /// event (not to be published).
  bool journal_alarm(Item& it, OverturnAlarm& m, double run_start);
  bool journal_probability_alarm(Item& it, ProbabilityAlarm& m, double run_start);
  void journal_reset(const std::string& why);
  void journal_stale_period(Sensor& s);  // on the state timer: a stale period opened or closed
  void journal_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& stat);
  // One meaning of an event (issue 29 part 4): it ends when the shaking has stopped, every sensor's
  // input below ~event_quiet_threshold and every item at rest or overturned for ~event_quiet_time of
  // input (the report's rule), or on ~reset; the next shaking is a new event whose levels alarm again.
  double event_quiet_time_ = 5.0;        // ~event_quiet_time, s of input
  double event_quiet_threshold_ = 0.05;  // ~event_quiet_threshold, m/s^2 (horizontal norm and vertical)
  double last_end_check_ = 0.0;          // input stamp of the last check of the items, s since 1970
  std::uint64_t events_ended_ = 0;
  void track_quiet(Sensor& s, const Eigen::Vector3d& a, const ::ros::Time& stamp);
  void check_event_end(const ::ros::Time& stamp);

  // State snapshots (issue 29, ros/monitor_snapshot.cpp, docs/journal.md): every item's model state
  // written beside the journal every ~snapshot_period of input time (encoded here between samples,
  // written by the writer's thread); a node restarted within ~max_bridge of its last sample continues
  // each sensor's items from it, the missed samples a gap (frozen, not bridged, as issue 19).
  std::string snapshot_path_;         // ~snapshot; "" = off
  double snapshot_period_ = 0.1;      // ~snapshot_period, s of input time between snapshots (at least)
  double snapshot_max_load_ = 0.05;   // ~snapshot_max_load: encoding takes at most this share of input time
  double snapshot_interval_ = 0.1;    // the interval in use: max(period, last encode / max load), s
  std::uint32_t fingerprint_ = 0;     // of the catalogue and model options (a foreign snapshot is refused)
  std::unique_ptr<core::SnapshotFileWriter> snapshot_writer_;
  core::SnapshotEncoder snapshot_encoder_;
  ::ros::Time last_snapshot_stamp_;   // input stamp of the last snapshot taken
  Cost snapshot_cost_;                // wall time of encoding one (between samples), s
  std::uint64_t snapshot_failures_seen_ = 0;
  std::unique_ptr<core::StateSnapshot> resume_;  // read at start; each sensor's part used at its first sample
  std::vector<bool> resume_pending_;  // per sensor: its part not used yet
  std::string snapshot_start_;        // what happened at start: resumed, refused (why), none
  struct Resumed {
    std::string sensor;
    double gap_s = 0.0;               // last sample before the restart to the first after it, s
    long missing = 0;                 // samples missing at the nominal rate
    std::size_t items = 0;
  };
  std::vector<Resumed> resumed_;
  bool load_snapshot_parameters();
  /// sensors, items: the catalogue's parameters (with the model options, the configuration a
  /// snapshot must have been written by).
  void open_snapshot(const XmlRpc::XmlRpcValue& sensors, const XmlRpc::XmlRpcValue& items);
  /// next_in_history: `stamp` is the sample right after the snapshot's last (from a bridge's history):
  /// nothing is missing whatever the stamps' spacing.
  void resume_sensor(std::size_t sensor, const ::ros::Time& stamp, bool next_in_history = false);
  void take_snapshot(const ::ros::Time& stamp);
  void snapshot_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& stat);

  // Catching up (issue 29 part 2, ros/monitor_catch_up.cpp, docs/journal.md "Catching up"): a sensor
  // resuming from the snapshot first asks ~catch_up_service (a bridge's ~history) for the samples
  // since the snapshot's last, steps them through on_sample faster than real time, then goes on with
  // the live ones (those already stepped dropped and counted). Absent, failing or incomplete: the
  // frozen gap of part 1, said in the log and /diagnostics.
  std::string catch_up_service_;      // ~catch_up_service; "" = off
  double catch_up_timeout_ = 2.0;     // ~catch_up_timeout, s to wait for the service to appear, then for its answer
  bool catching_up_ = false;          // stepping history samples: no lag or overload from their age
  // ~criteria has a subscriber (read once per sample): else its messages are not built. Not latched,
  // so nobody misses one; the strongest shaking changes ~700 criteria per sample (10,000 items).
  bool criteria_wanted_ = true;
  struct CaughtUp {
    std::string sensor;
    std::string outcome;              // "caught up: ..." or why the gap stays frozen
    bool ok = false;
    std::size_t samples = 0;          // history samples stepped
    double input_s = 0.0;             // their span of input time, s
    double wall_s = 0.0;              // asking and stepping them, s of wall time
  };
  std::vector<CaughtUp> caught_up_;
  bool load_catch_up_parameters();
  /// At the sensor's first live sample after a restart with a snapshot: true when the items were
  /// resumed and the missed samples stepped from the history; false: nothing done (resume with a gap).
  bool catch_up(std::size_t sensor);
  void catch_up_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& stat);
};

}  // namespace rocking_monitor::live
