// Redacting URLs and passwords out of texts (see the header).
#include "rocking_monitor/notify/redact.hpp"

namespace rocking_monitor::notify {
namespace {

void replace_every(std::string& text, const std::string& what, const std::string& with) {
  if (what.empty()) return;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + with.size()))
    text.replace(at, what.size(), with);
}

}  // namespace

std::string redact_url(const std::string& url) {
  if (url.empty()) return url;
  const std::size_t scheme_end = url.find("://");
  if (scheme_end == std::string::npos) return "***";
  const std::size_t host_start = scheme_end + 3;
  std::size_t host_end = url.find_first_of("/?#", host_start);
  if (host_end == std::string::npos) host_end = url.size();
  std::string authority = url.substr(host_start, host_end - host_start);
  const std::size_t at = authority.rfind('@');
  if (at != std::string::npos) authority = "***@" + authority.substr(at + 1);
  std::string out = url.substr(0, host_start) + authority;
  // A bare "/" says nothing secret; any other path or query may be the token.
  if (host_end < url.size() && url.substr(host_end) != "/") out += "/***";
  return out;
}

std::string redact_secrets(std::string text, const std::string& url, const std::string& password) {
  replace_every(text, url, redact_url(url));
  replace_every(text, password, "***");
  return text;
}

}  // namespace rocking_monitor::notify
