// What every record reader needs of the text: errors as "file:line: problem" with the offending
// text made printable, whole-file and head reads, lines (LF, CRLF, lone CR), tokens, file names.
#include "record_reader_internal.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <utility>

namespace rocking_monitor::core::record_io {

// ------------------------------------------------------------------ errors

/// Makes arbitrary file text safe for a one-line message: control/non-ASCII bytes are escaped,
/// long text is shortened.
std::string printable(std::string_view s, std::size_t max_len) {
  std::string out;
  const std::size_t n = std::min(s.size(), max_len);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out.push_back(hex[c >> 4]);
      out.push_back(hex[c & 0xf]);
    }
  }
  if (s.size() > max_len) out += "...";
  return out;
}

std::string in_quotes(std::string_view s) { return "'" + printable(s) + "'"; }

/// Throws RecordError "<path>:<line>: <problem>" (line == 0: "<path>: <problem>").
[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& problem) {
  std::string msg = path;
  if (line > 0) msg += ":" + std::to_string(line);
  msg += ": " + problem;
  throw RecordError(msg);
}

// ------------------------------------------------------------------ files and lines

std::string read_whole_file(const std::string& path) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    fail(path, 0, std::string("cannot open file (") + (err != 0 ? std::strerror(err) : "unknown error") + ")");
  }
  std::string data;
  char buf[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(buf, 1, sizeof buf, f);
    data.append(buf, got);
    if (got < sizeof buf) break;
  }
  const bool error = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (error) {
    fail(path, 0, std::string("cannot read file (") + (err != 0 ? std::strerror(err) : "read error") + ")");
  }
  return data;
}

/// Reads at most max_bytes from the start of a file (for format detection).
std::string read_file_head(const std::string& path, std::size_t max_bytes, bool* whole) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    fail(path, 0, std::string("cannot open file (") + (err != 0 ? std::strerror(err) : "unknown error") + ")");
  }
  std::string data(max_bytes, '\0');
  const std::size_t got = std::fread(data.data(), 1, max_bytes, f);
  const bool error = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (error) {
    fail(path, 0, std::string("cannot read file (") + (err != 0 ? std::strerror(err) : "read error") + ")");
  }
  data.resize(got);
  *whole = got < max_bytes;
  return data;
}

/// Splits on LF, CRLF or a lone CR. A leading UTF-8 BOM is skipped.
std::vector<Line> split_lines(std::string_view data) {
  std::vector<Line> lines;
  lines.reserve(data.size() / 64 + 16);
  std::size_t pos = 0;
  if (data.size() >= 3 && data.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;
  std::size_t number = 1;
  const std::size_t n = data.size();
  while (pos < n) {
    std::size_t end = pos;
    while (end < n && data[end] != '\n' && data[end] != '\r') ++end;
    lines.push_back({data.substr(pos, end - pos), number++});
    if (end < n && data[end] == '\r' && end + 1 < n && data[end + 1] == '\n') {
      pos = end + 2;
    } else {
      pos = end + 1;
    }
  }
  return lines;
}

std::string_view trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && is_space(s[b])) ++b;
  while (e > b && is_space(s[e - 1])) --e;
  return s.substr(b, e - b);
}

bool is_blank(std::string_view s) { return trim(s).empty(); }

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// Calls f(token) for every whitespace-separated token of a line.

std::vector<std::string_view> ws_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  for_each_ws_token(line, [&](std::string_view t) { out.push_back(t); });
  return out;
}

/// Splits a CSV/whitespace line: fields are separated by a comma (with optional blanks around it)
/// or by blanks. Returns false (and sets *bad_column, 1-based) when a field is empty ("1,,2",
/// "1,2,", ",1").
bool csv_tokens(std::string_view line, std::vector<std::string_view>& out, std::size_t* bad_column) {
  out.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  bool need_field = false;  // a comma was just consumed
  while (true) {
    while (i < n && is_space(line[i])) ++i;
    if (i >= n) {
      if (need_field) {
        *bad_column = out.size() + 1;
        return false;
      }
      return true;
    }
    if (line[i] == ',') {
      // a comma with no field before it (",1" or "1,,2")
      if (need_field || out.empty()) {
        *bad_column = out.size() + 1;
        return false;
      }
      need_field = true;
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && !is_space(line[j]) && line[j] != ',') ++j;
    out.push_back(line.substr(i, j - i));
    need_field = false;
    i = j;
    // after a field: blanks, then optionally one comma
    while (i < n && is_space(line[i])) ++i;
    if (i < n && line[i] == ',') {
      need_field = true;
      ++i;
    }
  }
}

std::string file_extension_lower(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(std::string_view(path).substr(dot + 1));
}

std::string file_stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  return name;
}

std::vector<Component> npts_checked(Component c, std::size_t want, const std::string& path,
                                    std::size_t last_data_line) {
  if (c.accel.size() < want) {
    fail(path, last_data_line,
         "expected " + std::to_string(want) + " values (NPTS), found " + std::to_string(c.accel.size()));
  }
  std::vector<Component> out;
  out.push_back(std::move(c));
  return out;
}

}  // namespace rocking_monitor::core::record_io
