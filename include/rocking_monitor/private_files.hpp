#pragma once

// How this package creates the files it keeps (issue 54): journals, snapshots, the outbox and state
// files hold what a site monitors and where it sends alarms, so they are created readable by their
// owner only (0600), and written never through a link someone else planted. A temporary file for an
// atomic replace is made by mkostemp beside its target (same folder, so the rename stays atomic):
// a fresh name, O_EXCL, never an existing file or link. Header-only: every layer (feeds too) uses it.

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>

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

}  // namespace rocking_monitor
