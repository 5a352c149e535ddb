#pragma once

// The shared key of authenticated (version 2) datagrams, read from the bridge's ~key_file (issue 52,
// docs/inputs.md "Authenticated datagrams"). The file is refused when it cannot be read, is not a
// regular file, is empty, is larger than kMaxKeyBytes, or is accessible to group or others (any of
// mode 077): a key others can read authenticates nothing. The key is the file's raw bytes, with one
// trailing "\n" stripped (a key typed into an editor); binary keys from /dev/urandom are taken as
// they are, except that one final 0x0a byte is stripped too.

#include <cstddef>
#include <string>
#include <vector>

namespace rocking_monitor::feeds {

/// Larger than any sensible HMAC key: a file this big is the wrong file.
inline constexpr std::size_t kMaxKeyBytes = 4096;

/// Reads the key from `path` into `key`. On refusal returns false and sets `error` to a sentence
/// that names the file and the reason ("key file '/etc/k' is readable by group or others (mode
/// 0644): chmod 600 it").
bool read_key_file(const std::string& path, std::vector<unsigned char>& key, std::string& error);

}  // namespace rocking_monitor::feeds
