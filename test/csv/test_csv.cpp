// The csv layer: RFC 4180 reading through libcsv (rows, the line each starts on, errors naming
// file and line) and the one writer; a write-then-read round trip is the independent check.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "rocking_monitor/csv/csv_reader.hpp"
#include "rocking_monitor/csv/csv_writer.hpp"

namespace csv = rocking_monitor::core::csv;

namespace {

std::string error_of(const std::string& text) {
  try {
    csv::parse(text, "f.csv");
  } catch (const csv::CsvError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CsvReader, FieldsQuotesAndTheLineEachRowStartsOn) {
  const std::string text =
      "\xEF\xBB\xBF" "a,b,c\r\n"         // BOM, CRLF
      "\n"                               // blank line: skipped, still counted
      "1,\"x, y\",\"say \"\"hi\"\"\"\n"  // quoted comma, doubled quotes
      "2,\"two\nlines\", keep spaces \n"  // a quoted line break
      "3,,\n"                            // empty fields
      "4,last,no newline";
  const std::vector<csv::Row> rows = csv::parse(text, "f.csv");
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].fields, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(rows[0].line, 1u);
  EXPECT_EQ(rows[0].text, "a,b,c");
  EXPECT_EQ(rows[1].fields, (std::vector<std::string>{"1", "x, y", "say \"hi\""}));
  EXPECT_EQ(rows[1].line, 3u);
  EXPECT_EQ(rows[2].fields, (std::vector<std::string>{"2", "two\nlines", " keep spaces "}));
  EXPECT_EQ(rows[2].line, 4u);
  EXPECT_EQ(rows[2].text, "2,\"two\nlines\", keep spaces ");
  EXPECT_EQ(rows[3].fields, (std::vector<std::string>{"3", "", ""}));
  EXPECT_EQ(rows[3].line, 6u);
  EXPECT_EQ(rows[4].fields, (std::vector<std::string>{"4", "last", "no newline"}));
  EXPECT_EQ(rows[4].line, 7u);
  EXPECT_EQ(rows[4].text, "4,last,no newline");
}

TEST(CsvReader, MalformedQuotingNamesFileAndLine) {
  EXPECT_EQ(error_of("a,b\n1,\"open\n2,3\n"), "f.csv:2: unterminated quoted field (a '\"' is never closed)");
  EXPECT_EQ(error_of("a,b\n\n1,x\"y\n"), "f.csv:3: '\"' inside an unquoted field (quote the whole field)");
  EXPECT_EQ(error_of("a,b\n1,\"q\"z\n"), "f.csv:2: unexpected character 'z' after a quoted field");
  EXPECT_EQ(error_of("a,b\n"), "");
  EXPECT_EQ(csv::parse("", "f.csv").size(), 0u);
}

TEST(CsvReader, MissingFileIsAnErrorNamingIt) {
  try {
    csv::read_file("/nonexistent/x.csv");
    FAIL() << "no error";
  } catch (const csv::CsvError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/x.csv: cannot open");
  }
}

TEST(CsvReader, ColumnIndex) {
  const std::vector<csv::Row> rows = csv::parse(" Event ,FILE,file\n", "f.csv");
  const auto exact = csv::column_index(rows[0]);
  EXPECT_EQ(exact.at(" Event "), 0u);
  EXPECT_EQ(exact.count("event"), 0u);
  const auto norm = csv::column_index(rows[0], true);
  EXPECT_EQ(norm.at("event"), 0u);
  EXPECT_EQ(norm.at("file"), 2u);  // a repeated name: the last column
}

TEST(CsvWriter, QuotesOnlyWhatNeedsItAndReadsBackExactly) {
  EXPECT_EQ(csv::quote("plain text"), "plain text");
  EXPECT_EQ(csv::quote("a,b"), "\"a,b\"");
  EXPECT_EQ(csv::quote("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv::quote("cr\r"), "\"cr\r\"");
  const std::vector<std::vector<std::string>> table = {
      {"name", "value", "note"},
      {"San Francisco, 1295 Shafter", "0.25", "two\nlines"},
      {"\"quoted\"", "", " spaced "},
      {"", "1e-9", "comma, \"and\" quote"}};
  std::ostringstream out;
  csv::Writer w(out);
  for (const auto& row : table) {
    w.text(row[0]).value(row[1]).text(row[2]);
    w.end_row();
  }
  EXPECT_EQ(out.str().substr(0, 16), "name,value,note\n");
  const std::vector<csv::Row> back = csv::parse(out.str(), "round.csv");
  ASSERT_EQ(back.size(), table.size());
  for (std::size_t r = 0; r < table.size(); ++r) EXPECT_EQ(back[r].fields, table[r]) << "row " << r;
  EXPECT_EQ(back[2].line, 4u);  // row 1 spans lines 2-3
}
