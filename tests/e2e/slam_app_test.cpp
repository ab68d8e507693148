// rpvio-slam as a user runs it on a simulated rawlog: outputs written and parseable, the same
// inputs twice give the identical trajectory, bad arguments exit 2, a truncated rawlog keeps the
// frames before the truncation.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_writer.h"
#include "rawlog_io/trajectory_io.h"
#include "sim/sequence_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

/// rpvio-slam in a mode (config/<mode>.ini) on a simulated sequence folder's calib.ini and rawlog
/// (its seq.rawlog unless given), quiet, ending in "--out " (the caller adds the folder).
std::string slamCommand(const std::string& mode, const std::string& sequence_dir,
                        const std::string& rawlog = "") {
  return test::binDir() + "/rpvio-slam --config " + RPVIO_SOURCE_DIR + "/config/" + mode +
         ".ini --calib " + sequence_dir + "/calib.ini --rawlog " +
         (rawlog.empty() ? sequence_dir + "/seq.rawlog" : rawlog) + " --quiet --out ";
}

/// A simulated sequence of `duration` s with `characters` characters in `dir`/seq.
void writeSimulatedSequence(const test::TempDir& dir, double duration, int characters = 0) {
  sim::SimConfig config;
  config.duration = duration;
  config.scene.characters = characters;
  sim::writeSequence(config, dir.file("seq"));
}

TEST(SlamApp, WritesOutputsAndIsDeterministic) {
  test::TempDir dir;
  writeSimulatedSequence(dir, 6.0, 2);
  const std::string slam = slamCommand("rpvio-single", dir.file("seq"));
  std::string out;
  ASSERT_EQ(test::runCommand(slam + dir.file("a"), out), 0) << out;
  ASSERT_EQ(test::runCommand(slam + dir.file("b"), out), 0) << out;
  const Trajectory trajectory = readTum(dir.file("a/trajectory.tum"));
  EXPECT_GT(trajectory.size(), 60u);  // initialized after 2 s, every frame afterwards
  EXPECT_EQ(test::readFile(dir.file("a/trajectory.tum")),
            test::readFile(dir.file("b/trajectory.tum")));
  // rpvio-multi too (its plane covariances), the second run with its heap elsewhere: nothing may
  // depend on where blocks are allocated.
  const std::string multi = slamCommand("rpvio-multi", dir.file("seq"));
  ASSERT_EQ(test::runCommand(multi + dir.file("m1"), out), 0) << out;
  ASSERT_EQ(
      test::runCommand(
          "env RPVIO_TEST_PADDING=" + std::string(12000, 'x') + " " + multi + dir.file("m2"), out),
      0)
      << out;
  EXPECT_EQ(test::readFile(dir.file("m1/trajectory.tum")),
            test::readFile(dir.file("m2/trajectory.tum")));
  EXPECT_EQ(test::readFile(dir.file("m1/planes.yaml")), test::readFile(dir.file("m2/planes.yaml")));
  const std::string summary = test::readFile(dir.file("a/summary.json"));
  EXPECT_EQ(test::jsonNumber(summary, "resets"), 0) << summary;
  EXPECT_EQ(test::jsonNumber(summary, "poses"), static_cast<double>(trajectory.size())) << summary;
  // Timing split: decoding of the image files, then the processing of the frame.
  const double total = test::jsonNumber(summary, "total_ms_median");
  const double load = test::jsonNumber(summary, "load_ms_median");
  const double processing = test::jsonNumber(summary, "processing_ms_median");
  EXPECT_GT(load, 0) << summary;
  EXPECT_GT(processing, 0) << summary;
  EXPECT_LE(processing, total) << summary;
  std::ifstream stats(dir.file("a/stats.csv"));
  std::string header, row;
  ASSERT_TRUE(std::getline(stats, header));
  EXPECT_EQ(header, "t,load_ms,frontend_ms,optimization_ms,total_ms,features,planes,state");
  size_t rows = 0;
  while (std::getline(stats, row)) {
    double t = 0, load_ms = 0, frontend_ms = 0, optimization_ms = 0, total_ms = 0;
    char comma = 0;
    std::istringstream(row) >> t >> comma >> load_ms >> comma >> frontend_ms >> comma >>
        optimization_ms >> comma >> total_ms;
    ++rows;
    EXPECT_NEAR(load_ms + frontend_ms + optimization_ms, total_ms, 0.0025) << row;
    // Every frame is tracked in its own row, whichever row its optimization falls in (a frame
    // waiting for IMU data is optimized with the next one): the front-end's share is never 0.
    EXPECT_GT(frontend_ms, 0) << row;
  }
  EXPECT_EQ(static_cast<double>(rows), test::jsonNumber(summary, "frames"));
}

TEST(SlamApp, TruncatedRawlogKeepsTheFramesBeforeIt) {
  test::TempDir dir;
  writeSimulatedSequence(dir, 5.0);
  const std::string rawlog = dir.file("seq/seq.rawlog");
  const std::string slam = slamCommand("rpvio-single", dir.file("seq"));
  std::string out;
  ASSERT_EQ(test::runCommand(slam + dir.file("whole"), out), 0) << out;
  // Cut inside an entry three quarters of the way: the recording ends mid-write.
  std::filesystem::resize_file(rawlog, std::filesystem::file_size(rawlog) * 3 / 4 + 5);
  EXPECT_EQ(test::runCommand(slam + dir.file("cut"), out), 2) << out;
  EXPECT_NE(out.find("seq.rawlog:entry "), std::string::npos) << out;
  const std::string summary = test::readFile(dir.file("cut/summary.json"));
  EXPECT_NE(summary.find("\"complete\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"input_error\": \"" + rawlog + ":entry "), std::string::npos) << summary;
  EXPECT_NE(test::readFile(dir.file("whole/summary.json")).find("\"complete\": true"),
            std::string::npos);
  // The poses before the cut are the whole run's, to the byte (initialized at 2 s, 20 Hz).
  const std::string whole = test::readFile(dir.file("whole/trajectory.tum"));
  const std::string cut = test::readFile(dir.file("cut/trajectory.tum"));
  EXPECT_GT(readTum(dir.file("cut/trajectory.tum")).size(), 20u);
  EXPECT_LT(cut.size(), whole.size());
  EXPECT_EQ(whole.compare(0, cut.size(), cut), 0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("cut/stats.csv")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("cut/planes.yaml")));
}

// Pipelined (the front-end decodes and tracks the next images on a second thread): the same
// outputs, to the byte, on a whole rawlog, on one whose image at 4 s is not a PNG (the frames in
// flight after it are not published: the error stops the run there, as sequentially) and on one
// cut short (the frames in flight at the end are not lost).
TEST(SlamApp, PipelinedRunsGiveTheSameOutputs) {
  test::TempDir dir;
  writeSimulatedSequence(dir, 6.0, 2);
  std::string ini = test::readFile(std::string(RPVIO_SOURCE_DIR) + "/config/rpvio-multi.ini");
  const std::string section = "[FeatureTrackerModule]\n";
  ASSERT_NE(ini.find(section), std::string::npos);
  ini.insert(ini.find(section) + section.size(), "pipelined = true\n");
  std::ofstream(dir.file("pipelined.ini")) << ini;
  const std::string sequential = slamCommand("rpvio-multi", dir.file("seq"));
  std::string pipelined = sequential;
  const std::string mode_config = std::string(RPVIO_SOURCE_DIR) + "/config/rpvio-multi.ini";
  pipelined.replace(pipelined.find(mode_config), mode_config.size(), dir.file("pipelined.ini"));
  const std::string rawlog = dir.file("seq/seq.rawlog");
  const std::string image = dir.file("seq/seq_Images/CAM0_0000000004000000000.png");
  const std::string image_bytes = test::readFile(image);
  ASSERT_FALSE(image_bytes.empty());
  std::string out;
  for (const std::string run : {"whole", "bad_image", "cut"}) {
    if (run == "bad_image") test::writeText(image, "not a PNG");
    if (run == "cut") {
      test::writeText(image, image_bytes);
      std::filesystem::resize_file(rawlog, std::filesystem::file_size(rawlog) / 2);
    }
    const int code = run == "whole" ? 0 : 2;
    ASSERT_EQ(test::runCommand(sequential + dir.file(run + "_sequential"), out), code) << out;
    ASSERT_EQ(test::runCommand(pipelined + dir.file(run + "_pipelined"), out), code) << out;
    if (run == "bad_image") EXPECT_NE(out.find(image), std::string::npos) << out;
    EXPECT_NE(test::readFile(dir.file(run + "_pipelined/config_used.ini")).find("pipelined = true"),
              std::string::npos);
    for (const char* output : {"trajectory.tum", "planes.yaml", "planes.ply"})
      EXPECT_EQ(test::readFile(dir.file(run + "_sequential/") + output),
                test::readFile(dir.file(run + "_pipelined/") + output))
          << run << " " << output;
    const Trajectory poses = readTum(dir.file(run + "_pipelined/trajectory.tum"));
    EXPECT_GT(poses.size(), 10u) << run;
    if (run == "bad_image") EXPECT_LT(poses.back().t, 4.0);
  }
}

/// A copy of a rawlog without the observations of `label`, its masks stamped `mask_delay` s later
/// (the observations written in time order).
void copyWithout(const std::string& from, const std::string& to, const std::string& label,
                 const Calibration& calibration, double mask_delay = 0) {
  RawlogReader reader(from);
  std::multimap<double, std::function<void(RawlogWriter&)>> entries;  // by time, stable
  while (const auto obs = reader.next()) {
    if (obs->sensorLabel == label) continue;
    const double t = toSeconds(obs->timestamp);
    if (const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(obs.get())) {
      const cv::Mat pixels = loadGrayImage(*image, reader);
      if (obs->sensorLabel == labels::kCamera)
        entries.emplace(t, [t, pixels](RawlogWriter& w) { w.addImage(t, pixels); });
      else
        entries.emplace(t + mask_delay,
                        [t = t + mask_delay, pixels](RawlogWriter& w) { w.addMask(t, pixels); });
    } else if (const auto* imu = dynamic_cast<const mrpt::obs::CObservationIMU*>(obs.get())) {
      const ImuSample sample = toImuSample(*imu, reader);
      entries.emplace(t, [sample](RawlogWriter& w) { w.addImu(sample); });
    }
  }
  std::filesystem::create_directories(std::filesystem::path(to).parent_path());
  RawlogWriter writer(to, calibration);
  for (const auto& [t, write] : entries) write(writer);
  writer.close();
}

TEST(SlamApp, ARawlogWithoutWhatTheModeNeedsIsBadInputNamingIt) {
  test::TempDir dir;
  writeSimulatedSequence(dir, 1.0);
  const Calibration calibration = loadCalibration(dir.file("seq/calib.ini"));
  copyWithout(dir.file("seq/seq.rawlog"), dir.file("nomask/seq.rawlog"), labels::kPlaneMask,
              calibration);
  copyWithout(dir.file("seq/seq.rawlog"), dir.file("noimu/seq.rawlog"), labels::kImu, calibration);
  copyWithout(dir.file("seq/seq.rawlog"), dir.file("nocam/seq.rawlog"), labels::kCamera,
              calibration);
  const auto slam = [&](const char* mode, const std::string& rawlog, const std::string& out_dir) {
    return slamCommand(mode, dir.file("seq"), rawlog) + out_dir;
  };
  std::string out;
  // A masked mode on a rawlog without masks: one line naming the rawlog, the label and the mode
  // that runs; no output folder.
  EXPECT_EQ(
      test::runCommand(slam("rpvio-single", dir.file("nomask/seq.rawlog"), dir.file("o1")), out), 2)
      << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_NE(out.find("rpvio-slam: error: " + dir.file("nomask/seq.rawlog") + ": no PLANE_MASK"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("vins-mono"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o1")));
  // The unmasked mode runs on it.
  EXPECT_EQ(test::runCommand(slam("vins-mono", dir.file("nomask/seq.rawlog"), dir.file("o2")), out),
            0)
      << out;
  // Without IMU, no mode runs.
  EXPECT_EQ(test::runCommand(slam("vins-mono", dir.file("noimu/seq.rawlog"), dir.file("o3")), out),
            2)
      << out;
  EXPECT_NE(out.find(dir.file("noimu/seq.rawlog") + ": no IMU observation"), std::string::npos)
      << out;
  // Without images, no mode runs.
  EXPECT_EQ(test::runCommand(slam("vins-mono", dir.file("nocam/seq.rawlog"), dir.file("o4")), out),
            2)
      << out;
  EXPECT_NE(out.find(dir.file("nocam/seq.rawlog") + ": no CAM0 observation"), std::string::npos)
      << out;
}

TEST(SlamApp, ARawlogWhoseFramesNeverReachTheEstimatorIsBadInput) {
  // Every mask 1 ms after its image: no image is ever paired with its mask, so no frame is
  // processed; the run says so on one line and exits 2.
  test::TempDir dir;
  writeSimulatedSequence(dir, 1.0);
  copyWithout(dir.file("seq/seq.rawlog"), dir.file("late/seq.rawlog"), "",
              loadCalibration(dir.file("seq/calib.ini")), 0.001);
  std::string out;
  EXPECT_EQ(
      test::runCommand(
          slamCommand("rpvio-single", dir.file("seq"), dir.file("late/seq.rawlog")) + dir.file("o"),
          out),
      2)
      << out;
  EXPECT_NE(out.find("rpvio-slam: error: " + dir.file("late/seq.rawlog") +
                     ": no frame was processed (last status: "),
            std::string::npos)
      << out;
}

TEST(SlamApp, AnOutputThatCannotBeWrittenIsBadInputAndNothingIsHalfWritten) {
  // trajectory.tum's temporary name is taken by a folder: that output cannot be written (as on a
  // full disk). One line naming it, exit 2; the outputs written are whole, none is left temporary.
  test::TempDir dir;
  writeSimulatedSequence(dir, 3.0);
  std::filesystem::create_directories(dir.file("o/trajectory.tum.tmp"));
  std::string out;
  EXPECT_EQ(test::runCommand(slamCommand("rpvio-single", dir.file("seq")) + dir.file("o"), out), 2)
      << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_NE(out.find("rpvio-slam: error: " + dir.file("o") + ": writing the outputs failed: " +
                     dir.file("o/trajectory.tum") + ": cannot open for writing"),
            std::string::npos)
      << out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o/trajectory.tum")));
  const std::string summary = test::readFile(dir.file("o/summary.json"));
  EXPECT_EQ(summary.back(), '\n');  // written whole, before the failing writer
  EXPECT_NE(summary.find("\"status\": "), std::string::npos);
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("o"))) {
    if (entry.path().extension() == ".tmp") {
      EXPECT_TRUE(entry.is_directory()) << entry.path();  // only the folder put there
    }
  }
}

TEST(SlamApp, AnOutputPathThatCannotBeAFolderIsBadInput) {
  test::TempDir dir;
  writeSimulatedSequence(dir, 1.0);
  const std::string slam = slamCommand("rpvio-single", dir.file("seq"));
  std::string out;
  test::writeText(dir.file("a-file"), "keep me\n");
  EXPECT_EQ(test::runCommand(slam + dir.file("a-file"), out), 2) << out;
  EXPECT_EQ(out,
            "rpvio-slam: error: " + dir.file("a-file") + ": --out must be a folder, not a file\n");
  EXPECT_EQ(test::readFile(dir.file("a-file")), "keep me\n");
  EXPECT_EQ(test::runCommand(slam + dir.file("a-file/sub"), out), 2) << out;
  EXPECT_NE(out.find("cannot create the output folder"), std::string::npos) << out;
  // Not writable (root may write anywhere on disk: /proc refuses everyone).
  EXPECT_EQ(test::runCommand(slam + "/proc/rpvio-out", out), 2) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_NE(out.find("rpvio-slam: error: /proc/rpvio-out: "), std::string::npos) << out;
}

TEST(SlamApp, ARunThatNeverInitializesSaysWhy) {
  test::TempDir dir;
  writeSimulatedSequence(dir, 1.0);  // shorter than the 2 s initialization window
  std::string out;
  ASSERT_EQ(test::runCommand(slamCommand("rpvio-single", dir.file("seq")) + dir.file("o"), out), 0)
      << out;
  EXPECT_NE(out.find("no pose: never initialized (last status: "), std::string::npos) << out;
  const std::string summary = test::readFile(dir.file("o/summary.json"));
  EXPECT_EQ(test::jsonNumber(summary, "poses"), 0) << summary;
  const auto at = summary.find("\"status\": \"");
  ASSERT_NE(at, std::string::npos) << summary;
  EXPECT_NE(summary[at + 11], '"') << summary;  // not empty
}

TEST(SlamApp, BadArgumentsExitTwo) {
  std::string out;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config /nonexistent.ini --calib "
                                              "/nonexistent/calib.ini --rawlog y --out /tmp/z",
                             out),
            2)
      << out;
  EXPECT_NE(out.find("/nonexistent"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config x.ini", out), 2) << out;
  EXPECT_NE(out.find("missing required option"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config x.ini --calib c.ini --rawlog "
                                              "r.rawlog --out /tmp/z --threads 0",
                             out),
            2)
      << out;
  EXPECT_NE(out.find("--threads"), std::string::npos) << out;
}

}  // namespace
}  // namespace rpvio
