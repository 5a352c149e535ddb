#pragma once

// The one way this package turns a JSON document into text (issue 54): nlohmann::json::dump()
// throws type_error 316 on a string that is not valid UTF-8, and a throw inside a ROS callback or a
// notifier thread ends the node. Here invalid bytes become U+FFFD instead, so one bad item id,
// description or server reply can cost a character, never the node.

#include <string>

#include <nlohmann/json.hpp>

namespace rocking_monitor {

/// json.dump(indent) that never throws on invalid UTF-8 (each bad byte becomes U+FFFD).
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace rocking_monitor
