#include "dataset/csv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace vio {
namespace {

std::string Trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

}  // namespace

CsvReader::CsvReader(const std::string& path) : path_(path), in_(path) {
  if (!in_) throw DatasetError(path + ": cannot open the file");
}

bool CsvReader::Next() {
  std::string text;
  while (std::getline(in_, text)) {
    ++line_;
    // Written by some Windows editors and exporters; evo skips it too.
    if (line_ == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
    const std::string t = Trim(text);
    if (t.empty() || t[0] == '#') continue;
    fields_.clear();
    comma_separated_ = t.find(',') != std::string::npos;
    if (comma_separated_) {
      std::stringstream ss(t);
      std::string f;
      while (std::getline(ss, f, ',')) fields_.push_back(Trim(f));
      if (t.back() == ',') fields_.push_back("");
    } else {
      std::istringstream ss(t);
      std::string f;
      while (ss >> f) fields_.push_back(f);
    }
    return true;
  }
  return false;
}

void CsvReader::Fail(const std::string& message) const {
  throw DatasetError(path_ + ":" + std::to_string(line_) + ": " + message);
}

void CsvReader::ExpectAtLeast(size_t n) const {
  if (fields_.size() < n) {
    Fail("expected " + std::to_string(n) + " fields, got " +
         std::to_string(fields_.size()));
  }
}

const std::string& CsvReader::String(size_t i) const {
  ExpectAtLeast(i + 1);
  return fields_[i];
}

double CsvReader::Double(size_t i) const {
  const std::string& f = String(i);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(f.c_str(), &end);
  if (f.empty() || *end != '\0' || errno == ERANGE) {
    Fail("field " + std::to_string(i + 1) + " is not a number ('" + f + "')");
  }
  if (!std::isfinite(v)) {
    Fail("field " + std::to_string(i + 1) + " is not finite ('" + f + "')");
  }
  return v;
}

int64_t CsvReader::Int64(size_t i) const {
  const std::string& f = String(i);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(f.c_str(), &end, 10);
  if (f.empty() || *end != '\0' || errno == ERANGE) {
    Fail("field " + std::to_string(i + 1) + " is not an integer ('" + f + "')");
  }
  return static_cast<int64_t>(v);
}

}  // namespace vio
