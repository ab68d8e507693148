#pragma once
// Streams a rawlog entry by entry (images lazy-loaded, never the whole dataset in memory), from
// any working directory (works around MRPT 2.5.8's images-directory bug by computing
// `<dir>/<stem>_Images` and calling mrpt::io::setLazyLoadPathBase()).
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "common/sensor_types.h"

namespace rpvio {

class RawlogReader {
 public:
  /// Throws InputError when the file is missing or not a rawlog.
  explicit RawlogReader(const std::string& path);
  ~RawlogReader();

  /// Next observation in file order, nullptr at the end. Throws InputError(file, "entry N") on a
  /// truncated file, a non-observation entry or a timestamp earlier than the previous one.
  mrpt::obs::CObservation::Ptr next();
  size_t entriesRead() const;
  const std::string& path() const;
  const std::string& imagesDir() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

double toSeconds(const mrpt::Clock::time_point& t);
mrpt::Clock::time_point fromSeconds(double t);

/// Where the pixels of a CAM0/PLANE_MASK observation are: the file, and the rawlog position that
/// names it (for errors). Found while the reader is at that entry; decodable later, on any thread.
struct ImageFileRef {
  std::string file;
  std::string rawlog;
  std::string entry;  // "entry N"
};
/// Throws InputError(rawlog, "entry N") when the image is not stored in a file.
ImageFileRef locateImage(const mrpt::obs::CObservationImage& obs, const RawlogReader& reader);
/// The 8-bit image of the file. Throws InputError(rawlog, "entry N") naming a missing or
/// undecodable file.
cv::Mat decodeGrayImage(const ImageFileRef& ref);
/// decodeGrayImage(locateImage(obs, reader)).
cv::Mat loadGrayImage(const mrpt::obs::CObservationImage& obs, const RawlogReader& reader);
/// Throws InputError(rawlog, "entry N") when a value is NaN/inf or missing.
ImuSample toImuSample(const mrpt::obs::CObservationIMU& obs, const RawlogReader& reader);
StampedPose toStampedPose(const mrpt::obs::CObservationRobotPose& obs);

}  // namespace rpvio
