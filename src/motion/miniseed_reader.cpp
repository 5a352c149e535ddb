// miniSEED 2 records (libmseed 2): the records of each accelerometer channel are decoded (steim1,
// steim2, int16/32, float32/64), put in time order and joined; counts / gain -> m/s^2.
//
// Rules (docs/records.md, "miniSEED"):
//  * A gap or overlap inside a channel (more than half a sample from where the previous record
//    ended) is an error naming the channel, the time and the record: a silently zero-filled or
//    spliced record would feed the model acceleration that never happened. Cut or fill the file
//    explicitly (e.g. with dataselect or ObsPy) if that is what you want.
//  * All channels of a file: one station and location, one sample rate, the same first sample
//    (within half a sample). Different ends are allowed (the station's length rule applies).
//  * The gain and the azimuth of 1/2 channels come from the options or the channel table, never
//    from a default (SEED codes N/E do say north/east).
// miniSEED has no lines: errors name "<file>: record <n> at byte <offset>".
#include <libmseed.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <mutex>
#include <sstream>

#include "record_reader_internal.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace rocking_monitor::core::record_io {

namespace {

void quiet_log(char*) {}

// libmseed reports some problems only as a printed warning and decodes the record anyway (e.g.
// "Data integrity check for Steim2 failed"): the reader collects them per record and fails on them.
thread_local std::string* t_diagnostics = nullptr;
void collect_diagnostic(char* message) {
  if (t_diagnostics != nullptr && message != nullptr) {
    std::string m(message);
    while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
    if (!t_diagnostics->empty()) *t_diagnostics += "; ";
    *t_diagnostics += m;
  }
}

/// libmseed prints its own diagnostics on stderr; our errors say it all, on one line.
void silence_libmseed() {
  static std::once_flag once;
  std::call_once(once, [] { ms_loginit(quiet_log, nullptr, collect_diagnostic, nullptr); });
}

/// Points libmseed's diagnostics of this thread at a string while a file is read.
struct DiagnosticSink {
  std::string text;
  DiagnosticSink() { t_diagnostics = &text; }
  ~DiagnosticSink() { t_diagnostics = nullptr; }
};

/// Frees libmseed's reader state however the function is left.
struct MsReader {
  MSFileParam* msfp = nullptr;
  MSRecord* msr = nullptr;
  ~MsReader() { ms_readmsr_r(&msfp, &msr, nullptr, 0, nullptr, nullptr, 0, 0, 0); }
};

struct Segment {
  hptime_t start = 0;           // microseconds since the epoch
  double rate = 0.0;            // Hz
  std::vector<double> samples;  // as decoded (counts, or the float values)
  std::size_t record = 0;       // 1-based record number in the file
  long long offset = 0;         // byte offset of the record
};

struct Channel {
  std::string net, sta, loc, cha;
  std::vector<Segment> segments;
  std::string id() const { return net + "." + sta + "." + loc + "." + cha; }
};

std::string iso(hptime_t t) {
  char buf[64];
  ms_hptime2isotimestr(t, buf, 1);
  return std::string(buf) + "Z";
}

std::string record_where(const std::string& path, std::size_t record, long long offset) {
  return path + ": record " + std::to_string(record) + " at byte " + std::to_string(offset);
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << v;
  return os.str();
}

// One record's samples as decoded (counts, or the float values), each finite.
Segment record_segment(const MSRecord* msr, std::size_t record, long long offset, const std::string& where) {
  Segment s;
  s.start = msr->starttime;
  s.rate = msr->samprate;
  s.record = record;
  s.offset = offset;
  s.samples.resize(static_cast<std::size_t>(msr->numsamples));
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    switch (msr->sampletype) {
      case 'i':
        s.samples[i] = static_cast<const int32_t*>(msr->datasamples)[i];
        break;
      case 'f':
        s.samples[i] = static_cast<const float*>(msr->datasamples)[i];
        break;
      case 'd':
        s.samples[i] = static_cast<const double*>(msr->datasamples)[i];
        break;
      default:
        fail(where, 0, std::string("unknown sample type '") + msr->sampletype + "'");
    }
    if (!std::isfinite(s.samples[i])) {
      fail(where, 0, std::string("channel ") + msr->channel + ": non-finite sample " + std::to_string(i + 1));
    }
  }
  return s;
}

// A decoded record's samples appended to its channel (a new channel, in order of first appearance,
// is checked to be an accelerometer's).
void add_record(const MSRecord* msr, std::size_t record, long long offset, const std::string& where,
                std::vector<Channel>& channels, std::map<std::string, std::size_t>& index) {
  if (msr->sampletype == 'a') {
    fail(where, 0, std::string("channel ") + msr->channel + " holds text (ASCII encoding), not samples");
  }
  if (!(msr->samprate > 0.0)) {
    fail(where, 0, std::string("channel ") + msr->channel + ": sample rate " + fixed(msr->samprate, 6) + " Hz");
  }
  const std::string key = std::string(msr->network) + "." + msr->station + "." + msr->location + "." + msr->channel;
  auto it = index.find(key);
  if (it == index.end()) {
    classify_seed_channel(msr->channel, where);  // refuses non-accelerometer channels early
    Channel c;
    c.net = msr->network;
    c.sta = msr->station;
    c.loc = msr->location;
    c.cha = msr->channel;
    it = index.emplace(key, channels.size()).first;
    channels.push_back(std::move(c));
  }
  channels[it->second].segments.push_back(record_segment(msr, record, offset, where));
}

// Every record of the file, by channel (in order of first appearance); the records must cover the file.
std::vector<Channel> read_channels(const std::string& path) {
  std::vector<Channel> channels;
  std::map<std::string, std::size_t> index;
  DiagnosticSink diagnostics;
  MsReader reader;
  off_t fpos = 0;
  int last = 0;
  std::size_t record = 0;
  long long next_offset = 0;
  int rv = MS_NOERROR;
  // reclen -1: every record's length is detected (a file may mix 512- and 4096-byte records);
  // skipnotdata 0: bytes that are not a record are an error, not skipped.
  while ((rv = ms_readmsr_r(&reader.msfp, &reader.msr, path.c_str(), -1, &fpos, &last, 0, 1, 0)) == MS_NOERROR) {
    ++record;
    const MSRecord* msr = reader.msr;
    const long long offset = static_cast<long long>(fpos);
    next_offset = offset + msr->reclen;
    const std::string where = record_where(path, record, offset);
    if (!diagnostics.text.empty()) fail(where, 0, "libmseed: " + diagnostics.text);
    if (msr->numsamples == 0) continue;  // a record without samples (blockettes only) adds nothing
    add_record(msr, record, offset, where, channels, index);
  }
  if (rv != MS_ENDOFFILE) {
    fail(record_where(path, record + 1, next_offset), 0,
         std::string("not a valid miniSEED record (libmseed: ") + ms_errorstr(rv) +
             (diagnostics.text.empty() ? std::string() : "; " + diagnostics.text) + ")");
  }
  // libmseed may stop quietly at a record cut short: the records must cover the file.
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && static_cast<long long>(size) != next_offset) {
    fail(record_where(path, record + 1, next_offset), 0,
         "not a valid miniSEED record (file ends after " +
             std::to_string(static_cast<long long>(size) - next_offset) + " of its bytes: truncated)");
  }
  return channels;
}

// One station, one location per file: a station is what the rest of the project loads.
void check_one_station(const std::string& path, const std::vector<Channel>& channels) {
  for (const Channel& c : channels) {
    if (c.net != channels[0].net || c.sta != channels[0].sta || c.loc != channels[0].loc) {
      fail(path, 0,
           "holds several stations or locations (" + channels[0].id() + " and " + c.id() + "): one station per file");
    }
  }
}

// A channel's records in time order, then no gap, no overlap, no rate change.
void join_records(const std::string& path, Channel& c) {
  std::stable_sort(c.segments.begin(), c.segments.end(),
                   [](const Segment& a, const Segment& b) { return a.start < b.start; });
  for (std::size_t k = 1; k < c.segments.size(); ++k) {
    const Segment& prev = c.segments[k - 1];
    const Segment& cur = c.segments[k];
    const std::string where = record_where(path, cur.record, cur.offset);
    if (std::abs(cur.rate - prev.rate) > 1e-6 * prev.rate) {
      fail(where, 0,
           "channel " + c.id() + ": sample rate changes from " + fixed(prev.rate, 6) + " Hz to " +
               fixed(cur.rate, 6) + " Hz at " + iso(cur.start));
    }
    const double period_us = 1e6 / prev.rate;
    const double expected = static_cast<double>(prev.start) + static_cast<double>(prev.samples.size()) * period_us;
    const double diff_s = (static_cast<double>(cur.start) - expected) * 1e-6;
    if (std::abs(diff_s) * prev.rate > 0.5) {
      const bool gap = diff_s > 0.0;
      fail(where, 0,
           "channel " + c.id() + ": " + (gap ? "gap" : "overlap") + " of " + fixed(std::abs(diff_s), 6) + " s at " +
               iso(gap ? static_cast<hptime_t>(std::llround(expected)) : cur.start) +
               (gap ? " (the reader does not fill gaps; cut the file at the gap or fill it explicitly)"
                    : " (records overlap; remove the duplicate data)"));
    }
  }
}

// All channels: one rate, one first sample. Returns the rate (Hz).
double common_rate(const std::string& path, const std::vector<Channel>& channels) {
  const Channel& ref = channels[0];
  const double rate = ref.segments.front().rate;
  for (const Channel& c : channels) {
    const Segment& s = c.segments.front();
    const std::string where = record_where(path, s.record, s.offset);
    if (std::abs(s.rate - rate) > 1e-6 * rate) {
      fail(where, 0,
           "mixed sample rates: " + ref.id() + " " + fixed(rate, 6) + " Hz, " + c.id() + " " + fixed(s.rate, 6) +
               " Hz (one rate per station)");
    }
    const double offset_s = static_cast<double>(s.start - ref.segments.front().start) * 1e-6;
    if (std::abs(offset_s) * rate > 0.5) {
      fail(where, 0,
           "channels start at different samples: " + ref.id() + " at " + iso(ref.segments.front().start) + ", " +
               c.id() + " at " + iso(s.start) + " (trim them to a common start)");
    }
  }
  return rate;
}

// Components in a fixed order whatever the file's record order: N/1, E/2, then Z; one channel each.
void sort_directions(const std::string& path, std::vector<Channel>& channels) {
  auto rank = [&path](const Channel& c) {
    const SeedChannel k = classify_seed_channel(c.cha, path);
    return k.vertical ? 2 : k.horizontal_index;
  };
  std::stable_sort(channels.begin(), channels.end(),
                   [&](const Channel& a, const Channel& b) { return rank(a) < rank(b); });
  for (std::size_t k = 1; k < channels.size(); ++k) {
    if (rank(channels[k]) == rank(channels[k - 1])) {
      fail(path, 0,
           "channels " + channels[k - 1].id() + " and " + channels[k].id() +
               " measure the same direction (one band and instrument per file)");
    }
  }
}

// Counts per m/s^2: the option, else the channel table's; never a default.
double channel_gain(const std::string& path, const Channel& c, const ChannelTableRow* row,
                    const ReadOptions& options, const std::string& table_text) {
  double gain = 0.0;
  if (options.gain_counts_per_mps2) {
    gain = *options.gain_counts_per_mps2;
  } else if (row != nullptr && row->gain_counts_per_mps2) {
    gain = *row->gain_counts_per_mps2;
  } else {
    fail(path, 0,
         "channel " + c.id() +
             ": no gain (counts per m/s^2): give --gain or gain_counts_per_mps2 in a channel table (" + table_text +
             ")");
  }
  if (!(gain > 0.0) || !std::isfinite(gain))
    fail(path, 0, "channel " + c.id() + ": gain " + fixed(gain, 6) + " is not positive");
  return gain;
}

// "UP", or the horizontal's azimuth: the option's sensor azimuth, else the channel table's, else N/E's own.
std::string channel_label(const std::string& path, const Channel& c, const SeedChannel& kind,
                          const ChannelTableRow* row, const ReadOptions& options, const std::string& table_text) {
  if (kind.vertical) return "UP";
  double az = 0.0;
  if (options.sensor_azimuth_deg) {
    az = *options.sensor_azimuth_deg + 90.0 * kind.horizontal_index;
  } else if (row != nullptr && row->azimuth_deg) {
    az = *row->azimuth_deg;
  } else if (kind.geographic) {
    az = 90.0 * kind.horizontal_index;
  } else {
    fail(path, 0,
         "channel " + c.id() +
             ": the sensor's azimuth is unknown (channels 1/2 have no fixed direction): give --sensor-azimuth or "
             "azimuth_deg in a channel table (" +
             table_text + ")");
  }
  az = std::fmod(az, 360.0);
  if (az < 0.0) az += 360.0;
  return format_azimuth_label(az);
}

// A joined channel as a component: its samples / gain, in m/s^2.
Component channel_component(const std::string& path, const Channel& c, double rate, const ChannelTable& table,
                            const ReadOptions& options, const std::string& table_text) {
  const SeedChannel kind = classify_seed_channel(c.cha, path);
  const ChannelTableRow* row = table.find(c.net, c.sta, c.loc, c.cha);
  const double gain = channel_gain(path, c, row, options, table_text);
  Component comp;
  comp.file = path;
  comp.station = c.net + "." + c.sta + (c.loc.empty() ? std::string() : "." + c.loc);
  comp.channel = c.cha;
  comp.event = iso(c.segments.front().start);  // miniSEED names no event; its start time says which
  comp.dt = 1.0 / rate;
  comp.t0 = 0.0;
  comp.vertical = kind.vertical;
  comp.label = channel_label(path, c, kind, row, options, table_text);
  std::size_t n = 0;
  for (const Segment& s : c.segments) n += s.samples.size();
  comp.accel.reserve(n);
  for (const Segment& s : c.segments) {
    for (double v : s.samples) {
      const double a = v / gain;
      if (!std::isfinite(a)) {
        std::ostringstream msg;
        msg << std::setprecision(17) << "channel " << c.id() << ": sample " << v << " / gain " << gain
            << " overflows m/s^2";
        fail(path, 0, msg.str());
      }
      comp.accel.push_back(a);
    }
  }
  return comp;
}

}  // namespace

bool looks_like_miniseed(std::string_view head) {
  if (head.size() < 48) return false;
  const int n = static_cast<int>(std::min<std::size_t>(head.size(), 1 << 20));
  return ms_detect(head.data(), n) > 0;
}

std::vector<Component> read_miniseed(const std::string& path, const ReadOptions& options) {
  silence_libmseed();
  std::vector<Channel> channels = read_channels(path);
  if (channels.empty()) fail(path, 0, "no data records (a miniSEED file without samples)");
  check_one_station(path, channels);
  for (Channel& c : channels) join_records(path, c);
  const double rate = common_rate(path, channels);
  sort_directions(path, channels);
  const ChannelTable table = channel_table_for(path, options);
  const std::string table_text = table.path.empty() ? std::string("no CHANNELS.csv beside the file") : table.path;
  std::vector<Component> out;
  for (const Channel& c : channels) out.push_back(channel_component(path, c, rate, table, options, table_text));
  return out;
}

}  // namespace rocking_monitor::core::record_io
