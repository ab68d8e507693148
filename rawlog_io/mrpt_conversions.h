#pragma once
// Conversions between rpvio's Eigen/Calibration types and MRPT's.
#include <mrpt/img/TCamera.h>
#include <mrpt/poses/CPose3D.h>
#include <Eigen/Geometry>

#include "common/sensor_types.h"

namespace rpvio {

mrpt::poses::CPose3D toCPose3D(const Eigen::Isometry3d& pose);
Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& pose);
mrpt::img::TCamera toTCamera(const CameraIntrinsics& camera);

}  // namespace rpvio
