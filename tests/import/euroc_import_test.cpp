// EuRoC import of the real V1_01 subset, its reading by rpvio and by MRPT's rawlog-edit, and the
// import's handling of bad input (exit code 2, one line naming the file, no output left behind).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "common/input_error.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/euroc_import.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_summary.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

const std::string kMav0 = test::dataDir() + "/euroc_v101_static/mav0";
const std::string kGt = test::dataDir() + "/euroc_v101_static/groundtruth_v101_full.tum";

size_t countDataLines(const std::string& path) {
  std::ifstream in(path);
  size_t n = 0;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') ++n;
  return n;
}

TEST(EurocImport, RealV101WithGroundTruth) {
  ASSERT_TRUE(fs::is_directory(kMav0)) << "real data missing: " << kMav0;
  test::TempDir dir;
  EurocImportOptions opt;
  opt.mav0_dir = kMav0;
  opt.groundtruth_file = kGt;
  opt.output_rawlog = dir.file("v101.rawlog");
  const EurocImportCounts counts = importEuroc(opt);
  EXPECT_EQ(counts.images, 95u);
  EXPECT_EQ(counts.imu, countDataLines(kMav0 + "/imu0/data.csv"));
  EXPECT_EQ(counts.groundtruth, countDataLines(kGt));

  const RawlogSummary summary = summarizeRawlog(opt.output_rawlog);
  EXPECT_EQ(summary.observations_per_label.at("CAM0"), 95u);
  EXPECT_EQ(summary.observations_per_label.at("IMU"), counts.imu);
  EXPECT_EQ(summary.observations_per_label.at("GROUND_TRUTH"), counts.groundtruth);
  const double imu_rate = (counts.imu - 1) / (summary.last_t - summary.first_t);
  EXPECT_NEAR(imu_rate, 200.0, 1.0);

  const Calibration calib = loadCalibration(dir.file("calib.ini"));
  EXPECT_EQ(calib.camera.width, 752);
  EXPECT_DOUBLE_EQ(calib.camera.fx, 458.654);
  EXPECT_EQ(calib.camera.model, DistortionModel::RadTan);
  // cam0 in the EuRoC body (= IMU) frame: the optical axis is nearly the IMU z axis, the camera
  // sits 6.5 cm along IMU -y (sensor.yaml T_BS of cam0, IMU T_BS = identity).
  EXPECT_GT(calib.T_BC.linear().col(2).z(), 0.999);
  EXPECT_NEAR(calib.T_BC.translation().y(), -0.064676986768, 1e-12);

  if (!fs::exists("/usr/bin/rawlog-edit")) {
    GTEST_SKIP() << "rawlog-edit (mrpt-apps) not installed";
  }
  std::string out;
  const int rc = test::runCommand(
      "cd " + dir.path().string() + " && /usr/bin/rawlog-edit --info -i v101.rawlog", out);
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("Observations format               : Yes"), std::string::npos) << out;
  EXPECT_NE(out.find("Found external storage directory: v101_Images"), std::string::npos) << out;
  EXPECT_NE(out.find("All sensor labels                 : CAM0, GROUND_TRUTH, IMU"),
            std::string::npos)
      << out;
}

/// A small fake mav0 folder (3 tiny images, a few IMU lines) built from the real sensor YAMLs.
struct FakeMav0 {
  test::TempDir dir{"fake_mav0"};
  std::string mav0 = dir.file("mav0");
  FakeMav0() {
    fs::create_directories(mav0 + "/cam0/data");
    fs::create_directories(mav0 + "/imu0");
    fs::copy_file(kMav0 + "/cam0/sensor.yaml", mav0 + "/cam0/sensor.yaml");
    fs::copy_file(kMav0 + "/imu0/sensor.yaml", mav0 + "/imu0/sensor.yaml");
    std::string cams = "#timestamp [ns],filename\n", imu = "#timestamp [ns],w,w,w,a,a,a\n";
    for (int i = 0; i < 3; ++i) {
      const std::string stamp = std::to_string(1000000000LL + i * 50000000LL);
      cams += stamp + "," + stamp + ".png\n";
      cv::imwrite(mav0 + "/cam0/data/" + stamp + ".png", cv::Mat(48, 64, CV_8UC1, cv::Scalar(i)));
      imu += stamp + ",0,0,0,0,0,9.81\n";
    }
    test::writeText(mav0 + "/cam0/data.csv", cams);
    test::writeText(mav0 + "/imu0/data.csv", imu);
  }
  std::string out() const { return dir.file("out/seq.rawlog"); }
};

TEST(EurocImport, EurocCsvGroundTruthAndMasks) {
  FakeMav0 fake;
  // EuRoC CSV ground truth: t [ns], p, q as w x y z (TUM files order it x y z w).
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  std::ostringstream gt;
  gt << "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
        "q_RS_z []\n";
  for (int i = 0; i < 4; ++i)
    gt << 1000000000LL + i * 40000000LL << "," << i << ",2,3," << q.w() << "," << q.x() << ","
       << q.y() << "," << q.z() << "\n";
  test::writeText(fake.dir.file("gt.csv"), gt.str());
  const std::string masks = fake.dir.file("masks");
  fs::create_directories(masks);
  for (const auto& f : fs::directory_iterator(fake.mav0 + "/cam0/data"))
    cv::imwrite(masks + "/" + f.path().filename().string(), cv::Mat(48, 64, CV_8UC1, 3));

  EurocImportOptions opt;
  opt.mav0_dir = fake.mav0;
  opt.groundtruth_file = fake.dir.file("gt.csv");
  opt.masks_dir = masks;
  opt.output_rawlog = fake.dir.file("seq.rawlog");
  const EurocImportCounts counts = importEuroc(opt);
  EXPECT_EQ(counts.images, 3u);
  EXPECT_EQ(counts.masks, 3u);
  EXPECT_EQ(counts.imu, 3u);
  EXPECT_EQ(counts.groundtruth, 4u);

  RawlogReader reader(opt.output_rawlog);
  std::vector<std::string> labels;
  size_t n_gt = 0;
  while (auto obs = reader.next()) {
    labels.push_back(obs->sensorLabel);
    if (auto pose = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(obs)) {
      const StampedPose p = toStampedPose(*pose);
      EXPECT_NEAR(p.t, 1.0 + n_gt * 0.04, 1e-6);
      EXPECT_NEAR(p.p.x(), static_cast<double>(n_gt), 1e-9);
      EXPECT_LT(p.q.angularDistance(q), 1e-6);
      ++n_gt;
    } else if (auto img = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs)) {
      const cv::Mat m = loadGrayImage(*img, reader);
      if (obs->sensorLabel == "PLANE_MASK") {
        EXPECT_EQ(m.at<uint8_t>(0, 0), 3);
      }
    }
  }
  EXPECT_EQ(n_gt, 4u);
  // Time-merged, IMU first at equal stamps, each mask right after its image.
  const std::vector<std::string> expected = {
      "IMU",        "GROUND_TRUTH", "CAM0", "PLANE_MASK", "GROUND_TRUTH", "IMU",         "CAM0",
      "PLANE_MASK", "GROUND_TRUTH", "IMU",  "CAM0",       "PLANE_MASK",   "GROUND_TRUTH"};
  EXPECT_EQ(labels, expected);
}

/// Runs the import app; expects exit 2, a one-line error naming `named`, no output rawlog.
void expectImportFails(const std::string& args, const std::string& named, const std::string& out) {
  fs::create_directories(fs::path(out).parent_path());
  std::string output;
  const int rc = test::runCommand(test::binDir() + "/rpvio-import " + args, output);
  EXPECT_EQ(rc, 2) << output;
  EXPECT_NE(output.find(named), std::string::npos) << output;
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".tmp"));
}

TEST(EurocImportBadInput, FakeFolderImportsCleanly) {
  FakeMav0 fake;
  std::string output;
  fs::create_directories(fs::path(fake.out()).parent_path());
  ASSERT_EQ(test::runCommand(
                test::binDir() + "/rpvio-import euroc --mav0 " + fake.mav0 + " --out " + fake.out(),
                output),
            0)
      << output;
  EXPECT_TRUE(fs::exists(fake.out()));
}

TEST(EurocImportBadInput, MissingFolder) {
  FakeMav0 fake;
  expectImportFails("euroc --mav0 /nonexistent/mav0 --out " + fake.out(), "/nonexistent/mav0",
                    fake.out());
}

TEST(EurocImportBadInput, MalformedImuLine) {
  FakeMav0 fake;
  test::writeText(fake.mav0 + "/imu0/data.csv", "#h\n1000000000,0,0,0,0,0,9.81\n1005000000,0,0\n");
  expectImportFails("euroc --mav0 " + fake.mav0 + " --out " + fake.out(), "data.csv:line 3",
                    fake.out());
}

TEST(EurocImportBadInput, NanInImu) {
  FakeMav0 fake;
  test::writeText(fake.mav0 + "/imu0/data.csv", "#h\n1000000000,0,nan,0,0,0,9.81\n");
  expectImportFails("euroc --mav0 " + fake.mav0 + " --out " + fake.out(), "data.csv:line 2",
                    fake.out());
}

TEST(EurocImportBadInput, ImuTimestampsBackwards) {
  FakeMav0 fake;
  test::writeText(fake.mav0 + "/imu0/data.csv",
                  "#h\n1000000000,0,0,0,0,0,9.81\n900000000,0,0,0,0,0,9.81\n");
  expectImportFails("euroc --mav0 " + fake.mav0 + " --out " + fake.out(), "data.csv:line 3",
                    fake.out());
}

TEST(EurocImportBadInput, ImageMissingFromDisk) {
  FakeMav0 fake;
  fs::remove(fake.mav0 + "/cam0/data/1050000000.png");
  expectImportFails("euroc --mav0 " + fake.mav0 + " --out " + fake.out(), "1050000000.png",
                    fake.out());
}

TEST(EurocImportBadInput, MaskSizeMismatch) {
  FakeMav0 fake;
  const std::string masks = fake.dir.file("masks");
  fs::create_directories(masks);
  for (const auto& f : fs::directory_iterator(fake.mav0 + "/cam0/data"))
    cv::imwrite(masks + "/" + f.path().filename().string(), cv::Mat(10, 10, CV_8UC1, 1));
  expectImportFails("euroc --mav0 " + fake.mav0 + " --masks " + masks + " --out " + fake.out(),
                    "differs from its image", fake.out());
}

TEST(EurocImportBadInput, MalformedGroundTruth) {
  FakeMav0 fake;
  test::writeText(fake.dir.file("gt.tum"), "1.0 0 0 0 0 0 0 1\n1.1 0 0 0 0 0 1\n");
  expectImportFails(
      "euroc --mav0 " + fake.mav0 + " --gt " + fake.dir.file("gt.tum") + " --out " + fake.out(),
      "gt.tum:line 2", fake.out());
}

TEST(EurocImportBadInput, MissingSensorYaml) {
  FakeMav0 fake;
  fs::remove(fake.mav0 + "/cam0/sensor.yaml");
  expectImportFails("euroc --mav0 " + fake.mav0 + " --out " + fake.out(), "cam0/sensor.yaml",
                    fake.out());
}

TEST(EurocImportBadInput, MissingOutputFolder) {
  FakeMav0 fake;
  const std::string out = fake.dir.file("absent/seq.rawlog");
  std::string output;
  EXPECT_EQ(
      test::runCommand(test::binDir() + "/rpvio-import euroc --mav0 " + fake.mav0 + " --out " + out,
                       output),
      2);
  EXPECT_NE(output.find(out + ": output folder not found"), std::string::npos) << output;
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
}

TEST(EurocImportBadInput, MissingRequiredOption) {
  FakeMav0 fake;
  std::string output;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-import euroc --mav0 " + fake.mav0, output),
            2);
  EXPECT_NE(output.find("missing required option --out"), std::string::npos) << output;
  EXPECT_NE(output.find("usage: rpvio-import euroc"), std::string::npos) << output;
}

TEST(EurocImportBadInput, UnknownOption) {
  FakeMav0 fake;
  std::string output;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-import euroc --bogus 1", output), 2);
  EXPECT_NE(output.find("unknown option --bogus"), std::string::npos) << output;
}

}  // namespace
}  // namespace rpvio
