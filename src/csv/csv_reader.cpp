#include "rocking_monitor/csv/csv_reader.hpp"

#include <csv.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace rocking_monitor::core::csv {
namespace {

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& problem) {
  throw CsvError(path + ":" + std::to_string(line) + ": " + problem);
}

// libcsv hands over fields and row ends through callbacks; this is what they fill.
struct Collector {
  std::vector<Row> rows;
  Row current;
  std::size_t row_start = 0;  // first non-blank line since the last row ended (0: none yet)
};

void on_field(void* data, std::size_t size, void* ctx) {
  auto* c = static_cast<Collector*>(ctx);
  if (data == nullptr) {
    c->current.fields.emplace_back();
  } else {
    c->current.fields.emplace_back(static_cast<const char*>(data), size);
  }
}

void on_row_end(int, void* ctx) {
  auto* c = static_cast<Collector*>(ctx);
  c->current.line = c->row_start;
  c->rows.push_back(std::move(c->current));
  c->current = Row{};
  c->row_start = 0;
}

// Spaces belong to the field (libcsv trims them by default).
int no_space(unsigned char) { return 0; }

bool is_blank_line(const char* begin, std::size_t size) {
  return size == 0 || (size == 1 && begin[0] == '\n') || (size == 2 && begin[0] == '\r' && begin[1] == '\n');
}

std::string strip_line_break(std::string s) {
  if (!s.empty() && s.back() == '\n') s.pop_back();
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

}  // namespace

std::vector<Row> parse(const std::string& text, const std::string& path) {
  csv_parser parser;
  if (csv_init(&parser, CSV_STRICT | CSV_STRICT_FINI) != 0) throw CsvError(path + ": cannot start the CSV parser");
  csv_set_space_func(&parser, no_space);
  struct Free {
    csv_parser* p;
    ~Free() { csv_free(p); }
  } free_parser{&parser};

  Collector c;
  std::size_t begin = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  // Fed one line at a time so that every row and every error knows its line.
  std::vector<std::size_t> line_begin;  // offset of each line, for the rows' text
  for (std::size_t line = 1; begin < text.size(); ++line) {
    const std::size_t nl = text.find('\n', begin);
    const std::size_t end = nl == std::string::npos ? text.size() : nl + 1;
    line_begin.push_back(begin);
    const char* chunk = text.data() + begin;
    const std::size_t size = end - begin;
    if (c.row_start == 0 && !is_blank_line(chunk, size)) c.row_start = line;
    const std::size_t rows_before = c.rows.size();
    const std::size_t used = csv_parse(&parser, chunk, size, on_field, on_row_end, &c);
    if (used != size) {
      const char bad = chunk[used < size ? used : size - 1];
      if (bad == '"') fail(path, line, "'\"' inside an unquoted field (quote the whole field)");
      fail(path, line, "unexpected character '" + std::string(1, bad) + "' after a quoted field");
    }
    for (std::size_t r = rows_before; r < c.rows.size(); ++r) {
      Row& row = c.rows[r];
      row.text = strip_line_break(text.substr(line_begin[row.line - 1], end - line_begin[row.line - 1]));
    }
    begin = end;
  }
  const std::size_t rows_before = c.rows.size();
  if (csv_fini(&parser, on_field, on_row_end, &c) != 0)
    fail(path, c.row_start, "unterminated quoted field (a '\"' is never closed)");
  for (std::size_t r = rows_before; r < c.rows.size(); ++r)
    c.rows[r].text = strip_line_break(text.substr(line_begin[c.rows[r].line - 1]));
  return std::move(c.rows);
}

std::vector<Row> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CsvError(path + ": cannot open");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path);
}

std::map<std::string, std::size_t> column_index(const Row& header, bool normalise) {
  std::map<std::string, std::size_t> columns;
  for (std::size_t i = 0; i < header.fields.size(); ++i) {
    std::string name = header.fields[i];
    if (normalise) {
      const auto space = [](unsigned char ch) { return std::isspace(ch) != 0; };
      name.erase(name.begin(), std::find_if_not(name.begin(), name.end(), space));
      name.erase(std::find_if_not(name.rbegin(), name.rend(), space).base(), name.end());
      std::transform(name.begin(), name.end(), name.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    }
    columns[name] = i;  // a repeated name: the last column wins
  }
  return columns;
}

}  // namespace rocking_monitor::core::csv
