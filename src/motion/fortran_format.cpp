// Numbers laid out by a Fortran edit descriptor, as COSMOS headers announce them ("Format=(8F10.5)").
// Fields are cut by column, never by white space: Fortran writes touching fields
// ("-0.123456E+01-0.234567E+01") whenever a value fills its width.
#include <cctype>

#include "record_reader_internal.hpp"

namespace rocking_monitor::core::record_io {

namespace {

bool read_uint(std::string_view s, std::size_t& i, std::size_t& out) {
  const std::size_t b = i;
  out = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
    out = out * 10 + static_cast<std::size_t>(s[i++] - '0');
  return i > b && i - b < 6;
}

}  // namespace

bool parse_fortran_format(std::string_view text, FortranFormat& out) {
  std::string s;
  for (char c : text) {
    if (!is_space(c)) s.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  if (s.size() < 4 || s.front() != '(' || s.back() != ')') return false;
  const std::string_view b = std::string_view(s).substr(1, s.size() - 2);
  std::size_t i = 0;
  std::size_t n = 0;
  // An optional scale factor "1P" (with or without a comma) changes how values are printed, not
  // what they are (Fortran applies it on output only when there is an exponent).
  if (read_uint(b, i, n) && i < b.size() && b[i] == 'P') {
    ++i;
    if (i < b.size() && b[i] == ',') ++i;
  } else {
    i = 0;
  }
  std::size_t count = 1;
  const std::size_t before = i;
  if (!read_uint(b, i, count)) {
    i = before;
    count = 1;
  }
  if (i >= b.size()) return false;
  const char kind = b[i++];
  if (kind != 'F' && kind != 'E' && kind != 'D' && kind != 'G' && kind != 'I') return false;
  std::size_t width = 0;
  if (!read_uint(b, i, width) || width == 0) return false;
  if (i < b.size() && b[i] == '.') {
    ++i;
    std::size_t decimals = 0;
    if (!read_uint(b, i, decimals) || kind == 'I') return false;
  }
  if (i != b.size() || count == 0) return false;
  out.per_line = count;
  out.width = width;
  out.kind = kind;
  return true;
}

std::size_t read_fortran_values(const std::vector<Line>& lines, std::size_t first, std::size_t count,
                                const FortranFormat& format, const std::string& path, std::vector<double>& out) {
  std::size_t li = first;
  std::size_t got = 0;
  while (got < count) {
    if (li >= lines.size()) {
      const std::size_t last = lines.empty() ? 0 : lines.back().number;
      fail(path, last,
           "expected " + std::to_string(count) + " values, found " + std::to_string(got) + " (file ends early)");
    }
    const Line& ln = lines[li++];
    std::string_view t = ln.text;
    while (!t.empty() && is_space(t.back())) t.remove_suffix(1);  // trailing blanks
    const std::size_t want = std::min(format.per_line, count - got);
    if (t.size() > format.width * format.per_line) {
      fail(path, ln.number,
           "line longer than the format allows (" + std::to_string(format.per_line) + " fields of " +
               std::to_string(format.width) + " characters)");
    }
    const std::size_t fields = (t.size() + format.width - 1) / format.width;
    if (fields != want) {
      fail(path, ln.number,
           "expected " + std::to_string(want) + " values in " + std::to_string(format.width) +
               "-character fields, found " + std::to_string(fields) + " (" + std::to_string(got) + " of " +
               std::to_string(count) + " read)");
    }
    for (std::size_t k = 0; k < fields; ++k) {
      const std::string_view field = trim(t.substr(k * format.width, format.width));
      if (field.empty()) fail(path, ln.number, "blank field " + std::to_string(k + 1));
      double v = 0.0;
      if (format.kind == 'I') {
        long long iv = 0;
        if (!parse_integer(field, iv))
          fail(path, ln.number, "field " + std::to_string(k + 1) + " is not an integer: " + in_quotes(field));
        v = static_cast<double>(iv);
      } else {
        v = number_or_fail(field, path, ln.number);
      }
      out.push_back(v);
    }
    got += fields;
  }
  return li;
}

}  // namespace rocking_monitor::core::record_io
