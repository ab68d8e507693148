// rpvio-bench, short variant (issue 9): generates a 30 s C4 sequence, runs two modes side by side
// in parallel, and must write a results table, a JSON with every run and a plot; rpvio-single
// must cover the sequence. Bad arguments exit 2 with a one-line message.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_util.h"

namespace rpvio {
namespace {

/// The JSON object of the run of `mode` (flat, one line per run in results.json).
std::string runObject(const std::string& json, const std::string& mode) {
  const auto at = json.find("\"mode\": \"" + mode + "\"");
  if (at == std::string::npos) return "";
  const auto begin = json.rfind('{', at);
  return json.substr(begin, json.find('}', at) - begin + 1);
}

TEST(BenchApp, ShortSuiteSideBySide) {
  test::TempDir dir;
  const std::string command = test::binDir() + "/rpvio-bench --suite " + dir.file("suite") +
                              " --generate --duration 30 --sequences C4 --modes "
                              "vins-mono,rpvio-single --jobs 2 --out " +
                              dir.file("out");
  std::string output;
  ASSERT_EQ(test::runCommand(command, output), 0) << output;
  const std::string markdown = test::readFile(dir.file("out/results.md"));
  EXPECT_NE(markdown.find("| mode | C4 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| vins-mono |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| rpvio-single |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("total median"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("processing median"), std::string::npos) << markdown;
  // The sequence's moving-thing coverage from its sequence.json (the paper's C4: about 1 %).
  EXPECT_NE(markdown.find("| moving things (median % of the image) | "), std::string::npos)
      << markdown;

  const std::string json = test::readFile(dir.file("out/results.json"));
  const double c4_dynamic = test::jsonNumber(json, "C4");
  EXPECT_TRUE(c4_dynamic > 0.005 && c4_dynamic < 0.02) << json;
  for (const char* mode : {"vins-mono", "rpvio-single"}) {
    const std::string run = runObject(json, mode);
    ASSERT_FALSE(run.empty()) << mode << " missing in " << json;
    EXPECT_NE(run.find("\"evaluated\": true"), std::string::npos) << run;
    const double ate = test::jsonNumber(run, "ate_rmse");
    EXPECT_TRUE(ate > 0 && ate < 5) << run;
    EXPECT_GT(test::jsonNumber(run, "total_ms_median"), 0) << run;
    EXPECT_GT(test::jsonNumber(run, "processing_ms_median"), 0) << run;
    EXPECT_LT(test::jsonNumber(run, "processing_ms_median"),
              test::jsonNumber(run, "total_ms_median"))
        << run;
  }
  const std::string rpvio = runObject(json, "rpvio-single");
  EXPECT_GE(test::jsonNumber(rpvio, "coverage"), 0.9) << rpvio;
  EXPECT_NE(rpvio.find("\"tracked\": true"), std::string::npos) << rpvio;

  const cv::Mat plot = cv::imread(dir.file("out/plots/C4.png"));
  EXPECT_GT(plot.cols, 400);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/runs/C4/rpvio-single/run0/trajectory.tum")));
}

TEST(BenchApp, BadArgumentsExitTwo) {
  test::TempDir dir;
  const std::string bench = test::binDir() + "/rpvio-bench --out " + dir.file("out") + " ";
  std::string output;
  EXPECT_EQ(test::runCommand(bench + "--suite " + dir.file("none") + " --sequences C4", output), 2);
  EXPECT_NE(output.find(dir.file("none") + "/C4/seq.rawlog"), std::string::npos) << output;
  EXPECT_EQ(test::runCommand(bench + "--suite x --sequences C4,walls", output), 2);
  EXPECT_NE(output.find("unknown sequence 'walls'"), std::string::npos) << output;
  EXPECT_EQ(test::runCommand(bench + "--suite x --modes nonsense", output), 2);
  EXPECT_NE(output.find("nonsense.ini"), std::string::npos) << output;
  EXPECT_EQ(test::runCommand(bench + "--suite x --runs 0", output), 2);
  EXPECT_EQ(test::runCommand(bench + "--suite x --profile easy", output), 2);
  EXPECT_NE(output.find("--profile"), std::string::npos) << output;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-bench --help", output), 0);
  EXPECT_EQ(output.rfind("usage: rpvio-bench", 0), 0u) << output;
}

}  // namespace
}  // namespace rpvio
