#pragma once

// State snapshots (issue 29): every item's full model state written beside the alarm journal, so that
// a monitor killed during an earthquake and restarted at once continues each item from where it was
// instead of at rest. ROS-free: the node fills the sensors' stream positions and hands its items in.
//
// File (docs/journal.md, "State snapshots"): a 32-byte header, then the payload.
//   header: magic "RMSNAPSH", format version (u32), byte-order mark 0x01020304 (u32), payload size
//           (u64), CRC-32 of the payload (u32), CRC-32 of the 28 header bytes before it (u32)
//   payload: configuration fingerprint (u32: catalogue and model options), when written (f64, s
//           since 1970, node clock), the sensors (name, stream position, gravity baseline), the items
//           (id, whether started, every field of ItemMonitor::Saved, the ensemble's members).
// Values are in the machine's byte order (the mark refuses a file of another). Each model's state is
// written field by field from its Saved struct (no object memory is copied); reading checks every
// length, count and enum against the bytes that are there, so a damaged, truncated, foreign or
// stale file is refused with the file and the field, never half applied.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"

namespace rocking_monitor::core {

inline constexpr std::uint32_t kSnapshotVersion = 10;  // 2: the 3-D model's landing outcome, 128 base vertices; 3: its hull face; 4: its sliding (issue 51); 5: its frictional landings; 6: its pivot against the friction cone; 7: the footprint its contact on a support was cut for; 8: a pedestal reaching beyond a hull body's base, cuts made again on a corner, overturns at the events bound; 9: lips along the support's edges; 10: the 3-D model's flight
inline constexpr std::size_t kSnapshotHeaderBytes = 32;

/// A sensor's stream position at the snapshot (what the node needs to continue its items).
struct SnapshotSensor {
  std::string name;
  std::int64_t last_stamp_ns = 0;  ///< stamp of the last sample stepped, ns since 1970
  std::int64_t epoch_ns = 0;       ///< the models' t = 0 (stamp of the run's first sample, shifted by gaps), ns since 1970
  double last_t = 0.0;             ///< s since the epoch of the last sample stepped (the models' time)
  double dt_nominal = 0.0;         ///< s, the running spectra's sample interval
  double min_dt = 0.0;             ///< s, shortest step between stamps seen
  bool baseline_initialized = false;
  double baseline[3] = {0.0, 0.0, 0.0};  ///< gravity baseline, m/s^2 (sensor frame)
  std::uint64_t samples = 0;       ///< samples stepped in this run
};

/// One item as read back.
struct SnapshotItem {
  std::string id;
  ItemMonitor::Saved monitor;
  bool has_ensemble = false;
  ItemEnsemble::Saved ensemble;
};

struct StateSnapshot {
  std::uint32_t fingerprint = 0;  ///< configuration_fingerprint() of the writer
  double written = 0.0;           ///< node clock when captured, s since 1970
  std::vector<SnapshotSensor> sensors;
  std::vector<SnapshotItem> items;
};

/// CRC-32 (zlib) of a text describing everything the models' state depends on (the catalogue and
/// the model options): a snapshot of another configuration is foreign.
std::uint32_t configuration_fingerprint(const std::string& text);

/// Encodes snapshots into a caller's buffer. Keep one: its scratch states keep their storage, so
/// that after the first snapshot encoding allocates nothing (the buffer keeps its capacity too).
class SnapshotEncoder {
 public:
  /// Starts a snapshot in out (cleared); then exactly `sensors` sensor() and `items` item() calls,
  /// then finish().
  void begin(std::vector<std::uint8_t>& out, std::uint32_t fingerprint, double written, std::size_t sensors,
             std::size_t items);
  void sensor(const SnapshotSensor& s);
  /// The item's monitor (brought up to date by the caller) and its ensemble (null: none).
  void item(const std::string& id, const ItemMonitor& monitor, const ItemEnsemble* ensemble);
  /// Writes the header. With checksums (seal_snapshot()) the buffer then holds the whole file;
  /// without, whoever writes it seals it (SnapshotFileWriter does, on its thread).
  void finish(bool checksums = true);

 private:
  std::vector<std::uint8_t>* out_ = nullptr;
  std::size_t pos_ = 0;  // bytes written into *out_
  ItemMonitor::Saved monitor_;
  ItemEnsemble::Saved ensemble_;
};

/// Fills in the checksums of an encoded snapshot (finish(false)).
void seal_snapshot(std::vector<std::uint8_t>& bytes);

/// Decodes a whole file's bytes. Empty string on success, else what is wrong, naming the field
/// ("payload checksum ...", "item 'vase' (2 of 10): plane x: adaptive: contact: mode = 9 ..."). `out`
/// is complete only on success.
std::string decode_snapshot(const std::uint8_t* data, std::size_t size, StateSnapshot& out);
/// Reads and decodes a file; errors begin with the path. `exists` (if given) tells a missing file
/// (the first start) from a bad one.
std::string read_snapshot(const std::string& path, StateSnapshot& out, bool* exists = nullptr);
/// Whether a decoded snapshot was written by this configuration: the fingerprint, then the sensors'
/// and items' ids in order. Empty string, else why it is foreign (naming the first difference).
std::string foreign_snapshot(const StateSnapshot& snapshot, std::uint32_t fingerprint,
                             const std::vector<std::string>& sensor_names, const std::vector<std::string>& item_ids);

/// Writes data to path durably: a temporary file beside it (path + ".tmp.XXXXXX", mkostemp: 0600, a
/// fresh name, never a planted link), write, fsync, rename over
/// path, fsync of the directory, as the journal keeps its lines. Empty string, else what failed
/// (path and errno text); path is then untouched (the previous snapshot stays).
std::string write_file_durably(const std::string& path, const std::uint8_t* data, std::size_t size);

/// Writes snapshots on a thread of its own, so that the sample path never waits for the disk: the
/// caller encodes into buffer() (SnapshotEncoder::finish(false)) and submit()s it; the thread seals it
/// (seal_snapshot()) and writes it with write_file_durably().
/// Two buffers: while one is written the next is encoded; a buffer submitted but not yet picked up
/// is replaced by a newer one (counted as superseded). A failed write (disk full, ...) is counted and
/// kept in status(); the caller goes on.
class SnapshotFileWriter {
 public:
  struct Status {
    std::uint64_t written = 0, failed = 0, superseded = 0;
    std::string last_error;          ///< of the last failed write ("" once one succeeds again)
    std::size_t last_bytes = 0;      ///< size of the last file written
    double last_write_s = 0.0, max_write_s = 0.0;  ///< wall time of a write (with fsync), s
  };
  /// Creates missing directories of path (an error shows in status() at the first write).
  explicit SnapshotFileWriter(std::string path);
  ~SnapshotFileWriter();
  SnapshotFileWriter(const SnapshotFileWriter&) = delete;
  SnapshotFileWriter& operator=(const SnapshotFileWriter&) = delete;

  const std::string& path() const { return path_; }
  /// The buffer to encode the next snapshot into (not the one being written).
  std::vector<std::uint8_t>& buffer();
  /// Hands the buffer from buffer() to the writing thread.
  void submit();
  /// Waits until every submitted snapshot is written or failed (tests, shutdown).
  void flush();
  Status status() const;

 private:
  void run();
  std::string path_;
  std::vector<std::uint8_t> buffers_[2];
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  int encoding_ = -1, pending_ = -1, writing_ = -1;
  bool stop_ = false;
  Status status_;
  std::thread thread_;
};

}  // namespace rocking_monitor::core
