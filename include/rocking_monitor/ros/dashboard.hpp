#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/AccelStamped.h>
#include <sensor_msgs/Imu.h>
#include <nlohmann/json_fwd.hpp>
#include <ros/ros.h>

#include "rocking_monitor/CriterionExceedance.h"
#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/RockingStateArray.h"
#include "rocking_monitor/monitoring/alarm_dedup.hpp"
#include "rocking_monitor/ros/catalogue.hpp"

namespace httplib {
class Server;
}

namespace rocking_monitor::live {

/// The operator's live view (issue 14): a read-only web page served by the node itself (no CDN, works
/// offline) with the floor plan, the selected item's side view and charts, the alarm log and sensor
/// health. Subscribes to the monitor's ~states, ~alarms, ~criteria and /diagnostics; reads the item
/// geometry and poses from the monitor's catalogue on the parameter server (`<monitor>/items`).
///
/// Threads: ROS callbacks (one spinner) and the HTTP server's pool share the cache under `mutex_`.
/// ROS never waits on a client: the states callback only swaps a shared pointer; deltas and alarms
/// are formatted once and queued to each Server-Sent-Events client, whose own HTTP thread writes them.
class Dashboard {
 public:
  Dashboard(::ros::NodeHandle nh, ::ros::NodeHandle pnh);
  ~Dashboard();
  Dashboard(const Dashboard&) = delete;
  Dashboard& operator=(const Dashboard&) = delete;

  /// Reads parameters, binds the port, subscribes. False (after a ROS_FATAL naming the parameter or
  /// the address) on bad configuration or a port that cannot be bound.
  bool init();

  /// http://address:port/ once bound (also set as the parameter ~url).
  const std::string& url() const { return url_; }

  /// JSON texts (used by the HTTP handlers; public so that they can be tested without a server).
  std::string snapshot_json() const;

  /// One item as in the snapshot (geometry, pose, full state of both planes); "" for an unknown id.
  std::string item_json(const std::string& id) const;

  /// {"id", "points": [[stamp s, signed theta/alpha, energy margin], ...]}: the item's last 60 s as
  /// sent to the pages; empty points for an unknown id or a quiet item.
  std::string history_json(const std::string& id) const;

  /// {"topic", "points": [[stamp s, a_x, a_y, a_z], ...]}: the input acceleration of the last 60 s
  /// (m/s^2, sensor axes, the at-rest reading removed), one point per 50 ms bin (its largest sample).
  std::string input_json() const;

  /// One file of the page, embedded in the binary (dashboard_assets.cpp) and served at `path`.
  struct WebAsset {
    const char* path;  // "/app.js"
    const char* type;  // its Content-Type
    const char* body;
  };
  /// The page (also served at "/"), its style and its ES modules: the entry app.js, the shared state.js
  /// and one module per panel (docs/dashboard.md).
  static const WebAsset kWebAssets[];
  static const std::size_t kWebAssetCount;

 private:
  // ---- state cache (dashboard_state.cpp)
  struct ItemGeometry {
    CatalogueItem entry;  // id, description, width, depth, cg_height, eccentricities, pose
    bool from_catalogue = true;  // false: seen in ~states only (drawn without geometry)
  };
  struct Sent {  // what the page last received for an item: a delta is sent when this changes
    std::uint8_t mode = 255;
    std::string plane;
    double rotation_ratio = 0.0, energy_margin = 0.0, theta = 0.0;
    std::uint32_t impacts = 0;
    bool valid = false;
    double p_overturned = -1.0;  // ensemble items: P(overturned) last sent
    double support_margin = 0.0;  // m, NaN without a support: a sliding item's margin changes alone
  };
  struct InputPoint {  // one 50 ms bin of the input acceleration (its sample of largest magnitude)
    double t;          // stamp, s
    float a[3];        // m/s^2, sensor axes, at-rest reading removed
  };
  struct Point {  // one chart point, as sent in a delta
    double t;      // input stamp, s
    float ratio;   // theta/alpha, signed by theta
    float margin;  // energy margin
  };
  struct Alarm {
    OverturnAlarm msg;  // the earliest copy received (a redundant pair: either monitor's)
    std::size_t row;    // its row in dedup_
  };

  bool load_parameters();
  void load_catalogue();
  void on_states(const RockingStateArray::ConstPtr& msg);
  void on_alarm(const OverturnAlarm::ConstPtr& msg) { on_alarm_from(monitor_, msg); }
  void on_pair_alarm(const OverturnAlarm::ConstPtr& msg) { on_alarm_from(pair_, msg); }
  /// One alarm once, however many copies (journal, re-sent after a restart, the pair's other monitor).
  void on_alarm_from(const std::string& source, const OverturnAlarm::ConstPtr& msg);
  void on_criterion(const CriterionExceedance::ConstPtr& msg);
  void on_diagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg);
  void on_update_timer(const ::ros::WallTimerEvent&);
  void on_catalogue_timer(const ::ros::WallTimerEvent&);
  void read_journal();  // the alarms of the monitor's open event, from its journal (docs/journal.md)
  // ---- the input acceleration (dashboard_input.cpp): the monitor does not republish its input
  void subscribe_input(const std::string& topic, bool imu);
  void on_imu(const sensor_msgs::Imu::ConstPtr& msg);
  void on_accel(const geometry_msgs::AccelStamped::ConstPtr& msg);
  void add_input_locked(double t, double x, double y, double z, bool gravity_included);
  void push_input();
  /// Maps ~states positions to items_, adding items the catalogue lacks (drawn without geometry);
  /// reread_catalogue: an unknown id or a new count asks for the catalogue to be read again.
  void rebuild_index_locked(const RockingStateArray& msg, bool reread_catalogue);
  nlohmann::json item_json_locked(std::size_t index, const RockingState* state) const;
  nlohmann::json health_json_locked() const;
  static nlohmann::json alarm_json(const OverturnAlarm& a);

  // ---- HTTP server (dashboard_http.cpp)
  /// ~keep_alive_timeout_s, ~keep_alive_max_requests, ~read_timeout_s, ~max_request_body_bytes (issue 54).
  bool load_server_limits();
  bool start_server();
  void stop_server();

  // ---- Server-Sent Events (dashboard_events.cpp)
  struct Client {
    std::deque<std::string> queue;  // formatted SSE frames waiting for this client's HTTP thread
    bool overflowed = false;        // fell too far behind: told to reload the snapshot
  };
  void publish_event(const std::string& event, const std::string& data);
  std::uint64_t add_client();
  void remove_client(std::uint64_t id);
  /// Blocks the calling HTTP thread (never ROS) up to `wait` for frames; empty: keep-alive due.
  /// False when the client is gone or the server stops.
  bool next_frames(std::uint64_t id, std::chrono::milliseconds wait, std::string& out);

  ::ros::NodeHandle nh_, pnh_;
  std::string bind_address_ = "127.0.0.1";
  int port_ = 8080;  // 0: any free port (tests); the bound one is in ~url
  std::string monitor_ = "/rocking_monitor";
  std::string pair_;  // ~pair: the other monitor of a redundant pair (launch/monitor_pair.launch); "" = none
  double update_rate_ = 10.0;  // Hz, at most 10: deltas to the page
  int max_clients_ = 8;        // SSE connections at once (each holds one HTTP thread)
  // Issue 54: what one client may hold. A connection, idle or not, holds one pool thread.
  int keep_alive_timeout_s_ = 5;       // s without a new request before an idle connection is closed
  int keep_alive_max_requests_ = 100;  // requests on one connection before it is closed
  int read_timeout_s_ = 5;             // s a receive may wait mid-request (per receive: no whole-request deadline)
  int max_request_body_bytes_ = 0;     // bytes; the dashboard takes no bodies: any larger one is 413
  std::string url_;
  std::string sensor_topic_;  // ~sensor_topic; empty: the first sensor of the monitor's catalogue
  std::string sensor_type_ = "imu";  // ~sensor_type with ~sensor_topic: imu | accel
  std::string input_topic_;   // subscribed now

  mutable std::mutex mutex_;  // guards everything below down to the SSE section
  std::vector<ItemGeometry> items_;
  std::unordered_map<std::string, std::size_t> index_of_;  // id -> items_
  std::vector<std::size_t> state_to_item_;                 // position in ~states -> items_
  std::vector<Sent> sent_;                                 // per items_
  // Per items_: the deltas of the last 60 s (at most 60 s x update_rate points; quiet items none).
  std::vector<std::deque<Point>> history_;
  RockingStateArray::ConstPtr latest_;                     // newest ~states (shared, not copied)
  bool latest_sent_ = true;
  std::deque<Alarm> alarms_;                               // newest first
  core::AlarmDedup dedup_;  // which copies are one alarm (docs/journal.md "A redundant pair")
  std::map<std::string, std::set<std::string>> criteria_;  // id -> "plane:criterion" exceeded now
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> health_;  // this monitor's statuses by name
  bool catalogue_loaded_ = false;
  bool catalogue_dirty_ = false;  // ~states named items the catalogue does not have: reread it
  std::uint64_t states_received_ = 0;
  ::ros::WallTime last_health_push_;
  std::deque<InputPoint> input_;       // last 60 s, 50 ms bins
  bool have_rest_ = false;             // at-rest reading known (the first sample's, as the monitor)
  double rest_[3] = {0.0, 0.0, 0.0};
  std::size_t input_pushed_ = 0;       // bins of input_ already sent on the event stream
  double input_pushed_t_ = 0.0;        // stamp of the last bin sent

  ::ros::Subscriber states_sub_, alarms_sub_, pair_alarms_sub_, criteria_sub_, diagnostics_sub_, input_sub_;
  ::ros::WallTimer update_timer_, catalogue_timer_;

  // ---- SSE clients, own lock so that formatting the snapshot never delays a push
  std::mutex clients_mutex_;
  std::condition_variable clients_cv_;
  std::map<std::uint64_t, Client> clients_;
  std::uint64_t next_client_ = 1;
  bool stopping_ = false;

  std::unique_ptr<httplib::Server> server_;
  std::thread server_thread_;
};

}  // namespace rocking_monitor::live
