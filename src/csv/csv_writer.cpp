#include "rocking_monitor/csv/csv_writer.hpp"

#include <algorithm>
#include <cstdio>

namespace rocking_monitor::core::csv {
namespace {

// Appends `text` to `out` as one field, quoted only when RFC 4180 needs it.
void append_field(std::string& out, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    out += text;
    return;
  }
  out += '"';
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

}  // namespace

std::string quote(std::string_view text) {
  std::string quoted;
  append_field(quoted, text);
  return quoted;
}

void Writer::separate() {
  if (!first_) line_ += ',';
  first_ = false;
}

Writer& Writer::text(std::string_view field) {
  separate();
  append_field(line_, field);
  return *this;
}

Writer& Writer::value(std::string_view field) {
  separate();
  line_ += field;
  return *this;
}

Writer& Writer::number(const char* format, double field) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, format, field);
  return value(std::string_view(buf, std::min(static_cast<std::size_t>(std::max(n, 0)), sizeof buf - 1)));
}

void Writer::end_row() {
  line_ += '\n';
  out_ << line_;
  line_.clear();
  first_ = true;
}

}  // namespace rocking_monitor::core::csv
