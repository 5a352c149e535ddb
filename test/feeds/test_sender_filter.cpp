// Tests of udp_accel_bridge's ~allowed_senders (src/feeds/sender_filter.cpp): addresses, ports,
// CIDR boundaries at /0, /24 and /32, and bad entries refused with a message naming the entry.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rocking_monitor/feeds/sender_filter.hpp"

namespace fd = rocking_monitor::feeds;

namespace {

constexpr std::uint32_t sender_ip(unsigned a, unsigned b, unsigned c, unsigned d) {
  return (a << 24) | (b << 16) | (c << 8) | d;
}

fd::SenderFilter sender_filter(const std::vector<std::string>& entries) {
  fd::SenderFilter f;
  std::string error;
  EXPECT_TRUE(f.configure(entries, error)) << error;
  return f;
}

std::string sender_refusal(const std::string& entry) {
  std::string error;
  EXPECT_FALSE(fd::parse_sender_rule(entry, error).has_value()) << entry;
  return error;
}

}  // namespace

TEST(SenderFilter, ParsesAndFormatsAddresses) {
  EXPECT_EQ(fd::parse_ipv4("192.168.1.20"), sender_ip(192, 168, 1, 20));
  EXPECT_EQ(fd::parse_ipv4("0.0.0.0"), 0u);
  EXPECT_EQ(fd::parse_ipv4("255.255.255.255"), 0xFFFFFFFFu);
  EXPECT_EQ(fd::format_ipv4(sender_ip(10, 0, 3, 7)), "10.0.3.7");
  EXPECT_EQ(fd::format_endpoint(sender_ip(127, 0, 0, 2), 15601), "127.0.0.2:15601");
  for (const char* bad : {"", "1.2.3", "1.2.3.4.5", "256.1.1.1", "1..2.3", "a.b.c.d", " 1.2.3.4",
                          "1.2.3.4 ", "+1.2.3.4", "0x7f.0.0.1", "1.2.3.1000"})
    EXPECT_FALSE(fd::parse_ipv4(bad).has_value()) << "'" << bad << "'";
}

TEST(SenderFilter, SingleAddressIsSlash32AnyPort) {
  const auto f = sender_filter({"192.168.1.20"});
  ASSERT_EQ(f.rules().size(), 1u);
  EXPECT_EQ(f.rules()[0].prefix, 32);
  EXPECT_EQ(f.rules()[0].mask, 0xFFFFFFFFu);
  EXPECT_FALSE(f.rules()[0].port.has_value());
  EXPECT_TRUE(f.pinned());
  EXPECT_TRUE(f.allows(sender_ip(192, 168, 1, 20), 1));
  EXPECT_TRUE(f.allows(sender_ip(192, 168, 1, 20), 65535));
  EXPECT_FALSE(f.allows(sender_ip(192, 168, 1, 21), 1));
  EXPECT_FALSE(f.allows(sender_ip(192, 168, 1, 19), 1));
}

TEST(SenderFilter, ExplicitSlash32AndPort) {
  const auto f = sender_filter({"127.0.0.1/32", "10.0.0.9:15601"});
  EXPECT_TRUE(f.allows(sender_ip(127, 0, 0, 1), 40000));
  EXPECT_FALSE(f.allows(sender_ip(127, 0, 0, 2), 40000));
  EXPECT_TRUE(f.allows(sender_ip(10, 0, 0, 9), 15601));
  EXPECT_FALSE(f.allows(sender_ip(10, 0, 0, 9), 15602));
  EXPECT_FALSE(f.allows(sender_ip(10, 0, 0, 9), 15600));
  EXPECT_FALSE(f.allows(sender_ip(10, 0, 0, 8), 15601));
}

TEST(SenderFilter, Slash24Boundaries) {
  const auto f = sender_filter({"192.168.7.0/24"});
  EXPECT_EQ(f.rules()[0].mask, 0xFFFFFF00u);
  EXPECT_TRUE(f.allows(sender_ip(192, 168, 7, 0), 5));
  EXPECT_TRUE(f.allows(sender_ip(192, 168, 7, 255), 5));
  EXPECT_FALSE(f.allows(sender_ip(192, 168, 6, 255), 5));
  EXPECT_FALSE(f.allows(sender_ip(192, 168, 8, 0), 5));
}

TEST(SenderFilter, Slash0IsEveryoneButMustBeWritten) {
  const auto f = sender_filter({"0.0.0.0/0"});
  EXPECT_EQ(f.rules()[0].mask, 0u);
  EXPECT_TRUE(f.pinned());
  EXPECT_TRUE(f.allows(0u, 1));
  EXPECT_TRUE(f.allows(0xFFFFFFFFu, 65535));
  EXPECT_TRUE(f.allows(sender_ip(8, 8, 8, 8), 53));
}

TEST(SenderFilter, EmptyListAcceptsEveryoneUnpinned) {
  const auto f = sender_filter({});
  EXPECT_FALSE(f.pinned());
  EXPECT_TRUE(f.allows(sender_ip(1, 2, 3, 4), 9));
}

TEST(SenderFilter, BadEntriesAreRefusedNamingTheEntry) {
  EXPECT_EQ(sender_refusal("10.0.0.5/24"),
            "allowed_senders entry '10.0.0.5/24': host bits are set beyond /24 (the range is "
            "10.0.0.0/24)");
  EXPECT_EQ(sender_refusal("10.0.0.1/33"),
            "allowed_senders entry '10.0.0.1/33': the prefix length after '/' must be a number 0-32");
  EXPECT_EQ(sender_refusal("10.0.0.1:0"), "allowed_senders entry '10.0.0.1:0': the port must be a number 1-65535");
  EXPECT_EQ(sender_refusal("10.0.0.1:65536"),
            "allowed_senders entry '10.0.0.1:65536': the port must be a number 1-65535");
  EXPECT_EQ(sender_refusal("controller.lab"),
            "allowed_senders entry 'controller.lab': not an IPv4 address a.b.c.d (each part 0-255)");
  EXPECT_EQ(sender_refusal("10.0.0.0/24:5"),
            "allowed_senders entry '10.0.0.0/24:5': give either a port (a.b.c.d:port) or a range "
            "(a.b.c.d/nn), not both");
  EXPECT_NE(sender_refusal("10.0.0.1:").find("'10.0.0.1:'"), std::string::npos);
  EXPECT_NE(sender_refusal("10.0.0.0/").find("'10.0.0.0/'"), std::string::npos);
}

TEST(SenderFilter, OneBadEntryRefusesTheListAndKeepsTheOldRules) {
  fd::SenderFilter f = sender_filter({"127.0.0.1"});
  std::string error;
  EXPECT_FALSE(f.configure({"10.0.0.1", "10.0.0.300"}, error));
  EXPECT_EQ(error, "allowed_senders entry '10.0.0.300': not an IPv4 address a.b.c.d (each part 0-255)");
  ASSERT_EQ(f.rules().size(), 1u);
  EXPECT_TRUE(f.allows(sender_ip(127, 0, 0, 1), 1));
  EXPECT_FALSE(f.allows(sender_ip(10, 0, 0, 1), 1));
}

TEST(SenderTally, CountsAdmittedAndDroppedPerSource) {
  const auto f = sender_filter({"127.0.0.1:15601"});
  fd::SenderTally tally;
  EXPECT_TRUE(tally.admit(f, sender_ip(127, 0, 0, 1), 15601));
  EXPECT_TRUE(tally.admit(f, sender_ip(127, 0, 0, 1), 15601));
  EXPECT_FALSE(tally.admit(f, sender_ip(127, 0, 0, 1), 15602));
  EXPECT_FALSE(tally.admit(f, sender_ip(127, 0, 0, 2), 15601));
  EXPECT_FALSE(tally.admit(f, sender_ip(127, 0, 0, 2), 15601));
  EXPECT_EQ(tally.dropped_total(), 3u);
  EXPECT_EQ(tally.admitted_sources(), 1u);
  EXPECT_EQ(fd::SenderTally::describe(tally.admitted()), "127.0.0.1:15601 (2)");
  EXPECT_EQ(fd::SenderTally::describe(tally.dropped()), "127.0.0.1:15602 (1), 127.0.0.2:15601 (2)");
  EXPECT_EQ(fd::SenderTally::describe({}), "none");
}

TEST(SenderTally, ManySourcesAreStillCountedBeyondTheList) {
  const auto f = sender_filter({"10.0.0.1"});
  fd::SenderTally tally;
  const std::size_t n = fd::SenderTally::kMaxListed + 5;
  for (std::size_t k = 0; k < n; ++k)
    EXPECT_FALSE(tally.admit(f, sender_ip(10, 0, 1, 0) + static_cast<std::uint32_t>(k), 7));
  EXPECT_EQ(tally.dropped_total(), n);
  EXPECT_EQ(tally.dropped().size(), fd::SenderTally::kMaxListed);
  EXPECT_EQ(tally.unlisted_dropped(), 5u);
}

TEST(SenderTally, UnpinnedCountsDistinctSenders) {
  const auto f = sender_filter({});
  fd::SenderTally tally;
  EXPECT_TRUE(tally.admit(f, sender_ip(127, 0, 0, 1), 5000));
  EXPECT_EQ(tally.admitted_sources(), 1u);
  EXPECT_TRUE(tally.admit(f, sender_ip(127, 0, 0, 2), 5000));
  EXPECT_EQ(tally.admitted_sources(), 2u);
  EXPECT_EQ(tally.dropped_total(), 0u);
}

TEST(SenderFilter, OneStringListSplitsOnCommasAndSpaces) {
  EXPECT_EQ(fd::split_sender_list("10.0.0.1, 10.0.0.0/24  127.0.0.1:5,"),
            (std::vector<std::string>{"10.0.0.1", "10.0.0.0/24", "127.0.0.1:5"}));
  EXPECT_TRUE(fd::split_sender_list("").empty());
  EXPECT_TRUE(fd::split_sender_list(" , ").empty());
}
