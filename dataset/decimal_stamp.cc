#include "dataset/decimal_stamp.h"

#include <algorithm>
#include <cstddef>

namespace vio {
namespace {

constexpr uint64_t kMaxNs = 9000000000000000000ULL;  // 9e9 s
// No exponent beyond this changes the outcome (a line is far shorter), and
// clamping keeps the position arithmetic below from overflowing.
constexpr int64_t kExponentClamp = 1000000;

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

// The text is split into its mantissa digits M (dot removed), the number of
// them before the dot, and the exponent E. The value is then 0.M x 10^p with
// p = (digits before the dot) + E; once M's leading zeros are dropped (each
// one lowering p by one), the nanosecond count floor(|value| * 1e9) is the
// first k = p + 9 digits of M, padded with zeros when M is shorter. Since M
// then starts with a non-zero digit, k > 19 means |value| >= 1e10 s.
DecimalStampStatus ParseDecimalSeconds(const std::string& text, int64_t* t_ns) {
  size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) i = 1;

  std::string mantissa;
  int64_t before_dot = 0;
  bool dot = false;
  for (; i < text.size() && (IsDigit(text[i]) || text[i] == '.'); ++i) {
    if (text[i] == '.') {
      if (dot) return DecimalStampStatus::kNotANumber;
      dot = true;
    } else {
      mantissa.push_back(text[i]);
      if (!dot) ++before_dot;
    }
  }
  if (mantissa.empty()) return DecimalStampStatus::kNotANumber;

  int64_t exponent = 0;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool exponent_negative = false;
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) {
      exponent_negative = text[i] == '-';
      ++i;
    }
    if (i == text.size()) return DecimalStampStatus::kNotANumber;
    for (; i < text.size() && IsDigit(text[i]); ++i) {
      exponent = std::min(kExponentClamp, exponent * 10 + (text[i] - '0'));
    }
    if (exponent_negative) exponent = -exponent;
  }
  if (i != text.size()) return DecimalStampStatus::kNotANumber;

  const size_t first = mantissa.find_first_not_of('0');
  if (first == std::string::npos) {
    *t_ns = 0;
    return DecimalStampStatus::kOk;
  }
  const std::string significant = mantissa.substr(first);
  const int64_t k = before_dot - static_cast<int64_t>(first) + exponent + 9;
  if (k > 19) return DecimalStampStatus::kOutOfRange;
  uint64_t ns = 0;
  for (int64_t d = 0; d < k; ++d) {
    const size_t index = static_cast<size_t>(d);
    ns = ns * 10 + (index < significant.size() ? significant[index] - '0' : 0);
  }
  if (ns >= kMaxNs) return DecimalStampStatus::kOutOfRange;
  *t_ns = negative ? -static_cast<int64_t>(ns) : static_cast<int64_t>(ns);
  return DecimalStampStatus::kOk;
}

}  // namespace vio
