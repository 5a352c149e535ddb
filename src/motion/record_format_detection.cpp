// Which format a record is, from its content (not its name): miniSEED (binary), COSMOS V2, K-NET,
// AT2, BBP, SMC or a plain table; an unknown format is an error naming the file.
#include "record_reader_internal.hpp"

#include <cctype>
#include <string_view>

namespace rocking_monitor::core::record_io {

// ------------------------------------------------------------------ detection

RecordFormat detect_from_content(std::string_view head, bool whole_file, const std::string& path) {
  if (looks_like_miniseed(head)) return RecordFormat::MiniSeed;
  std::vector<Line> lines = split_lines(head);
  if (!whole_file && !lines.empty()) lines.pop_back();  // possibly cut in the middle
  if (lines.size() > 40) lines.resize(40);

  std::size_t first = 0;
  while (first < lines.size() && is_blank(lines[first].text)) ++first;
  if (first < lines.size()) {
    const std::string l1 = upper(lines[first].text);
    // COSMOS: "Corrected acceleration  (Format v01.20 with 13 text lines) ..."
    if (l1.find("(FORMAT V") != std::string::npos && l1.find("TEXT LINES") != std::string::npos) {
      return RecordFormat::CosmosV2;
    }
    // K-NET / KiK-net: "Origin Time       2006/01/18 23:25:00", line 6 "Station Code ..."
    if (l1.rfind("ORIGIN TIME", 0) == 0 && first + 5 < lines.size() &&
        upper(lines[first + 5].text).rfind("STATION CODE", 0) == 0) {
      return RecordFormat::Knet;
    }
    if (l1.find("PEER") != std::string::npos &&
        (l1.find("STRONG MOTION") != std::string::npos || l1.find("DATABASE") != std::string::npos)) {
      return RecordFormat::PeerAt2;
    }
    const std::string_view t1 = trim(lines[first].text);
    if (l1.find("ACCELEROGRAM") != std::string::npos && !t1.empty() &&
        std::isdigit(static_cast<unsigned char>(t1[0]))) {
      return RecordFormat::UsgsSmc;
    }
  }
  // AT2-like without the PEER title: line 3 "... UNITS OF G", line 4 "NPTS=" or "... NPTS, DT"
  if (lines.size() >= 4) {
    const std::string l3 = upper(lines[2].text);
    const std::string l4 = upper(lines[3].text);
    if (l3.find("UNITS OF G") != std::string::npos && l4.find("NPTS") != std::string::npos) {
      return RecordFormat::PeerAt2;
    }
  }
  // Tabular: '#' header lines then 4 numeric columns -> BBP; 2 or 3 -> CSV.
  bool header_used = false;
  std::vector<std::string_view> toks;
  for (std::size_t i = first; i < lines.size(); ++i) {
    const std::string_view t = trim(lines[i].text);
    if (t.empty()) continue;
    if (t[0] == '#') continue;
    std::size_t bad = 0;
    const bool ok = csv_tokens(t, toks, &bad);
    bool all_numeric = ok && !toks.empty();
    for (std::string_view tok : toks) all_numeric = all_numeric && is_number(tok);
    if (all_numeric) {
      if (toks.size() == 4 && t.find(',') == std::string_view::npos) return RecordFormat::Bbp;
      if (toks.size() == 2 || toks.size() == 3) return RecordFormat::Csv;
      break;
    }
    if (header_used) break;
    header_used = true;  // one non-numeric header line allowed
  }

  const std::string ext = file_extension_lower(path);
  if (ext == "at2") return RecordFormat::PeerAt2;
  if (ext == "bbp") return RecordFormat::Bbp;
  if (ext == "smc" || ext == "v2") return RecordFormat::UsgsSmc;
  if (ext == "csv" || ext == "txt" || ext == "dat" || ext == "tsv") return RecordFormat::Csv;
  if (ext == "mseed" || ext == "miniseed" || ext == "ms") return RecordFormat::MiniSeed;
  if (ext == "v2c") return RecordFormat::CosmosV2;
  return RecordFormat::Auto;
}

}  // namespace rocking_monitor::core::record_io
