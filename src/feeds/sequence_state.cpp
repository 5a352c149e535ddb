// Last sequence number per station <-> a small text file (see the header).
#include "rocking_monitor/feeds/sequence_state.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rocking_monitor/feeds/seedlink_protocol.hpp"
#include "rocking_monitor/private_files.hpp"

namespace rocking_monitor::feeds {

std::map<std::string, std::uint32_t> read_sequence_state(const std::string& path) {
  std::map<std::string, std::uint32_t> state;
  std::ifstream in(path);
  if (!in) return state;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string station, hex, extra;
    words >> station >> hex >> extra;
    char* end = nullptr;
    const unsigned long v = hex.empty() ? 0 : std::strtoul(hex.c_str(), &end, 16);
    if (station.empty() || hex.empty() || !extra.empty() || end != hex.c_str() + hex.size() || v >= kSequenceModulus)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected '<NET_STA> <sequence, hex below 1000000>', got '" + line + "'");
    state[station] = static_cast<std::uint32_t>(v);
  }
  return state;
}

void write_sequence_state(const std::string& path, const std::map<std::string, std::uint32_t>& state) {
  std::string text = "# seedlink_bridge: last SeedLink sequence number handed on, per station\n";
  char hex[16];
  for (const auto& [station, seq] : state) {
    std::snprintf(hex, sizeof hex, "%06X", static_cast<unsigned>(seq));
    text += station + " " + hex + "\n";
  }
  std::string tmp;
  const int fd = create_temp_beside(path, tmp);  // 0600, a fresh name: never an existing file or link
  if (fd < 0) throw std::runtime_error(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (done < text.size()) {
    ::unlink(tmp.c_str());
    throw std::runtime_error(tmp + ": cannot write the sequence state");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    ::unlink(tmp.c_str());
    throw std::runtime_error(path + ": cannot replace the sequence state");
  }
}

}  // namespace rocking_monitor::feeds
