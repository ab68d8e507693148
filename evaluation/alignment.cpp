#include "evaluation/alignment.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace rpvio::eval {
namespace {

Eigen::Matrix3Xd toMatrix(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Matrix3Xd m(3, points.size());
  for (size_t i = 0; i < points.size(); ++i) m.col(i) = points[i];
  return m;
}

/// Yaw θ and translation minimizing Σ |g_i − (Rz(θ) e_i + t)|²: with centred points the optimum is
/// θ = atan2(Σ (e_x g_y − e_y g_x), Σ (e_x g_x + e_y g_y)).
Similarity alignPositionYaw(const Eigen::Matrix3Xd& g, const Eigen::Matrix3Xd& e) {
  const Eigen::Vector3d g_mean = g.rowwise().mean(), e_mean = e.rowwise().mean();
  double sin_sum = 0, cos_sum = 0;
  for (Eigen::Index i = 0; i < g.cols(); ++i) {
    const Eigen::Vector3d gc = g.col(i) - g_mean, ec = e.col(i) - e_mean;
    sin_sum += ec.x() * gc.y() - ec.y() * gc.x();
    cos_sum += ec.x() * gc.x() + ec.y() * gc.y();
  }
  Similarity sim;
  sim.R =
      Eigen::AngleAxisd(std::atan2(sin_sum, cos_sum), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  sim.t = g_mean - sim.R * e_mean;
  return sim;
}

}  // namespace

AlignMode parseAlignMode(const std::string& text) {
  if (text == "se3") return AlignMode::SE3;
  if (text == "sim3") return AlignMode::Sim3;
  if (text == "posyaw") return AlignMode::PosYaw;
  if (text == "none") return AlignMode::None;
  throw std::invalid_argument("unknown alignment '" + text + "' (se3, sim3, posyaw, none)");
}

std::string toString(AlignMode mode) {
  switch (mode) {
    case AlignMode::SE3:
      return "se3";
    case AlignMode::Sim3:
      return "sim3";
    case AlignMode::PosYaw:
      return "posyaw";
    default:
      return "none";
  }
}

Similarity align(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                 AlignMode mode) {
  if (gt.size() != est.size()) throw std::invalid_argument("align: point counts differ");
  Similarity sim;
  if (mode == AlignMode::None || gt.empty()) return sim;
  const Eigen::Matrix3Xd g = toMatrix(gt), e = toMatrix(est);
  if (mode == AlignMode::PosYaw) return alignPositionYaw(g, e);
  // Umeyama (1991), Eq. 40-42: the similarity mapping e onto g.
  const Eigen::Matrix4d T = Eigen::umeyama(e, g, mode == AlignMode::Sim3);
  sim.s = T.topLeftCorner<3, 3>().col(0).norm();
  sim.R = T.topLeftCorner<3, 3>() / sim.s;
  sim.t = T.topRightCorner<3, 1>();
  return sim;
}

}  // namespace rpvio::eval
