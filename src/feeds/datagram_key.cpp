// Reading the shared datagram key (datagram_key.hpp): a private file (private_files.hpp: the mode
// checked on the open descriptor, so no file is swapped in between), one trailing newline dropped.
#include "rocking_monitor/feeds/datagram_key.hpp"

#include <string>

#include "rocking_monitor/private_files.hpp"

namespace rocking_monitor::feeds {

bool read_key_file(const std::string& path, std::vector<unsigned char>& key, std::string& error) {
  error.clear();
  if (path.empty()) {
    error = "key file: empty path";
    return false;
  }
  std::string text;
  if (!read_private_file(path, "key file", kMaxKeyBytes, text, error)) {
    if (error.find("is larger than") != std::string::npos) error += ": not a key";
    return false;
  }
  const std::size_t got = text.size();
  if (!text.empty() && text.back() == '\n') text.pop_back();  // one, documented
  if (text.empty()) {
    error = "key file '" + path + "' is empty" + (got > 0 ? " (after its trailing newline)" : "");
    return false;
  }
  key.assign(text.begin(), text.end());
  return true;
}

}  // namespace rocking_monitor::feeds
