// The line-at-a-time readers of imu0/data.csv and camN/data.csv
// (dataset/euroc_csv_stream.h): the IMU stream gives the whole-file
// filter's samples and counts on the real EuRoC IMU files, clean and with
// stamp faults put in at random (fixed seed); errors name the file and the
// line that causes them, after the samples before it; the image list gives
// the listed images that exist, in order, and counts the others.

#include "dataset/euroc_csv_stream.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "dataset/csv.h"
#include "test/testing/glitchy_imu_lines.h"
#include "test/testing/temp_folder.h"
#include "test/testing/whole_file_imu_stamp_filter.h"

namespace vio {
namespace {

using ::testing::HasSubstr;
using testing::TempFolder;

const std::string kData = std::string(VIO_SHARED_DIR) + "/data/";
const std::vector<std::string> kRealImuFiles = {
    kData + "euroc_V1_01_first5s/mav0/imu0/data.csv",
    kData + "euroc_MH_05_imu_gt/mav0/imu0/data.csv"};

std::vector<ImuSample> StreamAll(const std::string& path,
                                 ImuStampReport* report) {
  ImuCsvStream stream(path, report);
  std::vector<ImuSample> samples;
  ImuSample s;
  while (stream.Next(&s)) samples.push_back(s);
  EXPECT_FALSE(stream.Next(&s)) << "stays at the end";
  return samples;
}

// The stream over `path` against the whole-file filter over its lines.
void ExpectStreamEqualsWholeFile(const std::string& path) {
  SCOPED_TRACE(path);
  ImuStampReport whole_report, streamed_report;
  const std::vector<ImuSample> whole = testing::WholeFileImuStampFilter(
      testing::ReadImuLines(path), &whole_report);
  const std::vector<ImuSample> streamed = StreamAll(path, &streamed_report);
  ASSERT_EQ(whole.size(), streamed.size());
  for (size_t i = 0; i < whole.size(); ++i) {
    ASSERT_EQ(whole[i].t_ns, streamed[i].t_ns) << i;
    ASSERT_EQ(whole[i].acc, streamed[i].acc) << i;
    ASSERT_EQ(whole[i].gyr, streamed[i].gyr) << i;
  }
  EXPECT_EQ(whole_report.repeated_lines, streamed_report.repeated_lines);
  EXPECT_EQ(whole_report.conflicting_repeats,
            streamed_report.conflicting_repeats);
  EXPECT_EQ(whole_report.out_of_order, streamed_report.out_of_order);
  EXPECT_EQ(whole_report.first_repeated_line,
            streamed_report.first_repeated_line);
  EXPECT_EQ(whole_report.first_conflict_line,
            streamed_report.first_conflict_line);
  EXPECT_EQ(whole_report.first_out_of_order_line,
            streamed_report.first_out_of_order_line);
  EXPECT_EQ(whole_report.first_conflict_t_ns,
            streamed_report.first_conflict_t_ns);
}

TEST(ImuCsvStream, GivesTheWholeFileFiltersSamplesOnTheRealEurocFiles) {
  for (const std::string& path : kRealImuFiles) {
    ExpectStreamEqualsWholeFile(path);
    ImuStampReport report;
    EXPECT_GT(StreamAll(path, &report).size(), 20000u);
    EXPECT_EQ(report.dropped(), 0) << "the real files are clean";
  }
}

TEST(ImuCsvStream, GivesTheWholeFileFiltersSamplesOnRealFilesWithFaults) {
  std::mt19937 rng(42);
  TempFolder dir;
  for (const std::string& real : kRealImuFiles) {
    for (const double rate : {0.002, 0.05, 0.3}) {
      // The first 20 s keep the test short.
      std::vector<ImuLine> lines = testing::ReadImuLines(real);
      lines.resize(4000);
      testing::InjectStampGlitches(&lines, rate, &rng);
      const std::string path = dir.Path("data.csv");
      {
        std::ofstream out(path);
        out << "#timestamp [ns],w_x,w_y,w_z,a_x,a_y,a_z\n";
        char row[256];
        for (const ImuLine& l : lines) {
          const ImuSample& s = l.sample;
          std::snprintf(row, sizeof(row),
                        "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                        static_cast<long long>(s.t_ns), s.gyr.x(), s.gyr.y(),
                        s.gyr.z(), s.acc.x(), s.acc.y(), s.acc.z());
          out << row;
        }
      }
      ExpectStreamEqualsWholeFile(path);
      ImuStampReport report;
      StreamAll(path, &report);
      EXPECT_GT(report.dropped(), 0) << "faults were put in at " << rate;
    }
  }
}

constexpr char kHeader[] = "#timestamp [ns],w_x,w_y,w_z,a_x,a_y,a_z\n";
constexpr char kGood[] = "0.1,0.2,0.3,9.8,0.0,0.1\n";

// Each error comes at its line, after the samples the lines before it gave.
TEST(ImuCsvStream, AnErrorNamesFileAndLineAfterTheSamplesBeforeIt) {
  TempFolder dir;
  const std::string path = dir.Path("data.csv");
  dir.Write("data.csv", std::string(kHeader) + "1000," + kGood + "2000," +
                            kGood + "3000," + kGood +
                            "4000,0.1,nan,0.3,9.8,0.0,0.1\n");
  ImuStampReport counts;
  for (ImuStampReport* report :
       {static_cast<ImuStampReport*>(nullptr), &counts}) {
    ImuCsvStream stream(path, report);
    ImuSample s;
    int samples = 0;
    try {
      while (stream.Next(&s)) ++samples;
      ADD_FAILURE() << "no error";
    } catch (const DatasetError& e) {
      EXPECT_THAT(e.what(),
                  HasSubstr(path + ":5: field 3 is not finite ('nan')"));
    }
    // Strict gives each sample as read; the filter holds one line back.
    EXPECT_EQ(samples, report == nullptr ? 3 : 2);
  }
  // Strict: the first stamp that does not increase.
  dir.Write("data.csv", std::string(kHeader) + "1000," + kGood + "2000," +
                            kGood + "1500," + kGood);
  ImuCsvStream strict(path, nullptr);
  ImuSample s;
  EXPECT_TRUE(strict.Next(&s));
  EXPECT_TRUE(strict.Next(&s));
  try {
    strict.Next(&s);
    ADD_FAILURE() << "no error";
  } catch (const DatasetError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ":4: timestamp 1500 is before the "
                                           "previous one (2000)"));
  }
  // No sample at all: an error at the end of the file.
  dir.Write("data.csv", kHeader);
  ImuStampReport report;
  ImuCsvStream empty(path, &report);
  try {
    empty.Next(&s);
    ADD_FAILURE() << "no error";
  } catch (const DatasetError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ": holds no IMU sample"));
  }
  try {
    ImuCsvStream missing(dir.Path("nope.csv"), &report);
    ADD_FAILURE() << "no error";
  } catch (const DatasetError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nope.csv: no such file"));
  }
}

TEST(ImageListStream, GivesTheListedImagesThatExistAndCountsTheOthers) {
  // cam1 of the V1_01 excerpt lists 99 images, 4 of them absent.
  const std::string cam1 = kData + "euroc_V1_01_first5s/mav0/cam1";
  ImageListStream stream(cam1 + "/data.csv", cam1 + "/data");
  std::vector<ImageEntry> got;
  ImageEntry e;
  while (stream.Next(&e)) got.push_back(e);
  EXPECT_FALSE(stream.Next(&e));
  EXPECT_EQ(stream.missing(), 4);
  // The list's rows, by a plain reading of the file.
  std::vector<ImageEntry> expected;
  std::ifstream list(cam1 + "/data.csv");
  std::string row;
  size_t rows = 0;
  while (std::getline(list, row)) {
    if (row.empty() || row[0] == '#') continue;
    ++rows;
    const size_t comma = row.find(',');
    std::string file = row.substr(comma + 1);
    while (!file.empty() && (file.back() == '\r' || file.back() == ' ')) {
      file.pop_back();
    }
    const std::string path = cam1 + "/data/" + file;
    if (std::filesystem::exists(path)) {
      expected.push_back({std::stoll(row.substr(0, comma)), path});
    }
  }
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_EQ(got.size() + 4, rows);
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t_ns, expected[i].t_ns);
    EXPECT_EQ(got[i].path, expected[i].path);
  }
}

TEST(ImageListStream, AnErrorNamesFileAndLineAfterTheImagesBeforeIt) {
  TempFolder dir;
  dir.Write("data/a.png", "x");
  dir.Write("data/b.png", "x");
  dir.Write("data.csv",
            "#timestamp [ns],filename\n100,a.png\n200,gone.png\n300,b.png\n"
            "250,c.png\n");
  ImageListStream stream(dir.Path("data.csv"), dir.Path("data"));
  ImageEntry e;
  ASSERT_TRUE(stream.Next(&e));
  EXPECT_EQ(e.t_ns, 100);
  ASSERT_TRUE(stream.Next(&e));
  EXPECT_EQ(e.t_ns, 300);
  EXPECT_EQ(stream.missing(), 1);
  try {
    stream.Next(&e);
    ADD_FAILURE() << "no error";
  } catch (const DatasetError& error) {
    EXPECT_THAT(error.what(),
                HasSubstr(dir.Path("data.csv") +
                          ":5: timestamp 250 is before the previous one"));
  }
}

}  // namespace
}  // namespace vio
