// Strong-motion record readers (PEER AT2, SCEC BBP, USGS SMC V2, miniSEED 2, COSMOS V2,
// K-NET/KiK-net ASCII, plain CSV/whitespace).
//
// Design notes
//  * The whole file is read into memory and split into lines (LF, CRLF or lone CR); numbers are
//    parsed with a strict grammar check followed by std::from_chars (locale independent, fast).
//    A token must be consumed completely: "1.2.3", "0x10", "1e" or "12abc" are rejected.
//    FORTRAN "D" exponents (1.0D-03) are accepted; NaN/inf/overflow are rejected as non-finite.
//  * Every problem throws RecordError("<file>:<line>: <problem>") (line omitted when not tied to a
//    line). Nothing is truncated silently; the only data deliberately ignored is what follows the
//    NPTS values of an AT2/SMC file (documented quirk: RSN960_NORTHR_LOS270.AT2 has a ".0" pad).
//  * Output is SI (m/s^2); vertical components are positive up.
//
// Sign convention for vertical components labelled "DWN" (PEER) / "down" (SMC):
//   PEER NGA names each component by the direction in which its acceleration is positive: the
//   horizontals carry the azimuth of their positive axis ("180", "W": the Chi-Chi files whose name
//   says -E but header says W are positive west), and the verticals are labelled either "UP" or
//   "DWN". Neither the AT2 header nor the README says that PEER re-oriented the DWN channels, and
//   the label is kept "as recorded" like the azimuths, so DWN is read as "positive downward".
//   These components are therefore multiplied by -1 on reading, so that every stored vertical is
//   positive up; Component::label keeps "DWN" as written. (PGA, i.e. max |a|, is unaffected.)
//   BBP U-D columns are "+ is upward" (header) and SMC "up" is positive up: not flipped.
//
// One file per format (at2_reader.cpp, bbp_reader.cpp, smc_reader.cpp, table_reader.cpp); what they
// share is in record_text.cpp, record_numbers.cpp and record_time_columns.cpp
// (record_reader_internal.hpp); record_format_detection.cpp tells the formats apart. This file holds
// the public API: detection and dispatch (read_record) and the component labels.

#include "rocking_monitor/motion/record_reader.hpp"

#include <string>

#include "record_reader_internal.hpp"

namespace rocking_monitor::core {

namespace record_io {

// ------------------------------------------------------------------ labels

std::string normalised_label(const std::string& label) {
  std::string l = upper(trim(label));
  while (!l.empty() && (l[0] == '-' || l[0] == '_')) l.erase(0, 1);
  return l;
}

}  // namespace record_io

using namespace record_io;

// ------------------------------------------------------------------ public API

bool label_is_vertical(const std::string& label) {
  const std::string l = normalised_label(label);
  return l == "UP" || l == "DWN" || l == "DOWN" || l == "DN" || l == "U-D" || l == "UD" || l == "D-U" ||
         l == "V" || l == "VER" || l == "VERT" || l == "VRT" || l == "VERTICAL" || l == "Z" || l == "UP-DOWN";
}

bool label_is_positive_down(const std::string& label) {
  const std::string l = normalised_label(label);
  return l == "DWN" || l == "DOWN" || l == "DN";
}

RecordFormat detect_format(const std::string& path) {
  bool whole = false;
  const std::string head = read_file_head(path, 16384, &whole);
  return detect_from_content(head, whole, path);
}

std::vector<Component> read_record(const std::string& path, const ReadOptions& options) {
  const std::string data = read_whole_file(path);
  if (trim(data).empty()) fail(path, 0, data.empty() ? "empty file" : "empty file (only blanks)");
  RecordFormat format = options.format;
  if (format == RecordFormat::Auto) {
    const std::size_t head_len = std::min<std::size_t>(data.size(), 16384);
    format = detect_from_content(std::string_view(data).substr(0, head_len), head_len == data.size(), path);
  }
  switch (format) {
    case RecordFormat::PeerAt2:
      return read_at2(path, data);
    case RecordFormat::Bbp:
      return read_bbp(path, data);
    case RecordFormat::UsgsSmc:
      return read_smc(path, data);
    case RecordFormat::Csv:
      return read_csv(path, data, options.csv_units);
    case RecordFormat::MiniSeed:
      return read_miniseed(path, options);
    case RecordFormat::CosmosV2:
      return read_cosmos(path, data);
    case RecordFormat::Knet:
      return read_knet(path, data);
    case RecordFormat::Auto:
      break;
  }
  const std::string ext = file_extension_lower(path);
  fail(path, 0,
       "unknown record format (not PEER AT2, SCEC BBP, USGS SMC V2, miniSEED, COSMOS V2, K-NET or CSV by content, and extension " +
           (ext.empty() ? std::string("none") : in_quotes(ext)) + " does not tell)");
}

const char* to_string(RecordFormat format) {
  switch (format) {
    case RecordFormat::Auto:
      return "auto";
    case RecordFormat::PeerAt2:
      return "peer_at2";
    case RecordFormat::Bbp:
      return "bbp";
    case RecordFormat::UsgsSmc:
      return "usgs_smc";
    case RecordFormat::Csv:
      return "csv";
    case RecordFormat::MiniSeed:
      return "miniseed";
    case RecordFormat::CosmosV2:
      return "cosmos_v2";
    case RecordFormat::Knet:
      return "knet";
  }
  return "unknown";
}

}  // namespace rocking_monitor::core
