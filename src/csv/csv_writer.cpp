#include "rocking_monitor/csv/csv_writer.hpp"

namespace rocking_monitor::core::csv {

std::string quote(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  quoted += '"';
  return quoted;
}

void Writer::separate() {
  if (!first_) line_ += ',';
  first_ = false;
}

Writer& Writer::text(std::string_view field) {
  separate();
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) {
    line_ += field;
  } else {
    line_ += quote(field);
  }
  return *this;
}

Writer& Writer::value(std::string_view field) {
  separate();
  line_ += field;
  return *this;
}

void Writer::end_row() {
  line_ += '\n';
  out_ << line_;
  line_.clear();
  first_ = true;
}

}  // namespace rocking_monitor::core::csv
