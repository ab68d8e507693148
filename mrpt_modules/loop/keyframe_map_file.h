#pragma once
// A saved map of keyframes (rpvio-slam --save-map DIR, read back with --map DIR): each keyframe's
// time, body pose in the map's frame and appearance (normalized points, ORB descriptors; the
// points' world positions are not kept: a map keyframe is only ever the old side of a revisit),
// with the calibration the points were undistorted with. Binary, little-endian, a fixed layout
// (docs/data-formats.md): "RPVIOMAP", version, calibration, keyframes, then a CRC-32 of all bytes
// before it. Doubles are stored as they are in memory: a map read and written again is the same
// file.
#include <string>
#include <vector>

#include "common/sensor_types.h"
#include "mrpt_modules/loop/keyframe_appearance.h"

namespace rpvio {

struct KeyframeMap {
  CameraIntrinsics camera;
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  std::vector<StoredKeyframe> keyframes;
};

/// DIR/keyframes.rpvmap
std::string keyframeMapPath(const std::string& dir);
/// DIR/planes.yaml: the map's planes, in its frame (plane_map_exporters.h's format)
std::string mapPlanesPath(const std::string& dir);

/// Writes the map whole or not at all (std::runtime_error naming the path when it cannot).
void writeKeyframeMap(const std::string& path, const KeyframeMap& map);

/// Reads a map; InputError(path, "byte N", why) for a missing, truncated or damaged file (the CRC
/// is checked before anything is parsed; every count is checked against the bytes left).
KeyframeMap readKeyframeMap(const std::string& path);

/// Why keyframes described with `map`'s calibration cannot be matched with `calibration`'s: the
/// image size, distortion model, intrinsics and camera-body pose must agree (within 1e-6
/// relative, the precision of a calibration file); "" when they do.
std::string calibrationMismatch(const KeyframeMap& map, const Calibration& calibration);

}  // namespace rpvio
