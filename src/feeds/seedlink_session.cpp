// The SeedLink client's state machine: handshake, packet loop, back-off and resume (see the header).
#include "rocking_monitor/feeds/seedlink_session.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <thread>

#include "rocking_monitor/feeds/seedlink_protocol.hpp"
#include "rocking_monitor/feeds/tcp_connection.hpp"
#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor::feeds {
namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

SeedLinkSession::SeedLinkSession(SessionConfig config, RecordHandler on_record, LogHandler log)
    : config_(std::move(config)), on_record_(std::move(on_record)), log_(std::move(log)),
      last_sequence_(config_.streams.size()), latest_time_us_(config_.streams.size()) {}

std::optional<std::uint32_t> SeedLinkSession::last_sequence(std::size_t stream) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_sequence_.at(stream);
}
void SeedLinkSession::resume_after(std::size_t stream, std::uint32_t sequence) {
  std::lock_guard<std::mutex> lock(mutex_);
  last_sequence_.at(stream) = sequence & (kSequenceModulus - 1);
}
double SeedLinkSession::last_outage_s() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_outage_s_;
}
double SeedLinkSession::total_outage_s() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return total_outage_s_;
}
std::string SeedLinkSession::last_error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_error_;
}
void SeedLinkSession::note_error(const std::string& raw) {
  // Messages quote the server's replies: no control character may forge a log line (issue 54).
  const std::string what = printable_text(raw, 1024);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_error_ = what;
  }
  log_(Level::Warn, what);
}

bool SeedLinkSession::accept_sequence(std::size_t stream, std::uint32_t sequence, std::optional<std::int64_t> time_us,
                                      bool first, const std::string& where) {
  const auto last = last_sequence(stream);
  if (!last) return true;
  const std::string name = config_.streams[stream].name();
  auto hex6 = [](std::uint32_t n) {
    char text[8];
    std::snprintf(text, sizeof text, "%06X", static_cast<unsigned>(n));
    return std::string(text);
  };
  const std::string hex = hex6(sequence);
  const SequenceStep step = sequence_step(*last, sequence);
  if (step.kind == SequenceStep::Kind::Repeat) {
    // A true repeat was handed on before, so its record is no newer than the latest one handed on
    // (the latest over all channels: records of a station's channels interleave out of time order).
    // Newer data under an old number, or a lower number where last + 1 was asked for and no record
    // time is known yet: the server restarted and numbers afresh; dropping would lose it all.
    const std::optional<std::int64_t> last_time = latest_time_us_[stream];
    const bool newer = time_us && last_time && *time_us > *last_time;
    if (newer || (first && !last_time && time_us)) {
      ++counters_.server_restarts;
      note_error("seedlink " + where + ": " + name + ": packet " + hex + " is numbered at or before the last one (" + hex6(*last) +
                 ") but " + (newer ? "its record is newer" : "the server was asked for the next one") +
                 ": the server restarted its numbering; resynchronised");
      return true;
    }
    ++counters_.repeated_sequence;
    note_error("seedlink " + where + ": " + name + ": packet " + hex + " repeats or precedes the last one handed on: dropped");
    return false;
  }
  if (step.kind == SequenceStep::Kind::Jump) {
    ++counters_.sequence_jumps;
    counters_.skipped_sequence += step.skipped;
    note_error("seedlink " + where + ": " + name + ": " + std::to_string(step.skipped) + " sequence number(s) missing before packet " + hex);
  }
  return true;
}

void SeedLinkSession::run(const std::atomic<bool>& stop) {
  double backoff = config_.backoff_min_s;
  while (!stop.load()) {
    bool got_data = false;
    const std::uint64_t connects_before = counters_.connects.load();
    if (!session_once(stop, got_data)) break;
    if (counters_.connects.load() != connects_before) {  // an established connection was lost
      ++counters_.disconnects;
      lost_ = true;
      down_since_ = Clock::now();
    }
    if (got_data) backoff = config_.backoff_min_s;
    // Wait, in small slices so that a stop request is honoured at once.
    const auto until = Clock::now() + std::chrono::duration<double>(backoff);
    while (!stop.load() && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    backoff = std::min(backoff * 2.0, config_.backoff_max_s);
  }
  connected_ = false;
}

bool SeedLinkSession::failed(const TcpConnection& tcp, TcpConnection::Status s, const std::string& where,
                             const std::string& during) {
  if (s == TcpConnection::Status::Stopped) return false;
  note_error("seedlink " + where + ": " + during + ": " + tcp.error());
  return true;
}

TcpConnection::Status SeedLinkSession::command(TcpConnection& tcp, const std::string& cmd, bool reply,
                                               std::string& line) const {
  TcpConnection::Status st = tcp.send_all(cmd, config_.connect_timeout_s);
  if (st == TcpConnection::Status::Ok && reply) st = tcp.read_line(line, config_.connect_timeout_s);
  return st;
}

std::optional<bool> SeedLinkSession::greet(TcpConnection& tcp, const std::string& where, std::string& org) {
  std::string line;
  TcpConnection::Status s = command(tcp, hello_command(), true, line);
  if (s == TcpConnection::Status::Ok) s = tcp.read_line(org, config_.connect_timeout_s);
  if (s != TcpConnection::Status::Ok) {
    ++counters_.connect_failures;
    return failed(tcp, s, where, "HELLO");
  }
  if (!hello_version(line)) {
    ++counters_.connect_failures;
    note_error("seedlink " + where + ": the answer to HELLO ('" + line + "') is not a SeedLink server's");
    return true;
  }
  return std::nullopt;
}

std::optional<bool> SeedLinkSession::request_stream(TcpConnection& tcp, const std::string& where, std::size_t i,
                                                    bool& accepted) {
  accepted = false;
  std::string line;
  const StreamSpec& st = config_.streams[i];
  TcpConnection::Status s = command(tcp, station_command(st.network, st.station), true, line);
  if (s != TcpConnection::Status::Ok) {
    ++counters_.connect_failures;
    return failed(tcp, s, where, "STATION " + st.name());
  }
  if (classify_reply(line) != Reply::Ok) {
    ++counters_.error_replies;
    note_error("seedlink " + where + ": STATION " + st.station + " " + st.network + " refused: '" + line + "'");
    return std::nullopt;
  }
  bool selected = false;
  for (const std::string& sel : st.selectors) {
    s = command(tcp, select_command(sel), true, line);
    if (s != TcpConnection::Status::Ok) {
      ++counters_.connect_failures;
      return failed(tcp, s, where, "SELECT " + sel);
    }
    if (classify_reply(line) == Reply::Ok) {
      selected = true;
    } else {
      ++counters_.error_replies;
      note_error("seedlink " + where + ": " + st.name() + ": SELECT " + sel + " refused: '" + line + "'");
    }
  }
  if (!selected) return std::nullopt;
  std::optional<std::uint32_t> from;
  if (const auto last = last_sequence(i)) from = next_sequence(*last);
  s = command(tcp, data_command(from), true, line);
  if (s != TcpConnection::Status::Ok) {
    ++counters_.connect_failures;
    return failed(tcp, s, where, "DATA");
  }
  if (classify_reply(line) != Reply::Ok) {
    ++counters_.error_replies;
    note_error("seedlink " + where + ": " + st.name() + ": DATA refused: '" + line + "'");
    return std::nullopt;
  }
  accepted = true;
  return std::nullopt;
}

std::optional<bool> SeedLinkSession::request_streams(TcpConnection& tcp, const std::string& where,
                                                     std::size_t& accepted) {
  accepted = 0;
  for (std::size_t i = 0; i < config_.streams.size(); ++i) {
    bool ok = false;
    if (const std::optional<bool> end = request_stream(tcp, where, i, ok)) return end;
    if (ok) ++accepted;
  }
  if (accepted == 0) {
    ++counters_.connect_failures;
    note_error("seedlink " + where + ": the server accepted none of the requested stations");
    return true;
  }
  std::string line;
  const TcpConnection::Status s = command(tcp, end_command(), false, line);
  if (s != TcpConnection::Status::Ok) {
    ++counters_.connect_failures;
    return failed(tcp, s, where, "END");
  }
  return std::nullopt;
}

void SeedLinkSession::note_connected(const std::string& where, std::size_t accepted, const std::string& org) {
  if (lost_) {  // this handshake ends the outage since the last connection was lost
    std::lock_guard<std::mutex> lock(mutex_);
    last_outage_s_ = seconds_since(down_since_);
    total_outage_s_ += last_outage_s_;
  }
  ++counters_.connects;
  connected_ = true;
  log_(Level::Info, "seedlink " + where + ": streaming " + std::to_string(accepted) + " station(s) (server: " + printable_text(org, 200) + ")");
}

void SeedLinkSession::hand_on(const char* record, std::uint32_t sequence, std::vector<bool>& seen_this_connection,
                              const std::string& where, bool& got_data) {
  std::string net, sta;
  std::size_t stream = config_.streams.size();
  if (record_station(record, kSeedLinkRecordBytes, net, sta)) {
    for (std::size_t i = 0; i < config_.streams.size(); ++i)
      if (config_.streams[i].network == net && config_.streams[i].station == sta) stream = i;
  }
  if (stream == config_.streams.size()) {
    ++counters_.unrequested;
    return;
  }
  const std::optional<std::int64_t> time_us = record_start_us(record, kSeedLinkRecordBytes);
  const bool first = !seen_this_connection[stream];
  seen_this_connection[stream] = true;
  if (!accept_sequence(stream, sequence, time_us, first, where)) return;
  if (time_us && (!latest_time_us_[stream] || *time_us > *latest_time_us_[stream])) latest_time_us_[stream] = time_us;
  got_data = true;
  ++counters_.packets;
  on_record_(stream, sequence, record, kSeedLinkRecordBytes);
  std::lock_guard<std::mutex> lock(mutex_);
  last_sequence_[stream] = sequence;
}

bool SeedLinkSession::stream_packets(TcpConnection& tcp, const std::string& where, bool& got_data) {
  std::array<char, kSeedLinkPacketBytes> packet{};
  std::vector<bool> seen_this_connection(config_.streams.size(), false);
  auto last_byte = Clock::now();
  TcpConnection::Status s;
  for (;;) {
    s = tcp.wait_readable(config_.keepalive_s);
    if (s == TcpConnection::Status::Timeout) {
      if (seconds_since(last_byte) >= config_.idle_timeout_s) {
        connected_ = false;
        note_error("seedlink " + where + ": nothing received for " + std::to_string(config_.idle_timeout_s) + " s: reconnecting");
        return true;
      }
      ++counters_.keepalives;
      s = tcp.send_all(keepalive_command(), config_.connect_timeout_s);
      if (s != TcpConnection::Status::Ok) {
        connected_ = false;
        return failed(tcp, s, where, "keep-alive");
      }
      continue;
    }
    if (s != TcpConnection::Status::Ok) break;
    // The whole packet within record_timeout_s of its first byte: a drip of a byte now and then
    // would otherwise keep an idle timeout from ever firing while no record comes.
    const auto packet_start = Clock::now();
    s = tcp.read_exact(packet.data(), kSeedLinkHeaderBytes, config_.record_timeout_s);
    if (s != TcpConnection::Status::Ok) break;
    last_byte = Clock::now();
    const PacketHeader h = parse_packet_header(packet.data());
    if (h.kind == PacketHeader::Kind::OutOfSync) {
      ++counters_.out_of_sync;
      connected_ = false;
      note_error("seedlink " + where + ": a packet header does not start with 'SL': the stream lost its framing; reconnecting");
      return true;
    }
    const double left_s = std::max(1e-3, config_.record_timeout_s - seconds_since(packet_start));
    s = tcp.read_exact(packet.data() + kSeedLinkHeaderBytes, kSeedLinkRecordBytes, left_s);
    if (s != TcpConnection::Status::Ok) break;
    if (h.kind == PacketHeader::Kind::Info) {
      ++counters_.info_packets;
      continue;
    }
    if (h.kind == PacketHeader::Kind::Malformed) {
      ++counters_.malformed;
      note_error("seedlink " + where + ": malformed packet header '" + std::string(packet.data(), 8) + "' dropped");
      continue;
    }
    hand_on(packet.data() + kSeedLinkHeaderBytes, h.sequence, seen_this_connection, where, got_data);
  }
  connected_ = false;
  if (s == TcpConnection::Status::Timeout) {
    ++counters_.slow_packets;
    note_error("seedlink " + where + ": a packet did not come whole within " + std::to_string(config_.record_timeout_s) +
               " s (~record_timeout): the link drips; reconnecting");
    return true;
  }
  return failed(tcp, s, where, "streaming");
}

bool SeedLinkSession::session_once(const std::atomic<bool>& stop, bool& got_data) {
  TcpConnection tcp;
  tcp.set_stop_flag(&stop);
  const std::string where = config_.host + ":" + std::to_string(config_.port);
  const TcpConnection::Status s = tcp.open(config_.host, config_.port, config_.connect_timeout_s);
  if (s != TcpConnection::Status::Ok) {
    ++counters_.connect_failures;
    return failed(tcp, s, where, "connect");
  }
  std::string org;
  if (const std::optional<bool> end = greet(tcp, where, org)) return *end;
  std::size_t accepted = 0;
  if (const std::optional<bool> end = request_streams(tcp, where, accepted)) return *end;
  note_connected(where, accepted, org);
  return stream_packets(tcp, where, got_data);
}

}  // namespace rocking_monitor::feeds
