// Numbers written in text we don't control (label files, replay scripts, filters): the whole text is one
// number or it is an error. strtod/strtol alone stop at the first byte they can't use, so "0.20\0\0\0" (a
// zero-filled block after a crash) read as 0.20 and "5x" as 5.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace ipd {

// [+-] digits [. digits] [e [+-] digits], also ".5" and "5."; nothing else (no hex, no spaces, no "nan").
bool is_decimal(std::string_view s);

// The value of a decimal (is_decimal), read in the C locale's spelling whatever the process locale; false
// for anything else. 1e309 reads as infinity: range checks are the caller's.
bool parse_decimal(const std::string& s, double* out);

// [-] digits within [lo, hi]; false for anything else (a sign alone, "5x", a value out of range).
bool parse_integer(const std::string& s, long long lo, long long hi, long long* out);

// A seed, the one range of every seed the tools take (--seed, study.yaml's registration.seed): digits only,
// 0 to 2^64 - 1, the whole range of the generators' 64-bit seed. False for a sign, "5x" or a larger value:
// such a value is never clamped or wrapped into another seed.
bool parse_seed(const std::string& s, std::uint64_t* out);
// What parse_seed accepts, for messages: "a whole number from 0 to 18446744073709551615".
extern const char* const kSeedRange;

// "nan", "-inf", "Infinity": a number, but not a finite one (said so, rather than "not a number").
bool is_non_finite_word(std::string_view s);

// Untrusted text for a message: at most 40 characters of it, control bytes (a NUL, an escape) and bytes that
// are not UTF-8 as \xHH, so the message stays readable on a terminal and fits in a JSON error object.
std::string quoted_for_message(std::string_view s);

// A whole number with thousands separators, as every count the tools print: 89700 -> "89,700", -1234 -> "-1,234".
std::string grouped_thousands(long long n);

// `decimals` fixed decimals that never read "-0.000": a value that rounds to zero prints unsigned. The studio,
// `ipd register` and a registration's fit in words all print through it.
std::string fixed_decimals(double v, int decimals);

}  // namespace ipd
