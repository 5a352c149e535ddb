#include "seed_records.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "network_parsers.hpp"  // kFuzzDatagramKey
#include "record_writers.hpp"  // test/support: the writers the format tests use
#include "rocking_monitor/feeds/udp_datagram.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::fuzz {
namespace {

namespace rm = rocking_monitor::core;
namespace rt = rocking_monitor::core::testing;
namespace rf = rocking_monitor::feeds;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read fuzz seed");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Seed file_seed(const std::string& path) {
  return {path.substr(path.find_last_of('/') + 1), slurp(path)};
}

std::string csv(const rm::Component& c) {
  std::string s = "time_s,accel_mps2\n";
  char b[64];
  for (std::size_t i = 0; i < c.accel.size(); ++i) {
    std::snprintf(b, sizeof b, "%.3f,%.9g\n", static_cast<double>(i) * c.dt, c.accel[i]);
    s += b;
  }
  return s;
}

}  // namespace

double miniseed_gain() { return rt::logger_gain(); }

std::vector<Target> make_targets(const std::string& records_dir, const std::string& config_dir) {
  const std::string r = records_dir + "/";
  const rm::Component h228 = rm::read_record(r + "northridge_1994/Rinaldi228.AT2").at(0);
  std::vector<Target> t;
  t.push_back({"at2", false,
               {file_seed(r + "northridge_1994/Rinaldi228.AT2"), file_seed(r + "northridge_1994/RinaldiUP.AT2"),
                file_seed(r + "imperial_valley_1979/H-E01140.at2")}});
  t.push_back({"bbp", false, {file_seed(r + "northridge_1994/s01.bbp")}});
  t.push_back({"smc", false, {file_seed(r + "loma_prieta_1989/0111a.smc")}});
  t.push_back({"csv", false, {{"rinaldi228.csv", csv(h228)}}});
  // The plainest files of each format (no quirks): the mutator adds the damage.
  const std::string mseed = rt::interleave(
      {rt::pack_channel("HNE", 1.0 / h228.dt, rt::kRinaldiStart, rt::counts(h228, rt::logger_gain()), DE_STEIM2, 512)});
  rt::CosmosChannel v2{&h228, 228, h228.dt};
  v2.quirks = false;
  t.push_back({"miniseed", true, {{"rrs.mseed", mseed}}});
  t.push_back({"cosmos", false, {{"rrs.v2", rt::cosmos_channel(v2, 1, "\n")}}});
  t.push_back({"knet", false,
               {{"RRS0019401171231.EW",
                 rt::knet_file(h228, "E-W", 8009, "\n", true, "3920(gal)/6182761", false).text}}});
  const std::vector<Seed> catalogues = {file_seed(config_dir + "/catalogue_example.yaml"),
                                        file_seed(config_dir + "/catalogue_uncertain_example.yaml")};  // config/monitor.yaml holds no catalogue
  t.push_back({"catalogue", false, catalogues});
  t.push_back({"catalogue_items", false, catalogues});
  // The network parsers (issue 54): what a shaking table's datagram, a SeedLink server's packets and
  // replies, and one miniSEED record off the wire can hold.
  const std::string record512 = rt::pack_channel("HNZ", 1.0 / h228.dt, rt::kRinaldiStart, rt::counts(h228, rt::logger_gain()),
                                                 DE_STEIM2, 512).at(0);
  unsigned char binary[48];
  const double accel[3] = {0.1, -0.02, 9.81};
  rf::encode_binary(42, 12.345, accel, binary);
  unsigned char authenticated[rf::kAuthSize];
  rf::encode_binary_auth(43, 12.35, accel,
                         rf::DatagramKey{reinterpret_cast<const unsigned char*>(kFuzzDatagramKey), sizeof kFuzzDatagramKey - 1},
                         authenticated);
  t.push_back({"udp_datagram", true,
               {{"text.dgram", "12.345,0.1,-0.02,0.003\n"}, {"binary.dgram", std::string(reinterpret_cast<char*>(binary), 48)},
                {"binary_v2.dgram", std::string(reinterpret_cast<char*>(authenticated), rf::kAuthSize)}}});
  t.push_back({"seedlink", true,
               {{"packet.sl", "SL00A3F1" + record512},
                {"replies.sl", "SeedLink v3.1 (2020.075) :: SLPROTO:3.1\r\nGEOFON\r\nOK\r\nERROR\r\n"}}});
  t.push_back({"mseed_record", true, {{"record.mseed", record512}}});
  return t;
}

}  // namespace rocking_monitor::fuzz
