// rpvio-eval as a user runs it: output lines, JSON, plot, and bad input (exit 2, one line).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_util.h"

namespace rpvio {
namespace {

const std::string kEvo = test::dataDir() + "/evo/";
const std::string kEval = test::binDir() + "/rpvio-eval";

TEST(EvalApp, PrintsAteLinesWritesJsonAndPlot) {
  test::TempDir dir;
  std::string out;
  const int rc = test::runCommand(
      kEval + " --gt " + kEvo + "KITTI_00_gt.txt --est " + kEvo + "KITTI_00_ORB.txt --est " + kEvo +
          "KITTI_00_SPTAM.txt --plot " + dir.file("p.png") + " --json " + dir.file("r.json"),
      out);
  ASSERT_EQ(rc, 0) << out;
  const auto first = out.find("ATE_RMSE 1.303449");
  const auto second = out.find("ATE_RMSE 3.738487");
  EXPECT_NE(first, std::string::npos) << out;
  EXPECT_NE(second, std::string::npos) << out;
  EXPECT_LT(first, second);
  const cv::Mat plot = cv::imread(dir.file("p.png"));
  EXPECT_GT(plot.cols, 1000);
  const std::string json = test::readFile(dir.file("r.json"));
  EXPECT_NEAR(test::jsonNumber(json, "rmse"), 1.3034497145650266, 1e-6) << json;
  EXPECT_EQ(test::jsonNumber(json, "pairs"), 4541) << json;
}

void expectFails(const std::string& args, const std::string& named) {
  std::string out;
  EXPECT_EQ(test::runCommand(kEval + " " + args, out), 2) << out;
  EXPECT_NE(out.find(named), std::string::npos) << out;
  EXPECT_EQ(out.find("ATE_RMSE"), std::string::npos) << out;
}

TEST(EvalApp, MalformedLine) {
  test::TempDir dir;
  test::writeText(dir.file("bad.tum"), "1 0 0 0 0 0 0 1\n2 0 0 zero 0 0 0 1\n");
  expectFails("--gt " + kEvo + "fr2_desk_groundtruth.txt --est " + dir.file("bad.tum"),
              "bad.tum:line 2");
}

TEST(EvalApp, EmptyFile) {
  test::TempDir dir;
  test::writeText(dir.file("empty.tum"), "");
  expectFails("--gt " + dir.file("empty.tum") + " --est " + kEvo + "fr2_desk_ORB.txt", "empty.tum");
}

TEST(EvalApp, NoOverlappingTimestamps) {
  test::TempDir dir;
  test::writeText(dir.file("late.tum"),
                  "9999999990 0 0 0 0 0 0 1\n9999999991 1 0 0 0 0 0 1\n9999999992 2 0 0 0 0 0 1\n");
  expectFails("--gt " + kEvo + "fr2_desk_groundtruth.txt --est " + dir.file("late.tum"),
              "late.tum");
}

TEST(EvalApp, MissingFileAndBadOption) {
  expectFails("--gt /nonexistent/gt.tum --est " + kEvo + "fr2_desk_ORB.txt", "/nonexistent/gt.tum");
  expectFails("--gt " + kEvo + "fr2_desk_ORB.txt --est " + kEvo + "fr2_desk_ORB.txt --align up",
              "unknown alignment");
}

}  // namespace
}  // namespace rpvio

namespace rpvio {
namespace {

TEST(EvalApp, MixedFormatsEurocCsvAgainstTum) {
  // A VIO estimate of EuRoC V1_02 (TUM) against its EuRoC CSV ground truth (ns stamps, w-first
  // quaternions): a wrong unit or quaternion order would give metres of error.
  std::string out;
  ASSERT_EQ(test::runCommand(kEval + " --gt " + kEvo + "V102_groundtruth.csv --est " + kEvo +
                                 "V102.txt --align se3",
                             out),
            0)
      << out;
  const double rmse = std::stod(out.substr(out.find("ATE_RMSE ") + 9));
  EXPECT_GT(rmse, 0.01);
  EXPECT_LT(rmse, 0.2);
}

}  // namespace
}  // namespace rpvio
