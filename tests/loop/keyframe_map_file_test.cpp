// The saved keyframe map: written, read and written again byte for byte; every damaged byte and
// every truncation refused with one line naming the byte; a map of another camera refused.
#include <gtest/gtest.h>
#include <libdeflate.h>

#include <cstring>
#include <random>

#include "common/input_error.h"
#include "mrpt_modules/loop/keyframe_map_file.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

KeyframeMap smallMap(int keyframes, int points) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  KeyframeMap map;
  map.camera = {
      640, 480, 460.1, 459.7, 320.3, 240.8, DistortionModel::RadTan, {-0.28, 0.07, 1e-4, -2e-5}};
  map.T_BC.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  map.T_BC.translation() = Eigen::Vector3d(0.05, -0.01, 0.002);
  for (int k = 0; k < keyframes; ++k) {
    StoredKeyframe keyframe;
    keyframe.t = 1403715273.262142976 + 0.1 * k;
    keyframe.body.linear() =
        Eigen::AngleAxisd(u(rng), Eigen::Vector3d(u(rng), u(rng), 1).normalized()).matrix();
    keyframe.body.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10;
    keyframe.appearance.descriptors.create(points, 32, CV_8U);
    cv::randu(keyframe.appearance.descriptors, 0, 256);
    for (int i = 0; i < points; ++i)
      keyframe.appearance.points.push_back({{u(rng), u(rng)}, {}, 0});
    map.keyframes.push_back(keyframe);
  }
  return map;
}

/// The InputError's message reading `bytes` as a map; "" when it reads.
std::string readError(const test::TempDir& dir, const std::string& bytes) {
  const std::string path = dir.file("damaged.rpvmap");
  test::writeText(path, bytes);
  try {
    readKeyframeMap(path);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

/// `bytes` with its CRC recomputed: a damaged file the CRC does not catch.
std::string withCrc(std::string bytes) {
  const uint32_t crc = libdeflate_crc32(0, bytes.data(), bytes.size() - 4);
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);
  return bytes;
}

TEST(KeyframeMapFile, ReadAndWrittenAgainIsTheSameFile) {
  test::TempDir dir;
  const KeyframeMap map = smallMap(5, 40);
  writeKeyframeMap(dir.file("a.rpvmap"), map);
  const KeyframeMap read = readKeyframeMap(dir.file("a.rpvmap"));
  ASSERT_EQ(read.keyframes.size(), 5u);
  EXPECT_EQ(read.camera.fx, map.camera.fx);
  EXPECT_EQ(read.camera.model, DistortionModel::RadTan);
  EXPECT_TRUE(read.T_BC.isApprox(map.T_BC, 0));
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(read.keyframes[k].t, map.keyframes[k].t);
    EXPECT_TRUE(read.keyframes[k].body.isApprox(map.keyframes[k].body, 0));
    ASSERT_EQ(read.keyframes[k].appearance.points.size(), 40u);
    EXPECT_EQ(read.keyframes[k].appearance.points[7].normalized,
              map.keyframes[k].appearance.points[7].normalized);
    EXPECT_EQ(cv::norm(read.keyframes[k].appearance.descriptors,
                       map.keyframes[k].appearance.descriptors, cv::NORM_HAMMING),
              0);
  }
  writeKeyframeMap(dir.file("b.rpvmap"), read);
  EXPECT_EQ(test::readFile(dir.file("a.rpvmap")), test::readFile(dir.file("b.rpvmap")));
  Calibration calibration;
  calibration.camera = map.camera;
  calibration.T_BC = map.T_BC;
  EXPECT_EQ(calibrationMismatch(read, calibration), "");
}

TEST(KeyframeMapFile, EveryDamagedByteAndEveryTruncationIsRefusedWithItsPosition) {
  test::TempDir dir;
  writeKeyframeMap(dir.file("a.rpvmap"), smallMap(2, 3));
  const std::string good = test::readFile(dir.file("a.rpvmap"));
  ASSERT_EQ(readError(dir, good), "");
  for (size_t at = 0; at < good.size(); ++at) {
    std::string damaged = good;
    damaged[at] ^= 0x10;
    const std::string error = readError(dir, damaged);
    EXPECT_NE(error.find(":byte "), std::string::npos) << "byte " << at << ": '" << error << "'";
    EXPECT_EQ(error.find('\n'), std::string::npos);
  }
  for (size_t size = 0; size < good.size(); ++size)
    EXPECT_NE(readError(dir, good.substr(0, size)), "") << size << " bytes";
  EXPECT_NE(readError(dir, good + "x"), "");
}

TEST(KeyframeMapFile, DamageTheCrcDoesNotCatchIsRefusedWithoutCrashing) {
  // Counts, numbers and poses changed and the CRC made to match: every field is checked itself
  // (a count past the end, a NaN, a pose that is not a rotation), never allocated blindly.
  test::TempDir dir;
  writeKeyframeMap(dir.file("a.rpvmap"), smallMap(2, 3));
  const std::string good = test::readFile(dir.file("a.rpvmap"));
  const size_t count_at = 8 + 4 + 3 * 4 + 8 * 8 + 12 * 8;  // the keyframe count
  std::string huge = good;
  huge[count_at + 6] = 0x7f;
  EXPECT_NE(readError(dir, withCrc(huge)).find("cannot fit"), std::string::npos);
  std::string nan = good;
  const double not_a_number = std::nan("");
  std::memcpy(nan.data() + count_at + 8, &not_a_number, 8);  // the first keyframe's time
  EXPECT_NE(readError(dir, withCrc(nan)).find("not a finite number"), std::string::npos);
  std::string skewed = good;
  const double two = 2;
  std::memcpy(skewed.data() + count_at + 16, &two, 8);  // its pose's R(0,0)
  EXPECT_NE(readError(dir, withCrc(skewed)).find("not a rotation"), std::string::npos);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3000; ++trial) {
    std::string damaged = good;
    for (int b = 0; b < 3; ++b) damaged[rng() % (good.size() - 4)] = static_cast<char>(rng());
    readError(dir, withCrc(damaged));  // reads or throws InputError; anything else fails the test
  }
}

TEST(KeyframeMapFile, AMapOfAnotherCameraIsNamedAsSuch) {
  const KeyframeMap map = smallMap(1, 1);
  Calibration same;
  same.camera = map.camera;
  same.T_BC = map.T_BC;
  EXPECT_EQ(calibrationMismatch(map, same), "");
  same.camera.fx *= 1 + 1e-8;  // the rounding of a calibration file
  EXPECT_EQ(calibrationMismatch(map, same), "");
  Calibration other = same;
  other.camera.width = 752;
  EXPECT_NE(calibrationMismatch(map, other).find("640x480"), std::string::npos);
  other = same;
  other.camera.cx += 1;
  EXPECT_NE(calibrationMismatch(map, other).find("intrinsics"), std::string::npos);
  other = same;
  other.T_BC.translation().x() += 0.01;
  EXPECT_NE(calibrationMismatch(map, other).find("T_BC"), std::string::npos);
}

}  // namespace
}  // namespace rpvio
