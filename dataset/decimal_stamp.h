#ifndef VIO_DATASET_DECIMAL_STAMP_H_
#define VIO_DATASET_DECIMAL_STAMP_H_

// A timestamp in seconds, written as text, read into integer nanoseconds
// without going through a double: 1.4e9 s at nanosecond resolution needs 19
// significant digits, a double holds 15 to 17.
//
// Accepted: [+-]digits[.digits][(e|E)[+-]digits] with at least one digit
// before the exponent, so "1403715529.112143517", "1403715529", ".5", "5."
// and numpy's (evo's) "1.403715529112143517e+09" all read. Digits below one
// nanosecond are cut (truncation toward zero). Not accepted: "nan", "inf",
// hexadecimal, digit separators, anything after the number.

#include <cstdint>
#include <string>

namespace vio {

enum class DecimalStampStatus {
  kOk,
  kNotANumber,  // the text is not of the form above
  kOutOfRange,  // |t| >= 9e9 s: past what int64 nanoseconds hold (9.2e9 s)
};

// Parses `text` (no surrounding blanks); on kOk sets *t_ns.
DecimalStampStatus ParseDecimalSeconds(const std::string& text, int64_t* t_ns);

}  // namespace vio

#endif  // VIO_DATASET_DECIMAL_STAMP_H_
