// Issue 54: one bad string cannot kill a node. Invalid UTF-8 becomes U+FFFD on every JSON path
// (json_text, the alarm journal), server text loses its control characters before a log line.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/monitoring/alarm_journal.hpp"
#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor {
namespace {

const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD

TEST(SafeText, ValidUtf8PassesUnchangedAndEachBadByteBecomesOneReplacement) {
  const std::string good = "vase \xC3\xA9 \xE2\x82\xAC \xF0\x9F\x8F\xBA";  // e-acute, euro, amphora
  EXPECT_TRUE(is_valid_utf8(good));
  EXPECT_EQ(valid_utf8(good), good);
  EXPECT_FALSE(is_valid_utf8("a\xFF"));
  EXPECT_EQ(valid_utf8("a\xFF" "b"), "a" + kReplacement + "b");
  EXPECT_EQ(valid_utf8("\xC3("), kReplacement + "(");                 // a lead byte without its tail
  EXPECT_EQ(valid_utf8("\xC0\xAF"), kReplacement + kReplacement);     // overlong '/'
  EXPECT_EQ(valid_utf8("\xED\xA0\x80"), kReplacement + kReplacement + kReplacement);  // a surrogate
  EXPECT_EQ(valid_utf8("\xE2\x82"), kReplacement + kReplacement);     // cut at the end
}

TEST(SafeText, PrintableTextEscapesControlCharactersAndCutsLongText) {
  EXPECT_EQ(printable_text("ERROR\r\nfake: line\x1B[2J\x07"), "ERROR\\x0D\\x0Afake: line\\x1B[2J\\x07");
  EXPECT_EQ(printable_text("tab\there\x7F"), "tab\\x09here\\x7F");
  EXPECT_EQ(printable_text("bad\xFF"), "bad" + kReplacement);
  EXPECT_EQ(printable_text(std::string(600, 'a'), 10), std::string(10, 'a') + "...");
}

TEST(SafeText, JsonTextReplacesWhereDumpThrows) {
  const nlohmann::json j = {{"id", "vase\xFF"}, {"description", "\xC3("}};
  EXPECT_THROW((void)j.dump(), nlohmann::json::type_error);  // why json_text exists
  std::string text;
  ASSERT_NO_THROW(text = json_text(j));
  EXPECT_EQ(text, "{\"description\":\"" + kReplacement + "(\",\"id\":\"vase" + kReplacement + "\"}");
  EXPECT_EQ(nlohmann::json::parse(text).at("id"), "vase" + kReplacement);
}

TEST(SafeText, JournalLineOfAnInvalidUtf8RecordIsWrittenNotThrown) {
  core::JournalRecord r;
  r.kind = core::JournalKind::Reset;
  r.item = "vase\xFF";
  r.reason = "restart \xC3(";
  r.time = 1.0e9;
  std::string line;
  ASSERT_NO_THROW(line = core::to_json_line(r));
  const nlohmann::json back = nlohmann::json::parse(line);
  EXPECT_EQ(back.at("item"), "vase" + kReplacement);
  EXPECT_EQ(back.at("reason"), "restart " + kReplacement + "(");
}

}  // namespace
}  // namespace rocking_monitor
