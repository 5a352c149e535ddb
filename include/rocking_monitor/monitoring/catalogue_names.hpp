#pragma once

// The character rule of catalogue ids (issue 54): an item id or a sensor name is a name, not text.
// It becomes an MQTT topic level, part of a file name, an e-mail subject and a dashboard key, so it
// holds only ASCII letters, digits, '_', '-' and '.', and cannot add a header, a topic level or a
// path. Descriptions stay free text and are encoded where they are used.

#include <cstddef>
#include <string>
#include <string_view>

namespace rocking_monitor::core {

constexpr std::size_t kMaxNameLength = 128;  ///< bytes; well below a file name's 255

/// Which names a rule admits beyond letters, digits, '_', '-' and '.'.
enum class NameRule {
  Strict,        ///< the live catalogue: ids reach MQTT topics, mail and file names
  MemberSuffix,  ///< offline catalogues: also "<id>#<k>", a member of an ensemble (rocking_geometry.py)
};

/// "" when `name` follows the rule; otherwise why not, naming the first offending character,
/// e.g. "'va se' holds ' ' at character 3: use letters, digits, '_', '-' and '.'".
std::string name_problem(std::string_view name, NameRule rule = NameRule::Strict);

}  // namespace rocking_monitor::core
