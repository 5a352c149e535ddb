// udp_accel_bridge (udp_accel_bridge.hpp): a receive thread reads one datagram per sample, the
// feeds layer parses it and puts the stream back in order, and each released sample is published
// as sensor_msgs/Imu. The per-sample path reuses one message and allocates nothing of its own.
#include "rocking_monitor/ros/udp_accel_bridge.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/feeds/conflict_mark.hpp"
#include "rocking_monitor/feeds/datagram_key.hpp"

namespace rocking_monitor::live {
namespace {
// What the bridge asks the kernel for: a few seconds of datagrams at 1 kHz. Linux grants at most
// net.core.rmem_max and reads back twice what it granted, so with rmem_max >= 4 MiB this is met.
constexpr int kAskedRcvbufBytes = 4 << 20;
}  // namespace

UdpAccelBridge::UdpAccelBridge(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {}

UdpAccelBridge::~UdpAccelBridge() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  if (socket_ >= 0) ::close(socket_);
}

bool UdpAccelBridge::init() {
  std::string topic = "/ground/imu";
  std::string clock = "first_arrival";
  pnh_.param("bind_address", bind_address_, bind_address_);
  pnh_.param("port", port_, port_);
  pnh_.param("rate_hz", rate_hz_, rate_hz_);
  pnh_.param("reorder_window", window_, window_);
  pnh_.param("idle_flush", idle_flush_s_, idle_flush_s_);
  pnh_.param("clock", clock, clock);
  pnh_.param("add_gravity", add_gravity_, add_gravity_);
  pnh_.param("linear_acceleration_variance", accel_variance_, accel_variance_);
  pnh_.param("frame_id", frame_id_, frame_id_);
  pnh_.param("topic", topic, topic);
  auto bad = [](const std::string& what) {
    ROS_FATAL_STREAM("udp_accel_bridge: " << what);
    return false;
  };
  if (!(rate_hz_ > 0.0) || !std::isfinite(rate_hz_))
    return bad("~rate_hz must be the controller's sample rate, > 0 Hz");
  if (port_ < 1 || port_ > 65535) return bad("~port must be 1-65535, not " + std::to_string(port_));
  if (window_ < 0 || window_ > 1000) return bad("~reorder_window must be 0-1000 samples");
  if (!(idle_flush_s_ > 0.0)) return bad("~idle_flush must be > 0 s");
  if (clock == "first_arrival")
    clock_ = Clock::FirstArrival;
  else if (clock == "controller")
    clock_ = Clock::Controller;
  else
    return bad("~clock must be first_arrival or controller, not '" + clock + "'");
  if (!(accel_variance_ >= 0.0)) return bad("~linear_acceleration_variance must be >= 0 (m/s^2)^2");
  if (!read_allowed_senders()) return false;
  if (!read_key()) return false;

  // With a key, a far-behind sample is a replay (or a counter that went back), not a restart.
  sequencer_ = std::make_unique<feeds::SampleSequencer>(static_cast<std::size_t>(window_), datagram_key_.size == 0);
  grid_ = std::make_unique<feeds::TimeGrid>(rate_hz_);

  if (!open_socket()) return false;

  // REP 145: linear acceleration only; orientation and angular velocity "not provided".
  msg_.header.frame_id = frame_id_;
  msg_.orientation_covariance[0] = -1.0;
  msg_.angular_velocity_covariance[0] = -1.0;
  for (int k = 0; k < 3; ++k) msg_.linear_acceleration_covariance[4 * k] = accel_variance_;

  imu_pub_ = nh_.advertise<sensor_msgs::Imu>(topic, 1000);
  try {
    const double history_length = read_history_length(pnh_);
    if (history_length > 0.0) {
      history_ = std::make_unique<SampleHistoryServer>(history_length);
      history_->add_topic(imu_pub_.getTopic(), "sensor_msgs/Imu", frame_id_, rate_hz_);
      history_->advertise(pnh_);
    }
  } catch (const std::invalid_argument& e) {
    return bad(e.what());
  }
  updater_ = std::make_unique<diagnostic_updater::Updater>(nh_, pnh_);
  updater_->setHardwareID("udp:" + bind_address_ + ":" + std::to_string(port_));
  updater_->add("udp_accel_bridge", this, &UdpAccelBridge::diagnostics);
  diag_timer_ = nh_.createTimer(ros::Duration(0.5), [this](const ros::TimerEvent&) { updater_->update(); });

  running_ = true;
  thread_ = std::thread([this] { receive_loop(); });
  ROS_INFO_STREAM("udp_accel_bridge: listening on " << bind_address_ << ":" << port_ << ", " << rate_hz_
                                                    << " Hz, publishing " << imu_pub_.getTopic());
  return true;
}

// Binds ~bind_address:~port and sizes the receive buffer; false after a FATAL line saying why.
bool UdpAccelBridge::open_socket() {
  auto bad = [](const std::string& what) {
    ROS_FATAL_STREAM("udp_accel_bridge: " << what);
    return false;
  };
  socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (socket_ < 0) return bad(std::string("socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port_));
  if (::inet_pton(AF_INET, bind_address_.c_str(), &addr.sin_addr) != 1)
    return bad("~bind_address '" + bind_address_ + "' is not an IPv4 address");
  if (::bind(socket_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    return bad("cannot bind " + bind_address_ + ":" + std::to_string(port_) + ": " + std::strerror(errno));
  }
  int rcvbuf = kAskedRcvbufBytes;  // a burst of a few seconds at 1 kHz must not overflow the kernel buffer
  ::setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  // The kernel caps the request at net.core.rmem_max (and reports twice what it grants, for its
  // bookkeeping): read back what was got, so that a small buffer is said, not silently suffered.
  socklen_t rcvbuf_len = sizeof rcvbuf_bytes_;
  if (::getsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &rcvbuf_bytes_, &rcvbuf_len) != 0) rcvbuf_bytes_ = 0;
  if (rcvbuf_bytes_ < kAskedRcvbufBytes)
    ROS_WARN("udp_accel_bridge: receive buffer %d bytes, asked for %d: raise net.core.rmem_max (docs/inputs.md)",
             rcvbuf_bytes_, kAskedRcvbufBytes);
  timeval tv{};
  tv.tv_usec = 20000;  // wake up to flush a paused stream
  ::setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  return true;
}

void UdpAccelBridge::receive_loop() {
  char buf[2048];
  ros::WallTime last_datagram = ros::WallTime::now();
  while (running_ && ros::ok()) {
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(socket_, buf, sizeof buf, 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    const ros::Time arrival = ros::Time::now();
    if (n < 0) {
      // A paused stream: release what the reorder window holds (its holes are lost).
      if ((ros::WallTime::now() - last_datagram).toSec() >= idle_flush_s_) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (sequencer_->held() > 0) {
          sequencer_->flush();
          ++flushes_;
          publish_ready(arrival);
        }
      }
      continue;
    }
    last_datagram = ros::WallTime::now();
    std::lock_guard<std::mutex> lock(mutex_);
    // Pinned senders (issue 52): anyone else's datagram is counted per source, never parsed.
    if (!tally_.admit(senders_, ntohl(from.sin_addr.s_addr), ntohs(from.sin_port))) continue;
    if (last_sender_.empty()) {
      char ip[INET_ADDRSTRLEN] = "?";
      ::inet_ntop(AF_INET, &from.sin_addr, ip, sizeof ip);
      last_sender_ = std::string(ip) + ":" + std::to_string(ntohs(from.sin_port));
    }
    on_datagram(buf, static_cast<std::size_t>(n), ntohl(from.sin_addr.s_addr), ntohs(from.sin_port), arrival);
  }
}

bool UdpAccelBridge::read_allowed_senders() {
  // A list of strings, or one string of entries separated by commas or spaces (a launch argument).
  std::vector<std::string> entries;
  if (pnh_.hasParam("allowed_senders")) {
    XmlRpc::XmlRpcValue value;
    pnh_.getParam("allowed_senders", value);
    if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
      entries = feeds::split_sender_list(static_cast<std::string>(value));
    } else if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      for (int k = 0; k < value.size(); ++k) {
        if (value[k].getType() != XmlRpc::XmlRpcValue::TypeString) {
          ROS_FATAL_STREAM("udp_accel_bridge: ~allowed_senders entry " << k << " is not a string");
          return false;
        }
        for (auto& piece : feeds::split_sender_list(static_cast<std::string>(value[k]))) entries.push_back(piece);
      }
    } else {
      ROS_FATAL("udp_accel_bridge: ~allowed_senders must be a list of strings (a.b.c.d, a.b.c.d:port, a.b.c.d/nn)");
      return false;
    }
  }
  // A launch argument left blank ("") is no list: the bridge accepts anyone and warns.
  std::string error;
  if (!senders_.configure(entries, error)) {
    ROS_FATAL_STREAM("udp_accel_bridge: ~" << error);
    return false;
  }
  if (!senders_.pinned())
    ROS_WARN("udp_accel_bridge: no ~allowed_senders: any host on the network can feed ground motion");
  return true;
}

bool UdpAccelBridge::read_key() {
  pnh_.param("key_file", key_file_, key_file_);
  if (key_file_.empty()) return true;  // opt-in: no key, version-2 datagrams are refused (counted)
  std::string error;
  if (!feeds::read_key_file(key_file_, key_, error)) {
    ROS_FATAL_STREAM("udp_accel_bridge: ~key_file: " << error);
    return false;
  }
  datagram_key_ = feeds::DatagramKey{key_.data(), key_.size()};
  if (key_.size() < 16)
    ROS_WARN("udp_accel_bridge: the key in '%s' is %zu bytes; use 32 random bytes (docs/inputs.md)",
             key_file_.c_str(), key_.size());
  ROS_INFO("udp_accel_bridge: authenticated datagrams only (HMAC-SHA256, key from '%s')", key_file_.c_str());
  return true;
}

// An authentication refusal is counted per source (true); other errors are left to the caller.
bool UdpAccelBridge::count_refusal(feeds::DatagramError err, std::uint32_t address, std::uint16_t port) {
  switch (err) {
    case feeds::DatagramError::Unauthenticated:
      unauthenticated_.add(address, port);
      return true;
    case feeds::DatagramError::BadTag:
      bad_tag_.add(address, port);
      return true;
    case feeds::DatagramError::NoKey:
      no_key_.add(address, port);
      return true;
    default:
      return false;
  }
}

void UdpAccelBridge::on_datagram(const char* data, std::size_t size, std::uint32_t address, std::uint16_t port,
                                 const ros::Time& arrival) {
  ++datagrams_;
  feeds::AccelSample s;
  const feeds::DatagramError err = feeds::parse_datagram(data, size, datagram_key_, s);
  if (err != feeds::DatagramError::None) {
    if (count_refusal(err, address, port)) return;
    ++malformed_;
    last_error_ = feeds::to_string(err);
    return;
  }
  const int form = s.has_sequence ? 2 : 1;
  if (form_ != 0 && form_ != form) mixed_forms_ = true;
  form_ = form;
  if (!s.has_sequence) {
    const std::optional<std::uint64_t> seq = grid_->sequence(s.time_s);
    if (!seq) {
      ++off_grid_;
      return;
    }
    s.sequence = *seq;
  }
  sequencer_->push(s);
  publish_ready(arrival);
}

void UdpAccelBridge::publish_ready(const ros::Time& arrival) {
  for (std::size_t i = 0; i < sequencer_->ready_count(); ++i) {
    const feeds::AccelSample& s = sequencer_->ready()[i];
    if (clock_ == Clock::FirstArrival && !first_arrival_) {
      first_arrival_ = arrival;
      first_time_s_ = s.time_s;
    }
    const double since_first = s.time_s - first_time_s_;
    const double stamp = clock_ == Clock::FirstArrival ? first_arrival_->toSec() + since_first : s.time_s;
    if (!(stamp > 0.0) || stamp > 4294967295.0) {
      ++malformed_;
      last_error_ = "time out of the range of a ROS stamp (with ~clock controller: seconds since 1970)";
      continue;
    }
    if (clock_ == Clock::FirstArrival) {
      const std::int64_t ns = static_cast<std::int64_t>(first_arrival_->toNSec()) + std::llround(since_first * 1e9);
      msg_.header.stamp.fromNSec(static_cast<std::uint64_t>(ns));  // > 0: checked above
    } else {
      msg_.header.stamp.fromSec(stamp);
    }
    msg_.header.seq = static_cast<std::uint32_t>(s.sequence);
    msg_.linear_acceleration.x = s.accel[0];
    msg_.linear_acceleration.y = s.accel[1];
    msg_.linear_acceleration.z = s.accel[2] + (add_gravity_ ? core::kGravity : 0.0);
    // A conflicting sample (issue 52) keeps its values but says they are not to be trusted:
    // infinite variance (docs/inputs.md); REP 145's -1 would say "no data" and discard them.
    feeds::mark_conflicting(msg_.linear_acceleration_covariance, s.conflict, accel_variance_);
    // Kept before it is published: a subscriber asking later finds whatever it did not receive.
    // Not a conflicting one: the history has no mark, and a monitor catching up from it should meet
    // the gap the live monitor met (it does not step on the sample either).
    if (history_ && !s.conflict) history_->push(0, msg_.header.stamp, msg_.linear_acceleration.x, msg_.linear_acceleration.y,
                                 msg_.linear_acceleration.z);
    imu_pub_.publish(msg_);
    ++published_;
    last_arrival_minus_stamp_s_ = arrival.toSec() - stamp;
    max_arrival_minus_stamp_s_ = std::max(max_arrival_minus_stamp_s_, last_arrival_minus_stamp_s_);
  }
}

// The senders' part of the summary, which outranks the stream's own: a second source on an
// unpinned port is ERROR (two streams interleaved are not ground motion), no list is WARN.
void UdpAccelBridge::sender_summary(diagnostic_updater::DiagnosticStatusWrapper& st) const {
  using diagnostic_msgs::DiagnosticStatus;
  // With a key, a datagram from anyone else fails authentication (auth_status says so): no list is fine.
  if (!senders_.pinned() && datagram_key_.size > 0) return;
  if (!senders_.pinned() && tally_.admitted_sources() >= 2)
    st.summary(DiagnosticStatus::ERROR,
               "several senders feed one stream: " + feeds::SenderTally::describe(tally_.admitted()));
  else if (!senders_.pinned())
    st.summary(DiagnosticStatus::WARN, "no allowed_senders: any host on the network can feed ground motion");
  else if (tally_.dropped_total() > 0)
    st.summary(DiagnosticStatus::WARN,
               "datagrams from senders not allowed dropped: " + feeds::SenderTally::describe(tally_.dropped()));
}

// Authentication (issue 52): any refused datagram is an ERROR, since either someone without the
// key is sending, or the real controller is not (yet) configured with it.
void UdpAccelBridge::auth_status(diagnostic_updater::DiagnosticStatusWrapper& st) const {
  using diagnostic_msgs::DiagnosticStatus;
  std::string refused;
  auto add = [&refused](const char* kind, const feeds::SourceCounter& c) {
    if (c.total() == 0) return;
    refused += (refused.empty() ? "" : "; ") + std::string(kind) + ": " + c.describe();
  };
  add("unauthenticated", unauthenticated_);
  add("bad tag", bad_tag_);
  add("version 2 without key_file", no_key_);
  if (!refused.empty()) st.mergeSummary(DiagnosticStatus::ERROR, "datagrams refused by authentication: " + refused);
  const std::uint64_t stale = sequencer_->counts().stale;
  if (stale > 0)
    st.mergeSummary(DiagnosticStatus::ERROR, std::to_string(stale) + " samples far behind the stream dropped "
                                             "(replayed, or the sender's counter went back)");
  st.add("authentication", datagram_key_.size > 0 ? "HMAC-SHA256, key_file " + key_file_
                                                  : std::string("none (no key_file)"));
  st.add("dropped, unauthenticated (no tag)", unauthenticated_.total());
  st.add("dropped, bad tag", bad_tag_.total());
  st.add("dropped, version 2 without key_file", no_key_.total());
  st.add("senders unauthenticated", unauthenticated_.describe());
  st.add("senders with a bad tag", bad_tag_.describe());
  st.add("senders of version 2 without key_file", no_key_.describe());
}

void UdpAccelBridge::diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  std::lock_guard<std::mutex> lock(mutex_);
  const feeds::SequenceCounts& c = sequencer_->counts();
  st.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  sender_summary(st);
  // mergeSummary keeps the worse level and joins the messages of the same level.
  if (datagrams_ == 0)
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "no datagrams yet");
  else if (mixed_forms_)
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::ERROR, "text and binary datagrams mixed on one port");
  else if (c.conflicts > 0)  // issue 52: never silent, two sources or a broken controller
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::ERROR,
                    std::to_string(c.conflicts) + " sequence numbers sent twice with different values (first kept)");
  else if (c.lost + c.late + c.duplicates + malformed_ + off_grid_ > 0)
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "samples lost, late, duplicated or malformed");
  auth_status(st);
  if (rcvbuf_bytes_ < kAskedRcvbufBytes)
    st.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "receive buffer " + std::to_string(rcvbuf_bytes_) +
                                                                  " bytes: raise net.core.rmem_max");
  st.add("port", port_);
  st.add("receive buffer (bytes)", rcvbuf_bytes_);
  st.add("sender", last_sender_);
  st.add("allowed senders", senders_.pinned() ? std::to_string(senders_.rules().size()) + " entries" : "any (none set)");
  st.add("senders admitted", feeds::SenderTally::describe(tally_.admitted()));
  st.add("senders dropped", feeds::SenderTally::describe(tally_.dropped()));
  st.add("dropped (sender not allowed)", tally_.dropped_total());
  st.add("dropped, sources beyond the list", tally_.unlisted_dropped());
  st.add("form", form_ == 0 ? "none yet" : form_ == 1 ? "text" : "binary");
  st.add("datagrams", datagrams_);
  st.add("malformed", malformed_);
  st.add("last malformed", last_error_);
  st.add("off the time grid (text)", off_grid_);
  st.add("samples accepted", c.accepted);
  st.add("published", published_);
  st.add("lost", c.lost);
  st.add("reordered (published in order)", c.reordered);
  st.add("late (dropped)", c.late);
  st.add("duplicates (dropped)", c.duplicates);
  st.add("conflicts (same sequence, other values: dropped, first kept)", c.conflicts);
  st.add("conflicts marked on the published sample (variance inf)", c.conflicts_marked);
  st.add("last conflict (sequence)", c.conflicts > 0 ? std::to_string(c.last_conflict) : std::string("none"));
  st.add("resyncs (counter restarted)", c.resyncs);
  st.add("stale (far behind, with key_file: dropped)", c.stale);
  st.add("held in the reorder window", sequencer_->held());
  st.add("reorder window (samples)", window_);
  st.add("idle flushes", flushes_);
  st.add("next sequence", sequencer_->next_sequence());
  st.add("clock", clock_ == Clock::Controller ? "controller" : "first_arrival");
  st.add("clock offset (s)", first_arrival_ ? first_arrival_->toSec() - first_time_s_ : 0.0);
  st.add("arrival - stamp, last (s)", last_arrival_minus_stamp_s_);
  st.add("arrival - stamp, max (s)", max_arrival_minus_stamp_s_);
}

}  // namespace rocking_monitor::live
