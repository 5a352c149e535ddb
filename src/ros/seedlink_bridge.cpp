// SeedLinkBridge: parameters, the client thread, per-record decoding and merging, Imu publication
// and /diagnostics (see seedlink_bridge.hpp).
#include "rocking_monitor/ros/seedlink_bridge.hpp"

#include <cmath>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/feeds/conflict_mark.hpp"
#include "rocking_monitor/feeds/sequence_state.hpp"
#include "rocking_monitor/feeds/tcp_connection.hpp"

namespace rocking_monitor::live {
namespace {

// A number parameter, or a map from station name ("CI_RIN") to numbers; `found` false when absent.
bool station_number(const ::ros::NodeHandle& pnh, const std::string& name, const std::string& station, double& value,
                    bool& found) {
  found = false;
  if (!pnh.hasParam(name)) return true;
  XmlRpc::XmlRpcValue v;
  pnh.getParam(name, v);
  auto number = [&](XmlRpc::XmlRpcValue& x) {
    if (x.getType() == XmlRpc::XmlRpcValue::TypeDouble) { value = static_cast<double>(x); return true; }
    if (x.getType() == XmlRpc::XmlRpcValue::TypeInt) { value = static_cast<int>(x); return true; }
    return false;
  };
  if (v.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    if (!v.hasMember(station)) return true;
    found = number(v[station]);
  } else {
    found = number(v);
  }
  if (!found) ROS_FATAL("seedlink_bridge: ~%s must be a number or a map {NET_STA: number} (station %s)", name.c_str(), station.c_str());
  return found;
}

// ~server and ~streams: where to connect and what to ask for. False after a ROS_FATAL.
bool read_server_and_streams(const ::ros::NodeHandle& pnh, feeds::SessionConfig& cfg, std::string& server) {
  if (!pnh.getParam("server", server)) {
    ROS_FATAL("seedlink_bridge: ~server (host:port of the SeedLink server, e.g. localhost:18000) is required");
    return false;
  }
  // A list of strings, or one string with the items separated by commas (handy on a command line).
  std::vector<std::string> items;
  std::string joined;
  if (pnh.getParam("streams", joined)) {
    std::size_t at = 0;
    for (std::size_t comma; (comma = joined.find(',', at)) != std::string::npos; at = comma + 1) items.push_back(joined.substr(at, comma - at));
    items.push_back(joined.substr(at));
  } else if (!pnh.getParam("streams", items)) {
    ROS_FATAL("seedlink_bridge: ~streams (a list of NET_STA:SELECTORS, e.g. [\"CI_RIN:HN?\"], or one string "
              "\"CI_RIN:HN?,IU_ANMO:00HN?\") is required");
    return false;
  }
  try {
    feeds::parse_host_port(server, cfg.host, cfg.port);
    cfg.streams = feeds::parse_streams(items);
  } catch (const std::invalid_argument& e) {
    ROS_FATAL("seedlink_bridge: %s", e.what());
    return false;
  }
  return true;
}

// The session's timeouts and reconnection backoff, each > 0 s. False after a ROS_FATAL.
bool read_session_timing(const ::ros::NodeHandle& pnh, feeds::SessionConfig& cfg) {
  pnh.param("connect_timeout", cfg.connect_timeout_s, cfg.connect_timeout_s);
  pnh.param("keepalive", cfg.keepalive_s, cfg.keepalive_s);
  pnh.param("idle_timeout", cfg.idle_timeout_s, cfg.idle_timeout_s);
  pnh.param("record_timeout", cfg.record_timeout_s, cfg.record_timeout_s);
  pnh.param("backoff_min", cfg.backoff_min_s, cfg.backoff_min_s);
  pnh.param("backoff_max", cfg.backoff_max_s, cfg.backoff_max_s);
  for (double v : {cfg.connect_timeout_s, cfg.keepalive_s, cfg.idle_timeout_s, cfg.record_timeout_s, cfg.backoff_min_s,
                   cfg.backoff_max_s}) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      ROS_FATAL("seedlink_bridge: ~connect_timeout, ~keepalive, ~idle_timeout, ~record_timeout, ~backoff_min and "
                "~backoff_max must be > 0 s");
      return false;
    }
  }
  return true;
}

}  // namespace

SeedLinkBridge::SeedLinkBridge(::ros::NodeHandle nh, ::ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {}

SeedLinkBridge::~SeedLinkBridge() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (session_) save_state();
}

void SeedLinkBridge::save_state() {
  if (state_file_.empty()) return;
  std::map<std::string, std::uint32_t> now = saved_state_;
  for (std::size_t i = 0; i < stations_.size(); ++i)
    if (const auto seq = session_->last_sequence(i)) now[stations_[i].spec.name()] = *seq;
  if (now == saved_state_) return;
  try {
    feeds::write_sequence_state(state_file_, now);
    saved_state_ = now;
  } catch (const std::runtime_error& e) {
    ++state_write_failures_;
    ROS_WARN_THROTTLE(30.0, "seedlink_bridge: %s", e.what());
  }
}

bool SeedLinkBridge::init() {
  feeds::SessionConfig cfg;
  std::string server;
  if (!read_server_and_streams(pnh_, cfg, server) || !read_session_timing(pnh_, cfg)) return false;
  bool add_gravity = true;
  pnh_.param("add_gravity", add_gravity, true);
  gravity_ = add_gravity ? core::kGravity : 0.0;
  std::string frame_id;
  pnh_.param("frame_id", frame_id, std::string());
  int queue_size = 2000;
  pnh_.param("queue_size", queue_size, queue_size);
  if (queue_size < 1) {
    ROS_FATAL("seedlink_bridge: ~queue_size = %d must be >= 1 (messages)", queue_size);
    return false;
  }
  if (!init_stations(cfg.streams, frame_id, queue_size) || !init_history()) return false;
  init_diagnostics(server);
  if (!start_session(cfg)) return false;
  ROS_INFO("seedlink_bridge: %zu station(s) from %s; up %s gravity", stations_.size(), server.c_str(),
           add_gravity ? "includes +9.80665 m/s^2 of" : "excludes");
  return true;
}

bool SeedLinkBridge::init_stations(const std::vector<feeds::StreamSpec>& streams, const std::string& frame_id,
                                   int queue_size) {
  stations_.resize(streams.size());
  for (std::size_t i = 0; i < streams.size(); ++i) {
    Station& s = stations_[i];
    s.spec = streams[i];
    const std::string name = s.spec.name();
    double gain = 0.0, azimuth = 0.0;
    bool has_gain = false, has_azimuth = false;
    if (!station_number(pnh_, "gain", name, gain, has_gain) || !station_number(pnh_, "azimuth", name, azimuth, has_azimuth))
      return false;
    if (!has_gain) {
      // Counts are the instrument's; nothing here can know what one count is in m/s^2.
      ROS_FATAL("seedlink_bridge: station %s: ~gain is missing: give the sensitivity in counts per m/s^2 (StationXML "
                "InstrumentSensitivity, or the recorder's sheet: counts per g / 9.80665), as a number or {%s: value}",
                name.c_str(), name.c_str());
      return false;
    }
    try {
      s.merger = std::make_unique<feeds::StationMerger>(gain, azimuth, has_azimuth);
    } catch (const std::invalid_argument& e) {
      ROS_FATAL("seedlink_bridge: station %s: ~gain / ~azimuth: %s", name.c_str(), e.what());
      return false;
    }
    if (!has_azimuth)
      ROS_INFO("seedlink_bridge: station %s: no ~azimuth: only N/E/Z channels are used (1/2 channels need the azimuth of 1)",
               name.c_str());
    s.pub = pnh_.advertise<sensor_msgs::Imu>(name + "/imu", static_cast<std::uint32_t>(queue_size));
    s.msg.header.frame_id = frame_id.empty() ? name : frame_id;
    s.msg.orientation_covariance[0] = -1.0;       // no orientation (REP 145)
    s.msg.angular_velocity_covariance[0] = -1.0;  // no gyroscope
  }
  return true;
}

bool SeedLinkBridge::init_history() {
  try {
    // The rate is the records' (known at the first): the rings are sized for the highest expected.
    const double history_length = read_history_length(pnh_);
    double max_rate = 250.0;
    pnh_.param("history_max_rate", max_rate, max_rate);
    if (history_length > 0.0) {
      history_ = std::make_unique<SampleHistoryServer>(history_length);
      for (Station& s : stations_)
        s.history = history_->add_topic(s.pub.getTopic(), "sensor_msgs/Imu", s.msg.header.frame_id, max_rate);
      history_->advertise(pnh_);
    }
  } catch (const std::invalid_argument& e) {
    ROS_FATAL("seedlink_bridge: ~history_length / ~history_max_rate: %s", e.what());
    return false;
  }
  return true;
}

void SeedLinkBridge::init_diagnostics(const std::string& server) {
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(nh_, pnh_);
  diagnostics_->setHardwareID("seedlink " + server);
  diagnostics_->add("seedlink connection", this, &SeedLinkBridge::connection_diagnostics);
  for (std::size_t i = 0; i < stations_.size(); ++i) {
    diagnostics_->add("seedlink station " + stations_[i].spec.name(),
                      [this, i](diagnostic_updater::DiagnosticStatusWrapper& st) { station_diagnostics(i, st); });
  }
  diagnostics_timer_ = nh_.createWallTimer(::ros::WallDuration(0.25), [this](const ::ros::WallTimerEvent&) {
    diagnostics_->update();
    save_state();
  });
}

bool SeedLinkBridge::start_session(const feeds::SessionConfig& cfg) {
  session_ = std::make_unique<feeds::SeedLinkSession>(
      cfg, [this](std::size_t stream, std::uint32_t seq, const char* rec, std::size_t len) { on_record(stream, seq, rec, len); },
      [](feeds::SeedLinkSession::Level level, const std::string& what) {
        if (level == feeds::SeedLinkSession::Level::Info) ROS_INFO("seedlink_bridge: %s", what.c_str());
        else ROS_WARN("seedlink_bridge: %s", what.c_str());
      });
  pnh_.param("state_file", state_file_, std::string());
  if (!state_file_.empty()) {
    try {
      saved_state_ = feeds::read_sequence_state(state_file_);
    } catch (const std::runtime_error& e) {
      ROS_FATAL("seedlink_bridge: ~state_file: %s (delete the file to start from the server's next packets)", e.what());
      return false;
    }
    for (std::size_t i = 0; i < stations_.size(); ++i) {
      const auto it = saved_state_.find(stations_[i].spec.name());
      if (it == saved_state_.end()) continue;
      session_->resume_after(i, it->second);
      ROS_INFO("seedlink_bridge: %s resumes after packet %06X (%s)", it->first.c_str(), static_cast<unsigned>(it->second),
               state_file_.c_str());
    }
  }
  thread_ = std::thread([this] { session_->run(stop_); });
  return true;
}

void SeedLinkBridge::on_record(std::size_t stream, std::uint32_t /*sequence*/, const char* record, std::size_t length) {
  Station& s = stations_[stream];
  const feeds::MseedDecoder::Result r = decoder_.decode(record, length, decoded_);
  std::lock_guard<std::mutex> lock(mutex_);
  const ::ros::WallTime now = ::ros::WallTime::now();
  if (s.records > 0) s.max_record_pause = std::max(s.max_record_pause, (now - s.last_record_wall).toSec());
  s.last_record_wall = now;
  ++s.records;
  if (r == feeds::MseedDecoder::Result::UnknownEncoding) {
    ++s.unknown_encoding;
    s.last_unknown_encoding = decoded_.encoding;
    ROS_WARN_THROTTLE(5.0, "seedlink_bridge: %s: record dropped: %s", s.spec.name().c_str(), decoder_.error().c_str());
    return;
  }
  if (r != feeds::MseedDecoder::Result::Ok) {
    ++s.malformed;
    ROS_WARN_THROTTLE(5.0, "seedlink_bridge: %s: malformed record dropped: %s", s.spec.name().c_str(), decoder_.error().c_str());
    return;
  }
  s.merger->add(decoded_, [&](const feeds::MergedSample& m) {
    s.msg.header.stamp.fromNSec(static_cast<std::uint64_t>(m.time_ns));
    s.msg.linear_acceleration.x = m.enu[0];
    s.msg.linear_acceleration.y = m.enu[1];
    s.msg.linear_acceleration.z = m.enu[2] + gravity_;
    // A channel sent this time again with another value (overlapping records, issue 52): the first
    // values, marked as the UDP bridge marks its conflicts (docs/inputs.md); the variance stays 0
    // ("unknown", REP 145) otherwise.
    feeds::mark_conflicting(s.msg.linear_acceleration_covariance, m.conflict, 0.0);
    // Kept before it is published: a subscriber asking later finds whatever it did not receive. Not a
    // conflicting one: a monitor catching up meets the gap the live one met.
    if (history_ && !m.conflict) history_->push(s.history, s.msg.header.stamp, s.msg.linear_acceleration.x, s.msg.linear_acceleration.y,
                                 s.msg.linear_acceleration.z);
    s.pub.publish(s.msg);
    const double latency = static_cast<double>(static_cast<std::int64_t>(::ros::WallTime::now().toNSec()) - m.time_ns) * 1e-9;
    s.latency_last = latency;
    if (!s.latency_seen) s.latency_min = s.latency_max = latency;
    s.latency_min = std::min(s.latency_min, latency);
    s.latency_max = std::max(s.latency_max, latency);
    s.latency_seen = true;
  });
}

void SeedLinkBridge::connection_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  const feeds::SessionCounters& k = session_->counters();
  const std::uint64_t problems = k.malformed + k.out_of_sync + k.repeated_sequence + k.sequence_jumps + k.unrequested +
                                 k.error_replies + k.disconnects + k.server_restarts + k.slow_packets;
  const feeds::SessionConfig& c = session_->config();
  if (!session_->connected()) {
    st.summary(diagnostic_msgs::DiagnosticStatus::ERROR,
               "not connected to " + c.host + ":" + std::to_string(c.port) + ": " + session_->last_error());
  } else if (problems != reported_session_problems_) {
    st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "connected; new protocol problems or reconnects: " + session_->last_error());
  } else {
    st.summary(diagnostic_msgs::DiagnosticStatus::OK, "connected");
  }
  reported_session_problems_ = problems;
  st.add("connected", session_->connected());
  st.add("connects (handshakes done)", k.connects.load());
  st.add("reconnects (connections lost)", k.disconnects.load());
  st.add("failed connects", k.connect_failures.load());
  st.add("last outage (s)", session_->last_outage_s());
  st.add("total outage (s)", session_->total_outage_s());
  st.add("data packets", k.packets.load());
  st.add("info packets", k.info_packets.load());
  st.add("keep-alives sent", k.keepalives.load());
  st.add("malformed packets", k.malformed.load());
  st.add("framing lost", k.out_of_sync.load());
  st.add("repeated sequence numbers (dropped)", k.repeated_sequence.load());
  st.add("server restarts (renumbered, resynchronised)", k.server_restarts.load());
  st.add("sequence jumps", k.sequence_jumps.load());
  st.add("sequence numbers skipped", k.skipped_sequence.load());
  st.add("records of unrequested stations", k.unrequested.load());
  st.add("ERROR replies", k.error_replies.load());
  st.add("packets too slow (dripping link, reconnected)", k.slow_packets.load());
  st.add("last error", session_->last_error());
  st.add("state file", state_file_.empty() ? std::string("(not kept)") : state_file_);
  st.add("state file write failures", state_write_failures_);
}

void SeedLinkBridge::station_diagnostics(std::size_t i, diagnostic_updater::DiagnosticStatusWrapper& st) {
  std::lock_guard<std::mutex> lock(mutex_);
  Station& s = stations_[i];
  const feeds::MergerCounters& m = s.merger->counters();
  const std::uint64_t problems = s.malformed + s.unknown_encoding + m.gaps + m.overlaps + m.incomplete + m.foreign_records +
                                 m.rate_mismatches + m.late_samples;
  if (m.samples_out == 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no sample published yet");
  else if (problems != s.reported_problems) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "new data problems (see counts)");
  else st.summary(diagnostic_msgs::DiagnosticStatus::OK, "publishing");
  // Two sources, or a broken digitiser, on one stream (issue 52): an ERROR for good, beside the rest.
  if (m.overlap_conflicts > 0)
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::ERROR,
                    std::to_string(m.overlap_conflicts) + " samples sent again with other values (overlapping records; first kept)");
  s.reported_problems = problems;
  const auto seq = session_->last_sequence(i);
  char hex[16] = "none";
  if (seq) std::snprintf(hex, sizeof hex, "%06X", static_cast<unsigned>(*seq));
  st.add("topic", s.pub.getTopic());
  st.add("last sequence number", std::string(hex));
  st.add("channels", s.merger->channels()[0] + " " + s.merger->channels()[1] + " " + s.merger->channels()[2]);
  st.add("sample rate (Hz)", s.merger->sample_rate());
  st.add("records", s.records);
  st.add("samples published", m.samples_out);
  st.add("last data time (s)", static_cast<double>(s.merger->last_time_ns()) * 1e-9);
  st.add("latency of newest sample (s)", s.latency_last);
  st.add("latency min since last report (s)", s.latency_min);
  st.add("latency max since last report (s)", s.latency_max);
  st.add("longest pause between records (s)", s.max_record_pause);
  st.add("malformed records", s.malformed);
  st.add("unknown-encoding records", s.unknown_encoding);
  st.add("last unknown encoding", s.last_unknown_encoding);
  st.add("gaps", m.gaps);
  st.add("gap samples", m.gap_samples);
  st.add("overlaps", m.overlaps);
  st.add("overlap samples", m.overlap_samples);
  st.add("overlap conflicts (other values; first kept)", m.overlap_conflicts);
  st.add("conflicts marked on the published sample (variance inf)", m.conflicts_marked);
  st.add("incomplete times dropped", m.incomplete);
  st.add("late samples dropped", m.late_samples);
  st.add("breaks in published times", m.output_gaps);
  st.add("records of other channels", m.foreign_records);
  st.add("records at another rate", m.rate_mismatches);
  s.latency_seen = false;
}

}  // namespace rocking_monitor::live
