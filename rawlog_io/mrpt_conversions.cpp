#include "rawlog_io/mrpt_conversions.h"

#include <mrpt/math/CQuaternion.h>

namespace rpvio {

mrpt::poses::CPose3D toCPose3D(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d& t = pose.translation();
  return mrpt::poses::CPose3D(mrpt::math::CQuaternionDouble(q.w(), q.x(), q.y(), q.z()), t.x(),
                              t.y(), t.z());
}

Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  mrpt::math::CQuaternionDouble q;
  pose.getAsQuaternion(q);
  out.linear() = Eigen::Quaterniond(q.r(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.x(), pose.y(), pose.z());
  return out;
}

mrpt::img::TCamera toTCamera(const CameraIntrinsics& camera) {
  mrpt::img::TCamera cam;
  cam.ncols = static_cast<uint32_t>(camera.width);
  cam.nrows = static_cast<uint32_t>(camera.height);
  cam.setIntrinsicParamsFromValues(camera.fx, camera.fy, camera.cx, camera.cy);
  const auto& d = camera.distortion;
  cam.dist.fill(0);
  switch (camera.model) {
    case DistortionModel::RadTan:  // [k1 k2 p1 p2 k3 ...]
      cam.distortion = mrpt::img::DistortionModel::plumb_bob;
      cam.dist = {d[0], d[1], d[2], d[3], 0, 0, 0, 0};
      break;
    case DistortionModel::Equidistant:  // Kannala-Brandt: [k1 k2 * * k3 k4]
      cam.distortion = mrpt::img::DistortionModel::kannala_brandt;
      cam.dist = {d[0], d[1], 0, 0, d[2], d[3], 0, 0};
      break;
    default:
      cam.distortion = mrpt::img::DistortionModel::none;
  }
  return cam;
}

}  // namespace rpvio
