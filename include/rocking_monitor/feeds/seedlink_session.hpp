#pragma once

// A SeedLink 3 client session in multi-station mode: connect, HELLO, per station STATION + SELECT +
// DATA [next sequence number], END, then packets until the connection fails; then back off
// (doubling from backoff_min_s to backoff_max_s) and reconnect, resuming every station after its
// last sequence number, so that a server restart loses and repeats nothing the server still holds.
//
// Every packet is checked: malformed headers, INFO packets (the keep-alive replies), repeated or
// skipped sequence numbers, records of stations not asked for. Each is counted; a malformed
// packet is dropped and the session goes on, a stream that lost its framing is reconnected.
//
// A packet numbered at or before the last one is a repeat unless the server restarted and numbers
// from lower values again (issue 54): a record newer in record time than any handed on, or
// the first packet of a connection when the stream's last record time is unknown (resumed from a
// state file: the server was asked for last + 1 and, not holding it, began lower). Either is
// accepted, counted in `server_restarts` and said in last_error(): the numbers restart from there.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "rocking_monitor/feeds/stream_list.hpp"
#include "rocking_monitor/feeds/tcp_connection.hpp"

namespace rocking_monitor::feeds {

struct SessionConfig {
  std::string host = "localhost";
  std::uint16_t port = 18000;
  std::vector<StreamSpec> streams;
  double connect_timeout_s = 10.0;  ///< s, for the TCP connect and each handshake reply
  double keepalive_s = 15.0;        ///< s without a packet before "INFO ID" is sent (keep-alive)
  double idle_timeout_s = 60.0;     ///< s without any byte before the connection is dropped and redone
  double record_timeout_s = 10.0;   ///< s for a whole packet (8 + 512 bytes) once its first byte came
  double backoff_min_s = 1.0;       ///< s, first wait before reconnecting
  double backoff_max_s = 30.0;      ///< s, longest wait (doubling in between)
};

/// Counters (read from other threads while the session runs).
struct SessionCounters {
  std::atomic<std::uint64_t> connects{0};             ///< handshakes completed
  std::atomic<std::uint64_t> connect_failures{0};     ///< connects or handshakes that failed
  std::atomic<std::uint64_t> disconnects{0};          ///< established connections lost
  std::atomic<std::uint64_t> packets{0};              ///< data packets handed on
  std::atomic<std::uint64_t> info_packets{0};         ///< INFO packets read and dropped
  std::atomic<std::uint64_t> keepalives{0};           ///< "INFO ID" keep-alives sent
  std::atomic<std::uint64_t> malformed{0};            ///< headers neither "SL"+hex6 nor "SLINFO", dropped
  std::atomic<std::uint64_t> out_of_sync{0};          ///< byte streams that lost framing (reconnected)
  std::atomic<std::uint64_t> repeated_sequence{0};    ///< packets at or before the last number, dropped
  std::atomic<std::uint64_t> server_restarts{0};      ///< lower numbers on newer records: the server renumbered
  std::atomic<std::uint64_t> sequence_jumps{0};       ///< packets after a hole in the numbers
  std::atomic<std::uint64_t> skipped_sequence{0};     ///< sequence numbers never received
  std::atomic<std::uint64_t> unrequested{0};          ///< records of no requested station, dropped
  std::atomic<std::uint64_t> error_replies{0};        ///< ERROR answers to STATION / SELECT / DATA
  std::atomic<std::uint64_t> slow_packets{0};         ///< packets not whole within record_timeout_s (reconnected)
};

class SeedLinkSession {
 public:
  enum class Level { Info, Warn, Error };
  /// A data packet of stream `stream` (index into config.streams): its record bytes.
  using RecordHandler = std::function<void(std::size_t stream, std::uint32_t sequence, const char* record, std::size_t length)>;
  using LogHandler = std::function<void(Level, const std::string&)>;

  SeedLinkSession(SessionConfig config, RecordHandler on_record, LogHandler log);

  /// Connects, streams, reconnects with back-off, until `stop` becomes true.
  void run(const std::atomic<bool>& stop);

  const SessionCounters& counters() const { return counters_; }
  /// Last sequence number handed on for the stream (nothing before its first packet).
  std::optional<std::uint32_t> last_sequence(std::size_t stream) const;
  /// Sets where the stream resumes (a number kept from an earlier run); before run() only.
  void resume_after(std::size_t stream, std::uint32_t sequence);
  bool connected() const { return connected_.load(); }
  /// Length of the last outage (connection lost -> next handshake done), s; total of all, s.
  double last_outage_s() const;
  double total_outage_s() const;
  std::string last_error() const;
  const SessionConfig& config() const { return config_; }

 private:
  /// One connection: false when it ended by `stop`.
  bool session_once(const std::atomic<bool>& stop, bool& got_data);
  void note_error(const std::string& raw);
  // session_once()'s steps. Those returning std::optional<bool>: nullopt to go on, else session_once()'s
  // answer (false: ended by `stop`).
  /// The answer to a failed network step: false when `stop` ended it, else the error is noted and true.
  bool failed(const TcpConnection& tcp, TcpConnection::Status s, const std::string& where, const std::string& during);
  /// Sends a command and, with `reply`, reads its one-line answer.
  TcpConnection::Status command(TcpConnection& tcp, const std::string& cmd, bool reply, std::string& line) const;
  std::optional<bool> greet(TcpConnection& tcp, const std::string& where, std::string& org);  ///< HELLO
  /// STATION, SELECT and DATA of each stream (`accepted` counts those the server took), then END.
  std::optional<bool> request_streams(TcpConnection& tcp, const std::string& where, std::size_t& accepted);
  std::optional<bool> request_stream(TcpConnection& tcp, const std::string& where, std::size_t i, bool& accepted);
  void note_connected(const std::string& where, std::size_t accepted, const std::string& org);
  /// The packet loop until the connection ends: keep-alives, timeouts, framing.
  bool stream_packets(TcpConnection& tcp, const std::string& where, bool& got_data);
  /// A data packet's record to its stream's handler, when requested and in sequence.
  void hand_on(const char* record, std::uint32_t sequence, std::vector<bool>& seen_this_connection,
               const std::string& where, bool& got_data);
  /// Whether the stream's packet `sequence` (record start `time_us`) is handed on; counts and says
  /// why not, or that the server renumbered. `first` marks the stream's first packet of a connection.
  bool accept_sequence(std::size_t stream, std::uint32_t sequence, std::optional<std::int64_t> time_us, bool first,
                       const std::string& where);

  SessionConfig config_;
  RecordHandler on_record_;
  LogHandler log_;
  SessionCounters counters_;
  std::atomic<bool> connected_{false};
  bool lost_ = false;  ///< a connection was established and lost (session thread only)
  std::chrono::steady_clock::time_point down_since_;
  mutable std::mutex mutex_;  // guards the fields below
  std::vector<std::optional<std::uint32_t>> last_sequence_;
  std::vector<std::optional<std::int64_t>> latest_time_us_;  ///< latest record start handed on (session thread)
  double last_outage_s_ = 0.0, total_outage_s_ = 0.0;
  std::string last_error_;
};

}  // namespace rocking_monitor::feeds
