#pragma once

// Secrets out of messages (issue 54): a webhook URL often carries its token in the path or query
// (https://hooks.example/services/T0/B0/secret, ?token=...), and SMTP or HTTP URLs may hold
// "user:pass@". Errors, logs, /diagnostics and reports show the redacted form only.

#include <string>

namespace rocking_monitor::notify {

/// The URL with its user information and everything after the host[:port] replaced by "***":
/// "https://user:pw@hooks.example:8443/services/T0/B0/x?token=y" -> "https://***@hooks.example:8443/***".
/// A text that is no URL ("no scheme://") comes back as "***" unless empty.
std::string redact_url(const std::string& url);

/// `text` with every occurrence of `url` replaced by redact_url(url), and of `password` (when not
/// empty) by "***": for error texts that quote either.
std::string redact_secrets(std::string text, const std::string& url, const std::string& password = "");

}  // namespace rocking_monitor::notify
