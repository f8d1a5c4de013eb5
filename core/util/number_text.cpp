#include "core/util/number_text.h"

#include <fmt/format.h>
#include <cerrno>
#include <clocale>
#include <cstdio>
#include <cstdlib>

#include "core/util/utf8.h"

namespace ipd {

bool is_decimal(std::string_view s) {
  size_t k = 0;
  auto digits = [&] {
    const size_t start = k;
    while (k < s.size() && s[k] >= '0' && s[k] <= '9') ++k;
    return k - start;
  };
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
  size_t mantissa = digits();
  if (k < s.size() && s[k] == '.') {
    ++k;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
    ++k;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
    if (digits() == 0) return false;
  }
  return k == s.size();
}

bool parse_decimal(const std::string& s, double* out) {
  if (!is_decimal(s)) return false;
  // strtod reads the process locale's decimal point: under a locale that writes "0,5" it would stop at the
  // '.', so the point is swapped for the locale's own one first.
  std::string text = s;
  const char* point = std::localeconv()->decimal_point;
  if (point && point[0] && point[0] != '.' && !point[1])
    for (char& c : text)
      if (c == '.') c = point[0];
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return false;
  *out = v;
  return true;
}

bool parse_integer(const std::string& s, long long lo, long long hi, long long* out) {
  const size_t first = !s.empty() && s[0] == '-' ? 1 : 0;
  if (s.size() == first || s.size() > first + 18) return false;  // 18 digits: never overflows long long
  for (size_t k = first; k < s.size(); ++k)
    if (s[k] < '0' || s[k] > '9') return false;
  const long long v = std::strtoll(s.c_str(), nullptr, 10);
  if (v < lo || v > hi) return false;
  *out = v;
  return true;
}

const char* const kSeedRange = "a whole number from 0 to 18446744073709551615";

bool parse_seed(const std::string& s, std::uint64_t* out) {
  if (s.empty()) return false;
  std::uint64_t v = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
    const auto digit = static_cast<std::uint64_t>(c - '0');
    if (v > (UINT64_MAX - digit) / 10) return false;  // v * 10 + digit would wrap
    v = v * 10 + digit;
  }
  *out = v;
  return true;
}

bool is_non_finite_word(std::string_view s) {
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.remove_prefix(1);
  std::string w;
  for (const unsigned char c : s) w += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return w == "nan" || w == "inf" || w == "infinity";
}

std::string quoted_for_message(std::string_view s) {
  const std::string cut = s.size() > 40 ? std::string(s.substr(0, 37)) + "..." : std::string(s);
  return escape_non_utf8(cut);
}

std::string grouped_thousands(long long n) {
  const bool negative = n < 0;
  // -(n + 1) + 1 in unsigned: the magnitude of the smallest long long too.
  const std::string digits =
      std::to_string(negative ? static_cast<unsigned long long>(-(n + 1)) + 1ULL : static_cast<unsigned long long>(n));
  std::string out = negative ? "-" : "";
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return out;
}

std::string fixed_decimals(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace ipd
