// Issue 54: the files the monitor keeps (journal, snapshot, SeedLink state) are created 0600, and
// temporary files are fresh names made beside their target: a link planted at the old fixed
// "<path>.tmp" name is never followed, a link at a journal's path is refused.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "rocking_monitor/feeds/sequence_state.hpp"
#include "rocking_monitor/monitoring/alarm_journal.hpp"
#include "rocking_monitor/monitoring/state_snapshot.hpp"
#include "temp_root.hpp"

namespace rocking_monitor::core {
namespace {

const testing::TempRoot& private_root = testing::TempRoot::registered("rocking_private_files_");

std::string private_scratch(const std::string& name) {
  const std::filesystem::path dir = private_root.path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

unsigned mode_of(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return 07777;
  return st.st_mode & 0777;
}

std::string contents_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PrivateFiles, JournalSnapshotAndSequenceStateAreCreated0600) {
  const ::mode_t old_umask = ::umask(022);  // the usual umask: 0644 would survive it
  const std::string dir = private_scratch("modes");
  AlarmJournal journal;
  ASSERT_EQ(journal.open(dir + "/journal.jsonl", 3600.0, 1.0e9), "");
  const std::uint8_t data[4] = {1, 2, 3, 4};
  ASSERT_EQ(write_file_durably(dir + "/state.snapshot", data, sizeof data), "");
  feeds::write_sequence_state(dir + "/seedlink.state", {{"CI_RIN", 0x102}});
  ::umask(old_umask);
  EXPECT_EQ(mode_of(dir + "/journal.jsonl"), 0600u);
  EXPECT_EQ(mode_of(dir + "/state.snapshot"), 0600u);
  EXPECT_EQ(mode_of(dir + "/seedlink.state"), 0600u);
  EXPECT_EQ(feeds::read_sequence_state(dir + "/seedlink.state").at("CI_RIN"), 0x102u);
}

TEST(PrivateFiles, ALinkPlantedAtTheOldTemporaryNameIsNotFollowed) {
  const std::string dir = private_scratch("links");
  const std::string victim = dir + "/victim";
  std::ofstream(victim) << "keep me";
  for (const std::string name : {"seedlink.state", "state.snapshot"})
    ASSERT_EQ(::symlink(victim.c_str(), (dir + "/" + name + ".tmp").c_str()), 0);
  feeds::write_sequence_state(dir + "/seedlink.state", {{"CI_RIN", 7}});
  const std::uint8_t data[4] = {1, 2, 3, 4};
  ASSERT_EQ(write_file_durably(dir + "/state.snapshot", data, sizeof data), "");
  EXPECT_EQ(contents_of(victim), "keep me");
  EXPECT_EQ(feeds::read_sequence_state(dir + "/seedlink.state").at("CI_RIN"), 7u);
  EXPECT_EQ(contents_of(dir + "/state.snapshot"), std::string("\x01\x02\x03\x04", 4));
}

TEST(PrivateFiles, AJournalPathThatIsALinkIsRefused) {
  const std::string dir = private_scratch("journal_link");
  const std::string victim = dir + "/victim";
  std::ofstream(victim) << "keep me";
  ASSERT_EQ(::symlink(victim.c_str(), (dir + "/journal.jsonl").c_str()), 0);
  AlarmJournal journal;
  const std::string e = journal.open(dir + "/journal.jsonl", 3600.0, 1.0e9);
  EXPECT_NE(e.find(dir + "/journal.jsonl"), std::string::npos) << e;
  EXPECT_EQ(contents_of(victim), "keep me");
}

}  // namespace
}  // namespace rocking_monitor::core
