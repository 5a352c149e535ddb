// The sequence state file: written and read back; absent = empty; a bad line names file and line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "rocking_monitor/feeds/sequence_state.hpp"

namespace rocking_monitor::feeds {
namespace {

TEST(SequenceState, RoundTripAndErrors) {
  const std::string path = "/tmp/seedlink_state_" + std::to_string(getpid()) + ".txt";
  EXPECT_TRUE(read_sequence_state(path).empty());
  write_sequence_state(path, {{"CI_RIN", 0x00A3F1}, {"IU_ANMO", 0xFFFFFF}});
  {
    std::ifstream in(path);
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(all.find("CI_RIN 00A3F1\n"), std::string::npos) << all;
    EXPECT_NE(all.find("IU_ANMO FFFFFF\n"), std::string::npos) << all;
  }
  const auto back = read_sequence_state(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back.at("CI_RIN"), 0x00A3F1u);
  EXPECT_EQ(back.at("IU_ANMO"), 0xFFFFFFu);
  {
    std::ofstream out(path);
    out << "# comment\nCI_RIN 00A3F1\nIU_ANMO 1000000\n";
  }
  try {
    read_sequence_state(path);
    ADD_FAILURE() << "a sequence number beyond 24 bits was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3: expected"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace rocking_monitor::feeds
