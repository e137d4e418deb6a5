// landmarks.csv: a round trip, and malformed lines as file:line errors.

#include "dataset/landmarks_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset/csv.h"
#include "testing/expect_error.h"
#include "testing/temp_folder.h"

namespace vio {
namespace {

TEST(LandmarksIo, WrittenLandmarksReadBack) {
  testing::TempFolder dir;
  const std::vector<LandmarkRow> points = {{{1.0, -2.5, 0.125}, 3.25},
                                           {{1e-7, 123.456789, -4.0}, 0.5}};
  WriteLandmarksCsv(dir.Path("landmarks.csv"), points);
  const std::vector<LandmarkRow> back =
      ReadLandmarksCsv(dir.Path("landmarks.csv"));
  ASSERT_EQ(back.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_LT((back[i].p_w - points[i].p_w).norm(), 1e-8);
    EXPECT_DOUBLE_EQ(back[i].parallax_deg, points[i].parallax_deg);
  }
}

TEST(LandmarksIo, ThreeFieldLinesHaveNoAngle) {
  testing::TempFolder dir;
  dir.Write("xyz.csv", "# x y z\n1,2,3\n");
  const std::vector<LandmarkRow> rows = ReadLandmarksCsv(dir.Path("xyz.csv"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].p_w, Eigen::Vector3d(1, 2, 3));
  EXPECT_LT(rows[0].parallax_deg, 0.0);
}

TEST(LandmarksIo, AnEmptyMapIsNotAnError) {
  testing::TempFolder dir;
  WriteLandmarksCsv(dir.Path("landmarks.csv"), {});
  EXPECT_TRUE(ReadLandmarksCsv(dir.Path("landmarks.csv")).empty());
}

TEST(LandmarksIo, MalformedLinesNameFileAndLine) {
  testing::TempFolder dir;
  dir.Write("a.csv", "#x,y,z\n1,2,3\n1,2\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadLandmarksCsv(dir.Path("a.csv")); },
      "a.csv:3: a landmark line has 4 fields (x,y,z,parallax_deg) or 3, got 2");
  dir.Write("c.csv", "1,2,3,-1\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadLandmarksCsv(dir.Path("c.csv")); },
      "c.csv:1: the parallax is negative");
  dir.Write("b.csv", "1,2,3\n1,nan,3\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadLandmarksCsv(dir.Path("b.csv")); }, "b.csv:2: field 2");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadLandmarksCsv(dir.Path("missing.csv")); }, "missing.csv");
}

}  // namespace
}  // namespace vio
