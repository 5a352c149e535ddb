// The strict number grammar shared by every record format: a token is consumed whole or rejected
// ("1.2.3", "0x10", "12abc"), FORTRAN "D" exponents are accepted, non-finite values are refused.
#include "record_reader_internal.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <string_view>
#include <system_error>

namespace rocking_monitor::core::record_io {

// ------------------------------------------------------------------ numbers

bool is_nonfinite_word(std::string_view t) {
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) t.remove_prefix(1);
  const std::string l = lower(t);
  return l == "nan" || l == "inf" || l == "infinity" || l == "-nan" || (l.size() > 4 && l.compare(0, 4, "nan(") == 0);
}

/// Strict decimal number: [+-] (digits [. digits] | . digits) [(E|e|D|d) [+-] digits], nothing else.
NumStatus parse_number(std::string_view tok, double& out) {
  const std::size_t n = tok.size();
  std::size_t i = 0;
  if (i < n && (tok[i] == '+' || tok[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++digits;
  bool has_d_exponent = false;
  if (i < n && tok[i] == '.') {
    ++i;
    while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++digits;
  }
  if (digits == 0) return is_nonfinite_word(tok) ? NumStatus::NonFinite : NumStatus::NonNumeric;
  if (i < n && (tok[i] == 'e' || tok[i] == 'E' || tok[i] == 'd' || tok[i] == 'D')) {
    has_d_exponent = tok[i] == 'd' || tok[i] == 'D';
    ++i;
    if (i < n && (tok[i] == '+' || tok[i] == '-')) ++i;
    std::size_t exp_digits = 0;
    while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++exp_digits;
    if (exp_digits == 0) return NumStatus::NonNumeric;
  }
  if (i != n) return NumStatus::NonNumeric;

  // from_chars does not take a leading '+' nor a 'D' exponent: normalise into a buffer.
  char small[128];
  std::string big;
  char* buf = small;
  if (n + 1 > sizeof small) {
    big.resize(n + 1);
    buf = big.data();
  }
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    char c = tok[k];
    if (k == 0 && c == '+') continue;
    if (has_d_exponent && (c == 'd' || c == 'D')) c = 'e';
    buf[m++] = c;
  }
  buf[m] = '\0';
  double value = 0.0;
  const auto res = std::from_chars(buf, buf + m, value, std::chars_format::general);
  if (res.ec == std::errc::result_out_of_range) {
    // Overflow (1e999) or underflow (1e-999): strtod tells which (the grammar is already checked).
    value = std::strtod(buf, nullptr);
    if (!std::isfinite(value)) return NumStatus::NonFinite;
  } else if (res.ec != std::errc() || res.ptr != buf + m) {
    return NumStatus::NonNumeric;
  }
  if (!std::isfinite(value)) return NumStatus::NonFinite;
  out = value;
  return NumStatus::Ok;
}

/// Parses a token or throws the standard "non-numeric value '...'" / "non-finite value '...'".
double number_or_fail(std::string_view tok, const std::string& path, std::size_t line) {
  double v = 0.0;
  switch (parse_number(tok, v)) {
    case NumStatus::Ok:
      return v;
    case NumStatus::NonFinite:
      fail(path, line, "non-finite value " + in_quotes(tok));
    case NumStatus::NonNumeric:
      break;
  }
  fail(path, line, "non-numeric value " + in_quotes(tok));
}

double scaled_or_fail(double value, double scale, const std::string& path, std::size_t line) {
  const double out = value * scale;
  if (!std::isfinite(out)) {
    std::ostringstream msg;
    msg << std::setprecision(10) << "value " << value << " overflows after conversion to m/s^2 (x " << scale << ")";
    fail(path, line, msg.str());
  }
  return out;
}

bool is_number(std::string_view tok) {
  double v = 0.0;
  return parse_number(tok, v) == NumStatus::Ok;
}

/// Strict non-negative/negative integer (digits only, optional sign).
bool parse_integer(std::string_view tok, long long& out) {
  if (tok.empty()) return false;
  const char* b = tok.data();
  const char* e = tok.data() + tok.size();
  if (*b == '+') {
    ++b;
    if (b == e || *b == '-') return false;
  }
  const auto res = std::from_chars(b, e, out, 10);
  return res.ec == std::errc() && res.ptr == e;
}

/// One unit in the last printed digit of a (validated) number token, e.g.
/// "5.000000e-03" -> 1e-9, "79.980000" -> 1e-6, "12" -> 1. Used as the rounding allowance of
/// printed time stamps.
double printed_resolution(std::string_view tok) {
  int frac_digits = 0;
  long exponent = 0;
  std::size_t i = 0;
  const std::size_t n = tok.size();
  while (i < n && tok[i] != '.' && tok[i] != 'e' && tok[i] != 'E' && tok[i] != 'd' && tok[i] != 'D') ++i;
  if (i < n && tok[i] == '.') {
    ++i;
    while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++frac_digits;
  }
  if (i < n && (tok[i] == 'e' || tok[i] == 'E' || tok[i] == 'd' || tok[i] == 'D')) {
    exponent = std::strtol(std::string(tok.substr(i + 1)).c_str(), nullptr, 10);
  }
  return std::pow(10.0, static_cast<double>(exponent - frac_digits));
}

}  // namespace rocking_monitor::core::record_io
