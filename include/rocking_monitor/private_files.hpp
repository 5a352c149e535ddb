#pragma once

// How this package creates the files it keeps (issue 54): journals, snapshots, the outbox and state
// files hold what a site monitors and where it sends alarms, so they are created readable by their
// owner only (0600), and written never through a link someone else planted. A temporary file for an
// atomic replace is made by mkostemp beside its target (same folder, so the rename stays atomic):
// a fresh name, O_EXCL, never an existing file or link. Header-only: every layer (feeds too) uses it.

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace rocking_monitor {

constexpr mode_t kPrivateFileMode = 0600;

/// Flags for opening a kept file for appending: created 0600 (with kPrivateFileMode), not through a
/// symbolic link at its last component.
constexpr int kPrivateAppendFlags = O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW;

/// Creates "<path>.tmp.XXXXXX" (a fresh unique name, mode 0600, O_EXCL) beside `path`; its descriptor,
/// or -1 with errno set. `tmp_path` receives the name to write, rename over `path` or unlink.
inline int create_temp_beside(const std::string& path, std::string& tmp_path) {
  std::string pattern = path + ".tmp.XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd >= 0) tmp_path = name.data();
  return fd;
}

/// Reads a secret kept in a file (a password, issue 52 item 5): false with `error` naming the file
/// ("password file '/etc/x'") and why when it cannot be opened, is not a regular file, is larger than
/// `max_bytes`, or is accessible to group or others (any of mode 077: a secret others can read is
/// none). The mode is that of the open descriptor (fstat), so no file is swapped in between.
inline bool read_private_file(const std::string& path, const std::string& what, std::size_t max_bytes,
                              std::string& content, std::string& error) {
  const std::string name = what + " '" + path + "'";
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = name + ": " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  error.clear();
  if (::fstat(fd, &st) != 0) {
    error = name + ": " + std::strerror(errno);
  } else if (!S_ISREG(st.st_mode)) {
    error = name + " is not a regular file";
  } else if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    error = name + " is accessible to group or others (mode " + mode + "): chmod 600 it";
  } else if (st.st_size > static_cast<off_t>(max_bytes)) {
    error = name + " is larger than " + std::to_string(max_bytes) + " bytes";
  } else {
    content.assign(static_cast<std::size_t>(st.st_size), '\0');
    std::size_t got = 0;
    while (got < content.size()) {
      const ssize_t n = ::read(fd, &content[got], content.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += static_cast<std::size_t>(n);
    }
    content.resize(got);
  }
  ::close(fd);
  return error.empty();
}

}  // namespace rocking_monitor
