// rpvio-bench --executor slurm against a real single-node Slurm (scripts/start-slurm.sh; label
// `slurm`, run by `make test-slurm`): a short suite generated and run as job arrays gives the same
// results as the local executor; a failed run is named by --collect and --resubmit-failed runs
// only it again. Skipped (not passed) when the Slurm daemons cannot start here.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <sstream>
#include <thread>
#include <vector>

#include "tests/test_util.h"

namespace rpvio {
namespace {

namespace fs = std::filesystem;

/// Every run of results.json (one line each) reduced to the figures the deterministic pipeline
/// repeats exactly: no timings, no folders.
std::vector<std::string> deterministicRuns(const std::string& results_json) {
  const std::regex field(
      R"re("(sequence|mode|run|exit_code|evaluated|tracked|ate_rmse|ate_rotation_deg|coverage|refined_ate_rmse|initialized_at|resets)": ("[^"]*"|[^,}]*))re");
  std::vector<std::string> runs;
  std::istringstream lines(results_json);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("\"sequence\":") == std::string::npos) continue;
    std::string run;
    for (std::sregex_iterator m(line.begin(), line.end(), field), end; m != end; ++m)
      run += m->str() + " ";
    runs.push_back(run);
  }
  return runs;
}

class SlurmBench : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string output;
    if (test::runCommand(std::string(RPVIO_SOURCE_DIR) + "/scripts/start-slurm.sh", output) != 0)
      GTEST_SKIP() << "no Slurm here: " << output;
  }
  std::string bench(const std::string& args) const {
    return test::binDir() + "/rpvio-bench --modes vins-mono,rpvio-single --sequences static,C2 " +
           args;
  }
};

TEST_F(SlurmBench, JobArraysGiveTheLocalExecutorsResults) {
  test::TempDir dir;
  const std::string suite = dir.file("suite");
  std::string output;
  ASSERT_EQ(test::runCommand(bench("--suite " + suite +
                                   " --generate --duration 8 --executor slurm --jobs 2 --out " +
                                   dir.file("slurm")),
                             output),
            0)
      << output;
  EXPECT_NE(output.find("[slurm SLAM runs, job "), std::string::npos) << output;
  ASSERT_EQ(
      test::runCommand(bench("--suite " + suite + " --jobs 2 --out " + dir.file("local")), output),
      0)
      << output;
  const auto slurm = deterministicRuns(test::readFile(dir.file("slurm/results.json")));
  const auto local = deterministicRuns(test::readFile(dir.file("local/results.json")));
  ASSERT_EQ(slurm.size(), 4u);
  EXPECT_EQ(slurm, local);
  EXPECT_NE(slurm[0].find("\"exit_code\": 0"), std::string::npos) << slurm[0];
  EXPECT_NE(slurm[0].find("\"evaluated\": true"), std::string::npos) << slurm[0];
}

TEST_F(SlurmBench, CollectNamesTheFailedRunAndResubmitRerunsOnlyIt) {
  test::TempDir dir;
  const std::string suite = dir.file("suite");
  std::string output;
  for (const char* sequence : {"static", "C2"})
    ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-sim --sequence " + sequence +
                                   " --duration 8 --out " + suite + "/" + sequence,
                               output),
              0)
        << output;
  const fs::path rawlog = fs::path(suite) / "C2" / "seq.rawlog";
  fs::copy_file(rawlog, dir.file("good.rawlog"));
  fs::resize_file(rawlog, 2000);  // a corrupt rawlog: rpvio-slam exits 2
  const std::string out = dir.file("out");
  ASSERT_EQ(test::runCommand(
                bench("--suite " + suite + " --executor slurm --submit-only --out " + out), output),
            0)
      << output;
  EXPECT_NE(output.find("rpvio-bench --collect " + out), std::string::npos) << output;
  // Collecting waits for nothing: poll until every run has left its status.
  for (int s = 0; s < 300 && !(fs::exists(out + "/runs/C2/rpvio-single/run0/task.json") &&
                               fs::exists(out + "/runs/C2/vins-mono/run0/task.json") &&
                               fs::exists(out + "/runs/static/rpvio-single/run0/task.json") &&
                               fs::exists(out + "/runs/static/vins-mono/run0/task.json"));
       ++s)
    std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-bench --collect " + out, output), 0)
      << output;
  EXPECT_NE(output.find("2 of 4 runs failed or did not finish"), std::string::npos) << output;
  for (const char* mode : {"vins-mono", "rpvio-single"}) {
    const std::regex report(
        std::string("C2 ") + mode +
        R"( run 0: exited with 2 \(Slurm job [0-9]+_[0-9]: FAILED, Slurm log .*rpvio-slam_[0-9].out\), log .*/runs/C2/)" +
        mode + "/run0/log.txt");
    EXPECT_TRUE(std::regex_search(output, report)) << mode << "\n" << output;
  }
  EXPECT_EQ(output.find("static vins-mono run 0: exited"), std::string::npos) << output;

  const std::string static_status = test::readFile(out + "/runs/static/vins-mono/run0/task.json");
  fs::copy_file(dir.file("good.rawlog"), rawlog, fs::copy_options::overwrite_existing);
  ASSERT_EQ(test::runCommand(
                test::binDir() + "/rpvio-bench --collect " + out + " --resubmit-failed", output),
            0)
      << output;
  EXPECT_NE(output.find("running 2 failed or unfinished run(s) again"), std::string::npos)
      << output;
  EXPECT_EQ(output.find("failed or did not finish:"), std::string::npos) << output;
  // The static runs were not run again (their status, with its wall time, is the same file).
  EXPECT_EQ(test::readFile(out + "/runs/static/vins-mono/run0/task.json"), static_status);
  for (const std::string& run : deterministicRuns(test::readFile(out + "/results.json")))
    EXPECT_NE(run.find("\"exit_code\": 0"), std::string::npos) << run;
}

}  // namespace
}  // namespace rpvio
