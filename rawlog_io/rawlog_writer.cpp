#include "rawlog_io/rawlog_writer.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "rawlog_io/mrpt_conversions.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

namespace fs = std::filesystem;

namespace rpvio {

struct RawlogWriter::Impl {
  std::string path, images_dir, images_tmp_dir;
  mrpt::img::TCamera camera;
  mrpt::poses::CPose3D camera_pose;
  mrpt::io::CFileGZOutputStream stream;
  double last_t = -INFINITY;
  bool closed = false;

  void checkTime(double t) {
    if (!std::isfinite(t)) throw std::invalid_argument(path + ": non-finite timestamp");
    if (t < last_t)
      throw std::invalid_argument(path + ": observation at t=" + std::to_string(t) +
                                  " s added after t=" + std::to_string(last_t) + " s");
    last_t = t;
  }

  void write(const mrpt::obs::CObservation& obs) {
    auto archive = mrpt::serialization::archiveFrom(stream);
    archive << obs;
  }

  /// `png_strategy`: zlib's, chosen per content (see addImage and addMask).
  void addImageObservation(const char* label, double t, const cv::Mat& img8, int png_strategy) {
    if (img8.type() != CV_8UC1) throw std::invalid_argument(path + ": images must be CV_8UC1");
    checkTime(t);
    char name[96];
    std::snprintf(name, sizeof(name), "%s_%019lld.png", label,
                  static_cast<long long>(std::llround(t * 1e9)));
    const std::string file = (fs::path(images_tmp_dir) / name).string();
    // PNG is lossless, as masks need. Without a compression level OpenCV writes zlib's fastest
    // level and the SUB filter on every row, the cheapest to reverse: PngGrayDecoder reads these
    // frames ~2x faster than libpng's adaptive (mostly Paeth) rows, for 3% more bytes.
    if (!cv::imwrite(file, img8, {cv::IMWRITE_PNG_STRATEGY, png_strategy}))
      throw std::runtime_error(file + ": cannot write image");
    mrpt::obs::CObservationImage obs;
    obs.sensorLabel = label;
    obs.timestamp = fromSeconds(t);
    obs.cameraParams = camera;
    obs.cameraPose = camera_pose;
    obs.image.setExternalStorage(name);
    write(obs);
  }
};

RawlogWriter::RawlogWriter(const std::string& path, const Calibration& calib)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  const fs::path p(path);
  const fs::path dir = existingOutputFolder(path);
  if (fs::is_directory(p)) throw InputError(path, "", "is a folder, not a rawlog file name");
  impl_->images_dir = (dir / (p.stem().string() + "_Images")).string();
  impl_->images_tmp_dir = impl_->images_dir + ".tmp";
  fs::remove_all(impl_->images_tmp_dir);
  fs::create_directories(impl_->images_tmp_dir);
  impl_->camera = toTCamera(calib.camera);
  impl_->camera_pose = toCPose3D(calib.T_BC);
  if (!impl_->stream.open(temporaryPathFor(path))) {
    std::error_code ec;
    fs::remove_all(impl_->images_tmp_dir, ec);
    throw InputError(path, "", "cannot open for writing");
  }
}

RawlogWriter::~RawlogWriter() {
  if (impl_->closed) return;
  impl_->stream.close();
  std::error_code ec;
  fs::remove(temporaryPathFor(impl_->path), ec);
  fs::remove_all(impl_->images_tmp_dir, ec);
}

void RawlogWriter::addImage(double t, const cv::Mat& gray8) {
  // Camera noise leaves LZ77 little to match: Huffman coding alone (186 KB per 640x480 frame)
  // skips the match search.
  impl_->addImageObservation(labels::kCamera, t, gray8, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY);
}

void RawlogWriter::addMask(double t, const cv::Mat& labels8) {
  // Labels are long runs: the default strategy makes them 5 KB (Huffman only: 39 KB).
  impl_->addImageObservation(labels::kPlaneMask, t, labels8, cv::IMWRITE_PNG_STRATEGY_DEFAULT);
}

void RawlogWriter::addImu(const ImuSample& s) {
  impl_->checkTime(s.t);
  mrpt::obs::CObservationIMU obs;
  obs.sensorLabel = labels::kImu;
  obs.timestamp = fromSeconds(s.t);
  obs.set(mrpt::obs::IMU_WX, s.gyro.x());
  obs.set(mrpt::obs::IMU_WY, s.gyro.y());
  obs.set(mrpt::obs::IMU_WZ, s.gyro.z());
  obs.set(mrpt::obs::IMU_X_ACC, s.accel.x());
  obs.set(mrpt::obs::IMU_Y_ACC, s.accel.y());
  obs.set(mrpt::obs::IMU_Z_ACC, s.accel.z());
  impl_->write(obs);
}

void RawlogWriter::addGroundTruth(const StampedPose& pose) {
  impl_->checkTime(pose.t);
  mrpt::obs::CObservationRobotPose obs;
  obs.sensorLabel = labels::kGroundTruth;
  obs.timestamp = fromSeconds(pose.t);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = pose.q.normalized().toRotationMatrix();
  T.translation() = pose.p;
  obs.pose.mean = toCPose3D(T);
  obs.pose.cov.setZero();
  impl_->write(obs);
}

void RawlogWriter::close() {
  if (impl_->closed) return;
  impl_->stream.close();
  fs::remove_all(impl_->images_dir);
  fs::rename(impl_->images_tmp_dir, impl_->images_dir);
  commitTemporary(impl_->path);
  impl_->closed = true;
}

std::string RawlogWriter::imagesDir() const { return impl_->images_dir; }

}  // namespace rpvio
