#pragma once

// Writing CSV (RFC 4180): the one place that decides how a field is quoted, for the study's tables,
// record_to_bag's index and rocking_sim --history.

#include <ostream>
#include <string>
#include <string_view>

namespace rocking_monitor::core::csv {

/// `text` as one CSV field: unchanged unless it holds a ',', '"', CR or LF; then enclosed in '"'
/// with inner quotes doubled.
std::string quote(std::string_view text);

/// Builds one row at a time and writes it with a final '\n'. The buffer is reused from row to row.
class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) {}
  /// A text field, quoted when it needs to be.
  Writer& text(std::string_view field);
  /// A field written as is: a formatted number, a code, or an empty field.
  Writer& value(std::string_view field);
  /// A number formatted with a printf format for one double ("%.9g"); written in place.
  Writer& number(const char* format, double field);
  /// Ends the row: writes it and starts the next.
  void end_row();

 private:
  void separate();
  std::ostream& out_;
  std::string line_;
  bool first_ = true;
};

}  // namespace rocking_monitor::core::csv
