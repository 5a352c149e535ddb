// The character rule of catalogue ids (see the header).
#include "rocking_monitor/monitoring/catalogue_names.hpp"

#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor::core {
namespace {

bool name_char_ok(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
}

// The member suffix "#<digits>" at `at` up to the end (rocking_geometry.py writes "SP1#0" ..).
bool member_suffix_at(std::string_view name, std::size_t at) {
  if (at == 0 || name[at] != '#' || at + 1 == name.size()) return false;
  for (std::size_t k = at + 1; k < name.size(); ++k)
    if (name[k] < '0' || name[k] > '9') return false;
  return true;
}

}  // namespace

std::string name_problem(std::string_view name, NameRule rule) {
  if (name.empty()) return "is empty: give a name of letters, digits, '_', '-' and '.'";
  const std::string shown = "'" + printable_text(name, 64) + "'";
  if (name.size() > kMaxNameLength)
    return shown + " is " + std::to_string(name.size()) + " bytes long: at most " + std::to_string(kMaxNameLength);
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name_char_ok(name[i])) continue;
    if (rule == NameRule::MemberSuffix && member_suffix_at(name, i)) return "";
    const std::string what = printable_text(std::string_view(&name[i], 1));
    // A byte of a non-ASCII character is shown as its code, not as half a character.
    const std::string ch = static_cast<unsigned char>(name[i]) >= 0x80 ? "a non-ASCII byte" : "'" + what + "'";
    return shown + " holds " + ch + " at character " + std::to_string(i + 1) +
           ": an id is a name of letters, digits, '_', '-' and '.' (it becomes an MQTT topic level, a file name "
           "and part of an e-mail subject)" +
           (rule == NameRule::MemberSuffix ? ", optionally followed by '#<member number>'" : "");
  }
  return "";
}

}  // namespace rocking_monitor::core
