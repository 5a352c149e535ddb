#pragma once

// Reading CSV (RFC 4180) for every part of the project: station manifests, study case files. The
// parsing is libcsv's (Debian libcsv-dev, strict mode); this file adds what every caller needs on
// top: the line where each row starts, and errors that name the file and the line.

#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace rocking_monitor::core::csv {

/// Malformed CSV or an unreadable file; what() is "path:line: problem" (or "path: problem").
class CsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Row {
  std::vector<std::string> fields;
  std::size_t line = 0;  ///< 1-based line where the row starts
  std::string text;      ///< the row as written (its lines, without the final line break)
};

/// Parses CSV text: fields separated by ',', optionally enclosed in '"' (then commas, line breaks and
/// doubled quotes "" may appear inside); rows end at LF or CRLF; blank lines are skipped; a UTF-8
/// byte-order mark is skipped; spaces are kept. A '"' inside an unquoted field, text after a closing
/// quote or a quote never closed throws CsvError naming `path` and the line.
std::vector<Row> parse(const std::string& text, const std::string& path);

/// Reads and parses a file (CsvError "path: cannot open" when it cannot be read).
std::vector<Row> read_file(const std::string& path);

/// Column name -> index of a header row (a repeated name: the last). With `normalise`, names are
/// trimmed of white space and lower-cased.
std::map<std::string, std::size_t> column_index(const Row& header, bool normalise = false);

}  // namespace rocking_monitor::core::csv
