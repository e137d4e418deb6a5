#ifndef VIO_DATASET_CSV_H_
#define VIO_DATASET_CSV_H_

// A strict reader of the comma-separated files of the EuRoC ASL layout and of
// our own trajectory and observation files. Lines starting with '#' (after
// blanks) and blank lines are skipped wherever they are, and so is a UTF-8
// byte-order mark at the start of the file; every other line must have the
// expected number of fields, each of the expected type. Any violation is a
// DatasetError that names the file and the line:
// "mav0/imu0/data.csv:17: field 3 is not a number ('abc')".

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vio {

// Bad dataset or trajectory input; what() names the file and, where there is
// one, the line.
class DatasetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CsvReader {
 public:
  // Opens the file; throws DatasetError when it cannot be opened.
  explicit CsvReader(const std::string& path);

  // Reads the next data line into fields (split on ',' or on white space when
  // the line has no comma, as TUM files use). Returns false at the end.
  bool Next();

  // The current line's fields; their count; the 1-based line number.
  size_t size() const { return fields_.size(); }
  // Whether the current line was split on commas (else on white space).
  bool comma_separated() const { return comma_separated_; }
  int line() const { return line_; }
  const std::string& path() const { return path_; }

  // Throws unless the line has at least `n` fields ("expected 7 fields, got
  // 5").
  void ExpectAtLeast(size_t n) const;
  // The i-th field (0-based) as a number; throws naming file, line and field.
  double Double(size_t i) const;
  int64_t Int64(size_t i) const;
  const std::string& String(size_t i) const;

  // "path:line: message", for errors raised by callers about this line.
  [[noreturn]] void Fail(const std::string& message) const;

 private:
  std::string path_;
  std::ifstream in_;
  int line_ = 0;
  bool comma_separated_ = false;
  std::vector<std::string> fields_;
};

}  // namespace vio

#endif  // VIO_DATASET_CSV_H_
