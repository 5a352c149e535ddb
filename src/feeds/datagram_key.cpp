// Reading the shared datagram key (datagram_key.hpp). The file is opened first and fstat'ed on the
// open descriptor, so the mode checked is that of the bytes read (no swap between check and read).
#include "rocking_monitor/feeds/datagram_key.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

namespace rocking_monitor::feeds {

bool read_key_file(const std::string& path, std::vector<unsigned char>& key, std::string& error) {
  error.clear();
  const std::string name = "key file '" + path + "'";
  if (path.empty()) {
    error = "key file: empty path";
    return false;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = name + ": " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  std::vector<unsigned char> bytes;
  if (::fstat(fd, &st) != 0) {
    error = name + ": " + std::strerror(errno);
  } else if (!S_ISREG(st.st_mode)) {
    error = name + " is not a regular file";
  } else if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    error = name + " is accessible to group or others (mode " + mode + "): chmod 600 it";
  } else if (st.st_size > static_cast<off_t>(kMaxKeyBytes)) {
    error = name + " is larger than " + std::to_string(kMaxKeyBytes) + " bytes: not a key";
  } else {
    bytes.resize(static_cast<std::size_t>(st.st_size));
    std::size_t got = 0;
    while (got < bytes.size()) {
      const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += static_cast<std::size_t>(n);
    }
    bytes.resize(got);
    if (!bytes.empty() && bytes.back() == '\n') bytes.pop_back();  // one, documented
    if (bytes.empty()) error = name + " is empty" + (got > 0 ? " (after its trailing newline)" : "");
  }
  ::close(fd);
  if (!error.empty()) return false;
  key = std::move(bytes);
  return true;
}

}  // namespace rocking_monitor::feeds
