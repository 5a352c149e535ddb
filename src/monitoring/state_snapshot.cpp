// The state snapshot's file format: header (magic, version, byte order, sizes, CRC-32s), encoder and
// decoder of the payload (its fields: state_snapshot_fields.hpp), and the checks of a snapshot read
// back (damaged, truncated, foreign). Writing the files: snapshot_file_writer.cpp.
#include "rocking_monitor/monitoring/state_snapshot.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "state_snapshot_fields.hpp"

namespace rocking_monitor::core {
namespace {

using namespace snapshot_fields;  // Writer, Reader, visit(): the payload's layout

constexpr char kMagic[8] = {'R', 'M', 'S', 'N', 'A', 'P', 'S', 'H'};
constexpr std::uint32_t kByteOrderMark = 0x01020304u;

std::uint32_t crc(const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32_z(0L, data, size));
}

template <class T>
void put_le(std::uint8_t* at, T x) {
  std::memcpy(at, &x, sizeof(T));
}
template <class T>
T get_le(const std::uint8_t* at) {
  T x;
  std::memcpy(&x, at, sizeof(T));
  return x;
}

// Header offsets.
constexpr std::size_t kVersionAt = 8, kMarkAt = 12, kSizeAt = 16, kPayloadCrcAt = 24, kHeaderCrcAt = 28;

}  // namespace

std::uint32_t configuration_fingerprint(const std::string& text) {
  return crc(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

void SnapshotEncoder::begin(std::vector<std::uint8_t>& out, std::uint32_t fingerprint, double written,
                            std::size_t sensors, std::size_t items) {
  out_ = &out;
  out.resize(std::max(out.capacity(), 2 * kSnapshotHeaderBytes));  // within the capacity: no allocation
  std::fill(out.begin(), out.begin() + kSnapshotHeaderBytes, 0);
  pos_ = kSnapshotHeaderBytes;
  Writer w(out, pos_);
  unsigned long fp = fingerprint;
  w("fingerprint", fp);
  w("written", written);
  w.count("sensors", sensors, kMaxCount);
  w.count("items", items, kMaxCount);
}

void SnapshotEncoder::sensor(const SnapshotSensor& s) {
  Writer w(*out_, pos_);
  SnapshotSensor copy = s;  // visit() takes the fields by reference (the reader fills them)
  visit(w, copy);
}

void SnapshotEncoder::item(const std::string& id, const ItemMonitor& monitor, const ItemEnsemble* ensemble) {
  Writer w(*out_, pos_);
  // The id is written straight from the caller's string (Writer only reads it).
  w("id", const_cast<std::string&>(id));
  monitor.save(monitor_);
  visit(w, monitor_);
  bool has_ensemble = ensemble != nullptr;
  w("has_ensemble", has_ensemble);
  if (ensemble != nullptr) {
    ensemble->save(ensemble_);
    visit(w, ensemble_);
  }
}

void SnapshotEncoder::finish(bool checksums) {
  std::vector<std::uint8_t>& out = *out_;
  out.resize(pos_);  // shrinking keeps the capacity for the next snapshot
  std::memcpy(out.data(), kMagic, sizeof kMagic);
  put_le<std::uint32_t>(out.data() + kVersionAt, kSnapshotVersion);
  put_le<std::uint32_t>(out.data() + kMarkAt, kByteOrderMark);
  put_le<std::uint64_t>(out.data() + kSizeAt, out.size() - kSnapshotHeaderBytes);
  if (checksums) seal_snapshot(out);
}

void seal_snapshot(std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < kSnapshotHeaderBytes) return;
  const std::uint8_t* payload = bytes.data() + kSnapshotHeaderBytes;
  put_le<std::uint32_t>(bytes.data() + kPayloadCrcAt, crc(payload, bytes.size() - kSnapshotHeaderBytes));
  put_le<std::uint32_t>(bytes.data() + kHeaderCrcAt, crc(bytes.data(), kHeaderCrcAt));
}

std::string decode_snapshot(const std::uint8_t* data, std::size_t size, StateSnapshot& out) {
  out = StateSnapshot{};
  if (size < kSnapshotHeaderBytes)
    return "truncated: " + std::to_string(size) + " bytes, shorter than the " + std::to_string(kSnapshotHeaderBytes) +
           "-byte header";
  if (std::memcmp(data, kMagic, sizeof kMagic) != 0) return "not a state snapshot (no RMSNAPSH magic)";
  if (get_le<std::uint32_t>(data + kHeaderCrcAt) != crc(data, kHeaderCrcAt))
    return "header checksum mismatch: the header is damaged";
  const auto version = get_le<std::uint32_t>(data + kVersionAt);
  if (version != kSnapshotVersion)
    return "format version " + std::to_string(version) + ", this monitor reads version " +
           std::to_string(kSnapshotVersion);
  if (get_le<std::uint32_t>(data + kMarkAt) != kByteOrderMark) return "written on a machine of another byte order";
  const auto payload_size = get_le<std::uint64_t>(data + kSizeAt);
  if (payload_size != size - kSnapshotHeaderBytes)
    return "truncated or extended: the header says " + std::to_string(payload_size) + " payload bytes, the file has " +
           std::to_string(size - kSnapshotHeaderBytes);
  const std::uint8_t* payload = data + kSnapshotHeaderBytes;
  if (get_le<std::uint32_t>(data + kPayloadCrcAt) != crc(payload, payload_size))
    return "payload checksum mismatch: the file is damaged";

  Reader r(payload, payload + payload_size);
  unsigned long fp = 0;
  r("fingerprint", fp);
  out.fingerprint = static_cast<std::uint32_t>(fp);
  r("written", out.written);
  std::size_t sensors = 0, items = 0;
  r.count("sensors", sensors, kMaxCount);
  r.count("items", items, kMaxCount);
  out.sensors.resize(sensors);
  for (std::size_t i = 0; i < sensors && !r.failed(); ++i) {
    const std::string name = "sensor " + std::to_string(i + 1) + " of " + std::to_string(sensors);
    r.group(name.c_str(), [&] { visit(r, out.sensors[i]); });
  }
  out.items.resize(items);
  for (std::size_t i = 0; i < items && !r.failed(); ++i) {
    SnapshotItem& item = out.items[i];
    r("item id", item.id);
    const std::string name = "item '" + item.id + "' (" + std::to_string(i + 1) + " of " + std::to_string(items) + ")";
    r.group(name.c_str(), [&] {
      visit(r, item.monitor);
      r("has_ensemble", item.has_ensemble);
      if (item.has_ensemble) r.group("ensemble", [&] { visit(r, item.ensemble); });
    });
  }
  if (!r.failed() && r.remaining() > 0)
    return "payload: " + std::to_string(r.remaining()) + " bytes after the last item";
  if (r.failed()) {
    const std::string e = r.error();
    out = StateSnapshot{};
    return e;
  }
  return {};
}

std::string read_snapshot(const std::string& path, StateSnapshot& out, bool* exists) {
  out = StateSnapshot{};
  std::error_code ec;
  const bool there = std::filesystem::exists(path, ec);
  if (exists != nullptr) *exists = there;
  if (!there) return path + ": no such file";
  std::ifstream in(path, std::ios::binary);
  if (!in) return path + ": cannot open: " + std::strerror(errno);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return path + ": cannot read: " + std::strerror(errno);
  if (std::string e = decode_snapshot(bytes.data(), bytes.size(), out); !e.empty()) return path + ": " + e;
  return {};
}

std::string foreign_snapshot(const StateSnapshot& snapshot, std::uint32_t fingerprint,
                             const std::vector<std::string>& sensor_names, const std::vector<std::string>& item_ids) {
  if (snapshot.sensors.size() != sensor_names.size())
    return "written for " + std::to_string(snapshot.sensors.size()) + " sensors, this catalogue has " +
           std::to_string(sensor_names.size());
  for (std::size_t i = 0; i < sensor_names.size(); ++i)
    if (snapshot.sensors[i].name != sensor_names[i])
      return "sensor " + std::to_string(i + 1) + " is '" + snapshot.sensors[i].name + "', this catalogue's is '" +
             sensor_names[i] + "'";
  if (snapshot.items.size() != item_ids.size())
    return "written for " + std::to_string(snapshot.items.size()) + " items, this catalogue has " +
           std::to_string(item_ids.size());
  for (std::size_t i = 0; i < item_ids.size(); ++i)
    if (snapshot.items[i].id != item_ids[i])
      return "item " + std::to_string(i + 1) + " is '" + snapshot.items[i].id + "', this catalogue's is '" +
             item_ids[i] + "'";
  if (snapshot.fingerprint != fingerprint)
    return "written with another configuration (catalogue parameters or model options; fingerprint " +
           std::to_string(snapshot.fingerprint) + ", this monitor's " + std::to_string(fingerprint) + ")";
  return {};
}

}  // namespace rocking_monitor::core
