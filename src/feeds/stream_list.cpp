// "NET_STA:SELECTORS" items -> StreamSpec, with errors that name the item.
#include "rocking_monitor/feeds/stream_list.hpp"

#include <sstream>
#include <stdexcept>

#include "rocking_monitor/feeds/seedlink_protocol.hpp"

namespace rocking_monitor::feeds {

StreamSpec parse_stream(const std::string& item) {
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument("stream '" + item + "': " + what + " (expected NET_STA:SELECTORS, e.g. CI_RIN:HN?)");
  };
  const std::size_t colon = item.find(':');
  if (colon == std::string::npos) fail("no ':' before the channel selectors");
  const std::string id = item.substr(0, colon);
  const std::size_t underscore = id.find('_');
  if (underscore == std::string::npos) fail("no '_' between network and station");
  StreamSpec s;
  s.network = id.substr(0, underscore);
  s.station = id.substr(underscore + 1);
  std::istringstream words(item.substr(colon + 1));
  for (std::string w; words >> w;) s.selectors.push_back(w);
  if (s.selectors.empty()) fail("no channel selector after ':'");
  try {
    station_command(s.network, s.station);
    for (const std::string& sel : s.selectors) select_command(sel);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
  return s;
}

std::vector<StreamSpec> parse_streams(const std::vector<std::string>& items) {
  if (items.empty()) throw std::invalid_argument("no stream given (a list of NET_STA:SELECTORS, e.g. [\"CI_RIN:HN?\"])");
  std::vector<StreamSpec> out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    StreamSpec s = parse_stream(items[i]);
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (out[j].name() == s.name())
        throw std::invalid_argument("stream '" + items[i] + "': station " + s.name() + " is already given by '" + items[j] +
                                    "' (put all its selectors in one item)");
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace rocking_monitor::feeds
