#include "mutator.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <vector>

namespace rocking_monitor::fuzz {
namespace {

// Numbers that break naive parsing or overflow after unit scaling (g or cm/s^2 -> m/s^2).
const std::array<const char*, 30> kNumbers = {
    "1e308", "-1e308", "1.7976931348623157e308", "9e999", "1e-320", "4.9e-324", "0", "-0", "nan", "NaN",
    "-nan", "inf", "-Infinity", "INF", "1.0D+308", "0.5D-02", "1.0d300", "99999999999999999999", "-1",
    "2147483648", "-2147483649", "1e", "--1", ".", "0x1p3", "1,5", "+", "1e+", "18446744073709551616", "3.4e38"};

std::size_t pick(std::mt19937_64& rng, std::size_t n) {
  return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

bool numeric_char(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == 'e' || c == 'E' || c == 'd' ||
         c == 'D' || c == '+' || c == '-';
}

/// [begin, end) of a random token holding a digit, or {npos, npos}.
std::pair<std::size_t, std::size_t> number_token(const std::string& s, std::mt19937_64& rng) {
  for (int attempt = 0; attempt < 16 && !s.empty(); ++attempt) {
    std::size_t p = pick(rng, s.size());
    if (!std::isdigit(static_cast<unsigned char>(s[p]))) continue;
    std::size_t b = p, e = p;
    while (b > 0 && numeric_char(s[b - 1])) --b;
    while (e < s.size() && numeric_char(s[e])) ++e;
    return {b, e};
  }
  return {std::string::npos, std::string::npos};
}

/// Line starts (offsets) of s.
std::vector<std::size_t> line_starts(const std::string& s) {
  std::vector<std::size_t> out{0};
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] == '\n' && i + 1 < s.size()) out.push_back(i + 1);
  return out;
}

std::pair<std::size_t, std::size_t> random_line(const std::string& s, std::mt19937_64& rng) {
  const std::vector<std::size_t> starts = line_starts(s);
  const std::size_t k = pick(rng, starts.size());
  const std::size_t b = starts[k];
  const std::size_t e = k + 1 < starts.size() ? starts[k + 1] : s.size();
  return {b, e};
}

void mutate_once(std::string& s, std::mt19937_64& rng, bool binary) {
  const int kind = static_cast<int>(pick(rng, 10));
  switch (kind) {
    case 0: {  // flip bits in a few bytes (miniSEED: often in a fixed header)
      const int n = 1 + static_cast<int>(pick(rng, 8));
      for (int k = 0; k < n && !s.empty(); ++k) {
        std::size_t p = pick(rng, s.size());
        if (binary && pick(rng, 2) == 0) p = (pick(rng, s.size() / 512 + 1) * 512 + pick(rng, 64)) % s.size();
        s[p] = static_cast<char>(s[p] ^ (1u << pick(rng, 8)));
      }
      break;
    }
    case 1: {  // set a byte to an extreme value
      if (s.empty()) break;
      const std::array<char, 6> bytes = {'\0', '\x7f', '\xff', '\x80', '\r', '\t'};
      s[pick(rng, s.size())] = bytes[pick(rng, bytes.size())];
      break;
    }
    case 2:  // truncate (anywhere: mid-number, mid-line, mid-record)
      s.resize(pick(rng, s.size() + 1));
      break;
    case 3:
    case 4: {  // replace a number by a huge/tiny/NaN/Inf/Fortran/malformed one
      const auto [b, e] = number_token(s, rng);
      if (b != std::string::npos) s.replace(b, e - b, kNumbers[pick(rng, kNumbers.size())]);
      break;
    }
    case 5: {  // Fortran D exponent for an E one
      const auto [b, e] = number_token(s, rng);
      if (b == std::string::npos) break;
      for (std::size_t i = b; i < e; ++i)
        if (s[i] == 'E' || s[i] == 'e') s[i] = pick(rng, 2) ? 'D' : 'd';
      break;
    }
    case 6: {  // CRLF everywhere, or lone CR
      std::string out;
      const bool lone_cr = pick(rng, 3) == 0;
      for (char c : s) {
        if (c == '\n') out += lone_cr ? "\r" : "\r\n";
        else out += c;
      }
      s = out;
      break;
    }
    case 7:  // UTF-8 byte order mark
      s.insert(0, "\xEF\xBB\xBF");
      break;
    case 8: {  // duplicate a line
      const auto [b, e] = random_line(s, rng);
      s.insert(b, s.substr(b, e - b));
      break;
    }
    default: {  // delete a line
      const auto [b, e] = random_line(s, rng);
      s.erase(b, e - b);
      break;
    }
  }
}

}  // namespace

std::string mutate(const std::string& in, std::mt19937_64& rng, bool binary) {
  std::string s = in;
  const int n = 1 + static_cast<int>(pick(rng, 4));
  for (int k = 0; k < n; ++k) mutate_once(s, rng, binary);
  return s;
}

}  // namespace rocking_monitor::fuzz
