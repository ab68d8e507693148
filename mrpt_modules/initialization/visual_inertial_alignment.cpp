#include "mrpt_modules/initialization/visual_inertial_alignment.h"

#include <Eigen/Dense>
#include <cstdlib>
#include <optional>

namespace rpvio {
namespace {

using P = ImuPreintegration;
const double kAccelBiasPriorWeight = 0.1;  // per m/s², against rows in m and m/s
const double kAccelBiasRange = 0.1;        // m/s², plausible accelerometer bias left unmodelled

Eigen::Matrix3d bodyRotation(const UpToScaleFrame& f, const Eigen::Isometry3d& T_BC) {
  return f.R_c0_c * T_BC.linear().transpose();  // R_c0_b = R_c0_c R_cb
}

/// Two unit vectors spanning the tangent plane of the sphere at g.
Eigen::Matrix<double, 3, 2> tangentBasis(const Eigen::Vector3d& g) {
  const Eigen::Vector3d a = g.normalized();
  Eigen::Vector3d helper =
      std::abs(a.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d b1 = (helper - a * a.dot(helper)).normalized();
  Eigen::Matrix<double, 3, 2> B;
  B << b1, a.cross(b1);
  return B;
}

/// Linear system of VINS-Mono Eq. 18-19 in the c0 frame. Unknowns: v_0..v_n (c0 frame), then
/// either g (3) or the gravity correction w (2) around `g_fixed` followed by the accelerometer
/// bias change δba (3, observable once |g| is fixed), then the scale s.
///   s (c_{k+1} − c_k) − v_k T − ½ g T² − R_k J_p,ba δba = R_k Δp_k + (R_{k+1} − R_k) t_bc
///   v_{k+1} − v_k − g T − R_k J_v,ba δba = R_k Δv_k
/// `scale_sigma`: uncertainty of the scale, combining the residual's variance times (AᵀA)⁻¹ and,
/// with g fixed, how far the scale moves when the accelerometer-bias prior is moved by
/// kAccelBiasRange along each axis (a bias the window cannot tell from a constant acceleration).
/// With `known_scale` its column moves to the right-hand side: the last unknown is then a
/// placeholder that stays 0, and is returned as the known scale.
Eigen::VectorXd solveLinear(const std::vector<UpToScaleFrame>& frames,
                            const Eigen::Isometry3d& T_BC, const Eigen::Vector3d* g_fixed,
                            double gravity, double* scale_sigma = nullptr,
                            std::optional<double> known_scale = {},
                            const std::optional<Eigen::Vector3d>& first_velocity_c0 = {}) {
  const int n = static_cast<int>(frames.size());
  const int g_dims = g_fixed ? 5 : 3;  // with g fixed: w (2) + δba (3)
  const int unknowns = 3 * n + g_dims + 1;
  // With g fixed, three more rows: a prior δba ≈ 0 (the accelerometer bias is weakly observable
  // over a short window: a constant body-frame acceleration looks like a bias).
  const int prior_rows = g_fixed ? 3 : 0;
  const int velocity_rows = first_velocity_c0 ? 3 : 0;  // v_0 = v_c0, after the bias prior's rows
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * (n - 1) + prior_rows + velocity_rows, unknowns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(A.rows());
  if (g_fixed)
    A.block<3, 3>(6 * (n - 1), 3 * n + 2) = kAccelBiasPriorWeight * Eigen::Matrix3d::Identity();
  if (first_velocity_c0) {
    A.block<3, 3>(6 * (n - 1) + prior_rows, 0) = Eigen::Matrix3d::Identity();
    b.segment<3>(6 * (n - 1) + prior_rows) = *first_velocity_c0;
  }
  Eigen::Matrix<double, 3, 2> B = Eigen::Matrix<double, 3, 2>::Zero();  // used when g_fixed
  Eigen::Vector3d g0 = Eigen::Vector3d::Zero();
  if (g_fixed) {
    g0 = g_fixed->normalized() * gravity;
    B = tangentBasis(g0);
  }
  const Eigen::Vector3d t_bc = T_BC.translation();
  for (int k = 0; k + 1 < n; ++k) {
    const P& pre = *frames[k + 1].from_previous;
    const double T = pre.sumDt();
    const Eigen::Matrix3d Rk = bodyRotation(frames[k], T_BC),
                          Rk1 = bodyRotation(frames[k + 1], T_BC);
    const int row = 6 * k, g_col = 3 * n, s_col = 3 * n + g_dims;
    // Position equation; the gravity term is −½ T² g = −½ T² (g0 + B w).
    A.block<3, 3>(row, 3 * k) = -T * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d baseline = frames[k + 1].p_c0_c - frames[k].p_c0_c;
    b.segment<3>(row) = Rk * pre.deltaP() + (Rk1 - Rk) * t_bc;
    if (known_scale)
      b.segment<3>(row) -= *known_scale * baseline;
    else
      A.block<3, 1>(row, s_col) = baseline;
    // Velocity equation.
    A.block<3, 3>(row + 3, 3 * k) = -Eigen::Matrix3d::Identity();
    A.block<3, 3>(row + 3, 3 * (k + 1)) = Eigen::Matrix3d::Identity();
    b.segment<3>(row + 3) = Rk * pre.deltaV();
    if (g_fixed) {
      A.block<3, 2>(row, g_col) = -0.5 * T * T * B;
      A.block<3, 2>(row + 3, g_col) = -T * B;
      A.block<3, 3>(row, g_col + 2) = -Rk * pre.jacobian().block<3, 3>(P::kP, P::kBa);
      A.block<3, 3>(row + 3, g_col + 2) = -Rk * pre.jacobian().block<3, 3>(P::kV, P::kBa);
      b.segment<3>(row) += 0.5 * T * T * g0;
      b.segment<3>(row + 3) += T * g0;
    } else {
      A.block<3, 3>(row, g_col) = -0.5 * T * T * Eigen::Matrix3d::Identity();
      A.block<3, 3>(row + 3, g_col) = -T * Eigen::Matrix3d::Identity();
    }
  }
  // Normal equations with the scale column rescaled for conditioning.
  const double s_weight = 100.0;
  A.col(unknowns - 1) *= s_weight;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  Eigen::VectorXd x = qr.solve(b);  // with a known scale its zero column solves to 0
  if (scale_sigma && !known_scale) {
    const double dof = std::max<double>(1, A.rows() - unknowns);
    const double variance = (A * x - b).squaredNorm() / dof;
    const Eigen::MatrixXd information = A.transpose() * A;
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(unknowns, unknowns - 1);
    double sigma2 = variance * e.dot(information.ldlt().solve(e));
    for (int axis = 0; axis < prior_rows; ++axis) {
      Eigen::VectorXd moved = b;
      moved(6 * (n - 1) + axis) += kAccelBiasPriorWeight * kAccelBiasRange;
      sigma2 += std::pow(qr.solve(moved)(unknowns - 1) - x(unknowns - 1), 2);
    }
    *scale_sigma = s_weight * std::sqrt(sigma2);
  }
  x(unknowns - 1) = known_scale ? *known_scale : s_weight * x(unknowns - 1);
  if (known_scale && scale_sigma) *scale_sigma = 0;
  if (g_fixed) {
    const Eigen::Vector3d g = g0 + B * x.segment<2>(3 * n);
    Eigen::VectorXd out(3 * n + 7);
    out << x.head(3 * n), g.normalized() * gravity, x(unknowns - 1), x.segment<3>(3 * n + 2);
    return out;
  }
  return x;
}

}  // namespace

Eigen::Vector3d solveGyroBias(std::vector<UpToScaleFrame>& frames, const Eigen::Isometry3d& T_BC) {
  // Each pair: Exp(J_bg δbg) ≈ Δq⁻¹ q_visual → J_bg δbg = 2 vec(Δq⁻¹ q_visual).
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (size_t k = 1; k < frames.size(); ++k) {
    const P& pre = *frames[k].from_previous;
    const Eigen::Quaterniond q_visual(bodyRotation(frames[k - 1], T_BC).transpose() *
                                      bodyRotation(frames[k], T_BC));
    const Eigen::Matrix3d J = pre.jacobian().block<3, 3>(P::kR, P::kBg);
    const Eigen::Vector3d r = 2 * (pre.deltaQ().inverse() * q_visual).vec();
    A += J.transpose() * J;
    b += J.transpose() * r;
  }
  const Eigen::Vector3d delta = A.ldlt().solve(b);
  for (size_t k = 1; k < frames.size(); ++k) {
    auto& pre = *frames[k].from_previous;
    pre.repropagate(pre.linearizedBa(), pre.linearizedBg() + delta);
  }
  return frames.size() > 1 ? Eigen::Vector3d(frames[1].from_previous->linearizedBg()) : delta;
}

std::optional<AlignmentResult> alignVisualInertial(
    std::vector<UpToScaleFrame>& frames, const Eigen::Isometry3d& T_BC, double gravity,
    std::string* why_not, std::optional<double> known_scale,
    const std::optional<Eigen::Vector3d>& first_velocity_c0) {
  auto fail = [&](const std::string& reason) {
    if (why_not) *why_not = reason;
    return std::nullopt;
  };
  if (frames.size() < 4) return fail("too few frames for the alignment");
  AlignmentResult result;
  result.gyro_bias = solveGyroBias(frames, T_BC);
  const int n = static_cast<int>(frames.size());
  Eigen::VectorXd x =
      solveLinear(frames, T_BC, nullptr, gravity, nullptr, known_scale, first_velocity_c0);
  const Eigen::Vector3d g_free = x.segment<3>(3 * n);
  if (x(3 * n + 3) <= 0) return fail("alignment rejected: non-positive scale");
  if (std::abs(g_free.norm() - gravity) > 0.2 * gravity)
    return fail("alignment rejected: gravity magnitude " + std::to_string(g_free.norm()));
  // Refinement on the sphere |g| = gravity (2 degrees of freedom), a few re-linearizations.
  Eigen::Vector3d g = g_free;
  for (int iteration = 0; iteration < 4; ++iteration) {
    x = solveLinear(frames, T_BC, &g, gravity, &result.scale_sigma, known_scale, first_velocity_c0);
    g = x.segment<3>(3 * n);
  }
  result.scale = x(3 * n + 3);
  result.accel_bias = x.segment<3>(3 * n + 4);
  if (result.scale <= 0) return fail("alignment rejected: non-positive scale after refinement");
  result.gravity_c0 = g;
  for (int k = 0; k < n; ++k) result.velocity_c0.push_back(x.segment<3>(3 * k));
  return result;
}

}  // namespace rpvio
