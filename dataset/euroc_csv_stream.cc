#include "dataset/euroc_csv_stream.h"

#include <filesystem>

#include "dataset/csv.h"

namespace vio {
namespace {

std::string JoinFolder(const std::string& folder, const std::string& name) {
  return (std::filesystem::path(folder) / name).string();
}

bool IsFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::unique_ptr<CsvReader> OpenRequired(const std::string& path) {
  if (!IsFile(path)) throw DatasetError(path + ": no such file");
  return std::make_unique<CsvReader>(path);
}

void RequireIncreasing(const CsvReader& csv, bool first, int64_t previous,
                       int64_t t_ns) {
  if (first) return;
  if (t_ns == previous) {
    csv.Fail("timestamp " + std::to_string(t_ns) + " is repeated");
  }
  if (t_ns < previous) {
    csv.Fail("timestamp " + std::to_string(t_ns) +
             " is before the previous one (" + std::to_string(previous) + ")");
  }
}

void RequireFieldCount(const CsvReader& csv, size_t n, const char* what) {
  csv.ExpectAtLeast(n);
  if (csv.size() != n) {
    csv.Fail("expected " + std::to_string(n) + " fields (" + what + "), got " +
             std::to_string(csv.size()));
  }
}

}  // namespace

ImuCsvStream::ImuCsvStream(const std::string& path, ImuStampReport* report)
    : path_(path),
      csv_(OpenRequired(path)),
      strict_(report == nullptr),
      filter_(report != nullptr ? report : &unused_report_) {}

ImuCsvStream::~ImuCsvStream() = default;

bool ImuCsvStream::ReadLine(ImuLine* line) {
  CsvReader& csv = *csv_;
  if (!csv.Next()) return false;
  RequireFieldCount(csv, 7, "timestamp, 3 angular rates, 3 accelerations");
  ImuSample& s = line->sample;
  s.t_ns = csv.Int64(0);
  if (strict_) RequireIncreasing(csv, !any_line_, previous_t_ns_, s.t_ns);
  s.gyr = {csv.Double(1), csv.Double(2), csv.Double(3)};
  s.acc = {csv.Double(4), csv.Double(5), csv.Double(6)};
  line->line = csv.line();
  any_line_ = true;
  previous_t_ns_ = s.t_ns;
  return true;
}

bool ImuCsvStream::Next(ImuSample* sample) {
  ImuLine line;
  while (!finished_) {
    if (!ReadLine(&line)) {
      finished_ = true;
      if (!any_line_) throw DatasetError(path_ + ": holds no IMU sample");
      return !strict_ && filter_.Finish(sample);
    }
    if (strict_) {
      *sample = line.sample;
      return true;
    }
    if (filter_.Add(line, sample)) return true;
  }
  return false;
}

ImageListStream::ImageListStream(const std::string& path,
                                 const std::string& image_folder)
    : image_folder_(image_folder), csv_(OpenRequired(path)) {}

ImageListStream::~ImageListStream() = default;

bool ImageListStream::Next(ImageEntry* entry) {
  CsvReader& csv = *csv_;
  while (csv.Next()) {
    RequireFieldCount(csv, 2, "timestamp, filename");
    const int64_t t_ns = csv.Int64(0);
    RequireIncreasing(csv, !any_line_, previous_t_ns_, t_ns);
    any_line_ = true;
    previous_t_ns_ = t_ns;
    const std::string& name = csv.String(1);
    if (name.empty()) csv.Fail("the filename is empty");
    std::string image = JoinFolder(image_folder_, name);
    if (IsFile(image)) {
      entry->t_ns = t_ns;
      entry->path = std::move(image);
      return true;
    }
    ++missing_;
  }
  return false;
}

}  // namespace vio
