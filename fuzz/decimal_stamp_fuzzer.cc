// A TUM stamp's text (dataset/decimal_stamp.h: ParseDecimalSeconds), checked
// against an independent reading: strtold's long double, which holds 1e9 s
// to about 1e-10 s. Whatever parses must be that close to it, and what
// strtold reads as a plain decimal number within range must parse.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "dataset/decimal_stamp.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  int64_t t_ns = 0;
  const vio::DecimalStampStatus status = vio::ParseDecimalSeconds(text, &t_ns);
  // strtold also takes blanks, hex, inf and nan: compare only on our syntax.
  const bool plain =
      !text.empty() &&
      text.find_first_not_of("0123456789.eE+-") == std::string::npos;
  if (!plain) {
    vio::fuzz::Require(status == vio::DecimalStampStatus::kNotANumber,
                       "accepted a character outside [0-9.eE+-]: " + text);
    return 0;
  }
  char* end = nullptr;
  const long double reference = std::strtold(text.c_str(), &end);
  const bool whole = end == text.c_str() + text.size();
  if (status == vio::DecimalStampStatus::kOk) {
    vio::fuzz::Require(whole, "accepted what strtold stops in: " + text);
    const long double ns = reference * 1e9L;
    // Truncation (1 ns) plus the long double's own rounding of the reference.
    vio::fuzz::Require(
        std::fabs(ns - static_cast<long double>(t_ns)) <=
            1.0L + std::fabs(ns) * 1e-17L,
        "differs from strtold: " + text + " -> " + std::to_string(t_ns));
  } else if (status == vio::DecimalStampStatus::kOutOfRange) {
    vio::fuzz::Require(whole && std::fabs(reference) >= 8.9e9L,
                       "called out of range: " + text);
  } else if (whole && std::isfinite(reference) &&
             std::fabs(reference) < 8.9e9L) {
    // strtold took all of it; only forms it reads and we do not may differ:
    // none exist within [0-9.eE+-].
    vio::fuzz::Require(false, "refused a number strtold reads: " + text);
  }
  return 0;
}
