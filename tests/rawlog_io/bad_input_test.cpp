// Bad input gets an InputError naming the file and the position (issue 2 §3).
#include <gtest/gtest.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/ini_file.h"
#include "common/input_error.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/euroc_csv.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_summary.h"
#include "rawlog_io/rawlog_writer.h"
#include "rawlog_io/trajectory_io.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

Calibration tinyCalibration() {
  Calibration c;
  c.camera.width = 8;
  c.camera.height = 6;
  c.camera.fx = c.camera.fy = 10;
  c.camera.cx = 4;
  c.camera.cy = 3;
  return c;
}

/// Reads the whole rawlog, loading images and IMU samples like a consumer would.
void consume(const std::string& path) {
  RawlogReader reader(path);
  while (auto obs = reader.next()) {
    if (auto img = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs))
      loadGrayImage(*img, reader);
    if (auto imu = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obs))
      toImuSample(*imu, reader);
  }
}

/// Expects an InputError whose message names `file` and contains `position`.
template <typename Fn>
void expectInputError(Fn fn, const std::string& file, const std::string& position) {
  try {
    fn();
    FAIL() << "no InputError thrown";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(position), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
  }
}

std::string writeImuRawlog(const test::TempDir& dir, const std::vector<double>& stamps) {
  const std::string path = dir.file("imu.rawlog");
  mrpt::io::CFileGZOutputStream out(path);
  auto archive = mrpt::serialization::archiveFrom(out);
  for (double t : stamps) {
    mrpt::obs::CObservationIMU obs;
    obs.sensorLabel = labels::kImu;
    obs.timestamp = fromSeconds(t);
    for (auto f : {mrpt::obs::IMU_WX, mrpt::obs::IMU_WY, mrpt::obs::IMU_WZ, mrpt::obs::IMU_X_ACC,
                   mrpt::obs::IMU_Y_ACC, mrpt::obs::IMU_Z_ACC})
      obs.set(f, t);
    archive << obs;
  }
  return path;
}

/// The uncompressed bytes of a gz rawlog.
std::string decompress(const std::string& path) {
  std::string plain;
  mrpt::io::CFileGZInputStream in(path);
  char buf[4096];
  while (size_t n = in.Read(buf, sizeof(buf))) plain.append(buf, n);
  return plain;
}

TEST(BadInput, MissingRawlog) {
  expectInputError([] { RawlogReader("/nonexistent/seq.rawlog"); }, "/nonexistent/seq.rawlog",
                   "not found");
}

TEST(BadInput, MissingCalibration) {
  expectInputError([] { loadCalibration("/nonexistent/calib.ini"); }, "/nonexistent/calib.ini",
                   "not found");
}

TEST(BadInput, DirectoryOrDeviceGivenForAFile) {
  test::TempDir dir;
  expectInputError([&] { loadCalibration(dir.path().string()); }, dir.path().string(),
                   "calibration file expected, found a directory");
  expectInputError([] { RawlogReader("/dev/null"); }, "/dev/null",
                   "rawlog file expected, found a special file");
  expectInputError([] { IniFile("/dev/null"); }, "/dev/null",
                   "file expected, found a special file");
}

TEST(BadInput, CalibrationMalformedValue) {
  test::TempDir dir;
  Calibration c = tinyCalibration();
  saveCalibration(dir.file("calib.ini"), c);
  std::ifstream in(dir.file("calib.ini"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.replace(text.find("fx = 10"), 7, "fx = ten");
  test::writeText(dir.file("calib.ini"), text);
  expectInputError([&] { loadCalibration(dir.file("calib.ini")); }, dir.file("calib.ini"),
                   "line 5");
}

TEST(BadInput, CalibrationImageSizeNotAnInt) {
  // Found by tests/fuzz/calibration_fuzz.cpp: 8e9 was cast to int (undefined behaviour).
  test::TempDir dir;
  saveCalibration(dir.file("calib.ini"), tinyCalibration());
  const std::string text = test::readFile(dir.file("calib.ini"));
  for (const std::string width : {"8000000001", "0", "7.5"}) {
    std::string bad = text;
    bad.replace(bad.find("width = 8"), 9, "width = " + width);
    test::writeText(dir.file("calib.ini"), bad);
    expectInputError([&] { loadCalibration(dir.file("calib.ini")); }, dir.file("calib.ini"),
                     "line 3: 'width' must be a positive whole number of pixels");
  }
}

TEST(BadInput, MalformedCsvLine) {
  test::TempDir dir;
  test::writeText(dir.file("gt.csv"),
                  "#timestamp,px,py,pz,qw,qx,qy,qz\n1000,0,0,0,1,0,0,0\n2000,0,0,x,1,0,0,0\n");
  expectInputError([&] { readEurocCsv(dir.file("gt.csv")); }, dir.file("gt.csv"), "line 3");
}

TEST(BadInput, TrajectoryTimestampsBackwards) {
  test::TempDir dir;
  test::writeText(dir.file("t.tum"), "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  expectInputError([&] { readTum(dir.file("t.tum")); }, dir.file("t.tum"), "line 2");
}

TEST(BadInput, HugeQuaternionCoefficientsGiveAUnitQuaternion) {
  // Found by tests/fuzz/trajectory_fuzz.cpp: |q|^2 overflowed and normalizing gave q = 0.
  test::TempDir dir;
  test::writeText(dir.file("t.tum"), "1 0 0 0 0 11e200 0 0\n");
  test::writeText(dir.file("t.csv"), "1000,0,0,0,0,0,-3e307,4e307\n");
  const StampedPose tum = readTum(dir.file("t.tum")).at(0);
  EXPECT_TRUE(tum.q.isApprox(Eigen::Quaterniond(0, 0, 1, 0))) << tum.q.coeffs().transpose();
  const StampedPose csv = readEurocCsv(dir.file("t.csv")).at(0);
  EXPECT_TRUE(csv.q.isApprox(Eigen::Quaterniond(0, 0, -0.6, 0.8))) << csv.q.coeffs().transpose();
}

TEST(BadInput, NulByteInsideANumber) {
  // Found by tests/fuzz/trajectory_fuzz.cpp: strtod stops at a NUL byte, so "1<NUL>x" read as 1.
  using namespace std::string_literals;
  test::TempDir dir;
  std::ofstream(dir.file("t.tum"), std::ios::binary) << "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\0x\n"s;
  expectInputError([&] { readTum(dir.file("t.tum")); }, dir.file("t.tum"),
                   "line 2: not a finite number");
  saveCalibration(dir.file("calib.ini"), tinyCalibration());
  std::string ini = test::readFile(dir.file("calib.ini"));
  ini.replace(ini.find("fx = 10"), 7, "fx = 10\0x"s);
  std::ofstream(dir.file("calib.ini"), std::ios::binary) << ini;
  expectInputError([&] { loadCalibration(dir.file("calib.ini")); }, dir.file("calib.ini"),
                   "line 5: 'fx': not a finite number");
}

TEST(BadInput, ZeroQuaternionInEurocStateCsv) {
  // Seen reviewing the readers for tests/fuzz (euroc_csv_fuzz's unit-quaternion check fails on
  // it): q = 0 was accepted and left zero.
  test::TempDir dir;
  test::writeText(dir.file("gt.csv"),
                  "#t,p,p,p,qw,qx,qy,qz,v,v,v,bw,bw,bw,ba,ba,ba\n"
                  "1000,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n"
                  "2000,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n");
  expectInputError([&] { readEurocStateCsv(dir.file("gt.csv")); }, dir.file("gt.csv"),
                   "line 3: zero quaternion");
}

TEST(BadInput, KittiRotationNotOrthonormal) {
  // Seen reviewing the readers for tests/fuzz: only det(R) ~ 1 was checked, so a shear passed, and
  // so did huge entries (det = inf - inf = NaN; trajectory_fuzz's unit-quaternion check fails).
  for (const std::string row :
       {"1 5 0 0 0 1 0 0 0 0 1 0", "1e200 1e200 0 0 1e200 1e200 0 0 0 0 1 0"}) {
    test::TempDir dir;
    test::writeText(dir.file("k.txt"), "1 0 0 0 0 1 0 0 0 0 1 0\n" + row + "\n");
    expectInputError([&] { readKitti(dir.file("k.txt")); }, dir.file("k.txt"),
                     "line 2: rotation is not orthonormal");
  }
}

TEST(BadInput, RawlogTimestampsBackwards) {
  test::TempDir dir;
  const std::string path = writeImuRawlog(dir, {1.0, 2.0, 1.5});
  expectInputError([&] { consume(path); }, path, "entry 3");
}

TEST(BadInput, TruncatedRawlog) {
  test::TempDir dir;
  const std::string full = writeImuRawlog(dir, {1.0, 2.0, 3.0, 4.0});
  // Decompress-level truncation: keep a prefix of the uncompressed stream, recompressed.
  const std::string plain = decompress(full);
  const std::string cut = dir.file("cut.rawlog");
  {
    mrpt::io::CFileGZOutputStream out(cut);
    out.Write(plain.data(), plain.size() - 10);  // ends inside the last entry
  }
  expectInputError([&] { consume(cut); }, cut, "truncated");
}

TEST(BadInput, NotARawlog) {
  test::TempDir dir;
  test::writeText(dir.file("notes.rawlog"), "this is a text file, not a rawlog\n");
  expectInputError([&] { consume(dir.file("notes.rawlog")); }, dir.file("notes.rawlog"), "entry 1");
}

TEST(BadInput, ImuPresenceFlagNeitherZeroNorOne) {
  // Found by tests/fuzz/rawlog_fuzz.cpp: MRPT reads CObservationIMU::dataIsPresent as raw bytes;
  // a flag byte of 64 was loaded as a bool (undefined behaviour, reported by UBSan).
  test::TempDir dir;
  std::string plain = decompress(writeImuRawlog(dir, {1.0}));
  std::string flags(mrpt::obs::COUNT_IMU_DATA_FIELDS, '\0');
  for (auto f : {mrpt::obs::IMU_WX, mrpt::obs::IMU_WY, mrpt::obs::IMU_WZ, mrpt::obs::IMU_X_ACC,
                 mrpt::obs::IMU_Y_ACC, mrpt::obs::IMU_Z_ACC})
    flags[f] = 1;
  const size_t at = plain.find(flags);
  ASSERT_NE(at, std::string::npos);
  plain[at + mrpt::obs::IMU_WY] = 64;
  const std::string path = dir.file("flag.rawlog");  // uncompressed: MRPT reads both
  std::ofstream(path, std::ios::binary) << plain;
  expectInputError([&] { consume(path); }, path, "entry 1: IMU sample missing or not finite");
}

TEST(BadInput, ImageMissingFromDisk) {
  test::TempDir dir;
  const std::string path = dir.file("seq.rawlog");
  {
    RawlogWriter writer(path, tinyCalibration());
    writer.addImage(1.0, cv::Mat(6, 8, CV_8UC1, cv::Scalar(7)));
    writer.close();
  }
  for (const auto& f : std::filesystem::directory_iterator(dir.file("seq_Images")))
    std::filesystem::remove(f.path());
  expectInputError([&] { consume(path); }, path, "entry 1");
}

TEST(BadInput, NanOrInfInImu) {
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    test::TempDir dir;
    const std::string path = dir.file("imu.rawlog");
    {
      RawlogWriter writer(path, tinyCalibration());
      ImuSample s;
      s.t = 1.0;
      writer.addImu(s);
      s.t = 1.005;
      s.gyro.y() = bad;
      writer.addImu(s);
      writer.close();
    }
    expectInputError([&] { consume(path); }, path, "entry 2");
  }
}

TEST(BadInput, MaskSizeDiffersFromImage) {
  test::TempDir dir;
  const std::string path = dir.file("seq.rawlog");
  {
    RawlogWriter writer(path, tinyCalibration());
    writer.addImage(1.0, cv::Mat(6, 8, CV_8UC1, cv::Scalar(7)));
    writer.addMask(1.0, cv::Mat(3, 4, CV_8UC1, cv::Scalar(1)));
    writer.close();
  }
  expectInputError([&] { summarizeRawlog(path); }, path, "entry 2");
}

TEST(BadInput, NonObservationEntry) {
  test::TempDir dir;
  const std::string path = dir.file("pose.rawlog");
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto archive = mrpt::serialization::archiveFrom(out);
    archive << mrpt::poses::CPose3D(1, 2, 3, 0, 0, 0);
  }
  expectInputError([&] { consume(path); }, path, "entry 1: not an observation");
}

TEST(BadInput, EmptyTrajectory) {
  test::TempDir dir;
  test::writeText(dir.file("empty.tum"), "# only a comment\n");
  expectInputError([&] { readTrajectory(dir.file("empty.tum")); }, dir.file("empty.tum"),
                   "no data lines");
}

}  // namespace
}  // namespace rpvio
