#pragma once
// Camera–IMU time offset from the rotations of an initialized window. The cameras' orientations
// come from vision alone (structure from motion); the gyroscope, integrated between the frame
// times moved by td, must reproduce them. With R_k the body orientation of frame k and
// ΔR(a, b; b_g) the gyroscope's rotation from time a to b with bias b_g,
//   (b_g, td) = argmin Σ_k ‖Log(ΔR(t_r + td, t_k + td; b_g)ᵀ R_rᵀ R_k)‖²,
// Gauss–Newton with central-difference derivatives (4 unknowns). The signal is the change of the
// angular rate over the window: ΔR(t_r + td, t_k + td) ≈ ΔR(t_r, t_k) Exp((ω_k − ΔRᵀ ω_r) td).
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

struct TimeOffsetEstimate {
  double td = 0;     // s, to add to the frame times (t_imu = t_frame + td)
  double sigma = 0;  // s, standard deviation: residual variance times (JᵀJ)⁻¹, inflated for
                     // the residuals' correlation from frame to frame (AR(1), time_offset.cpp)
  double residual_correlation = 0;  // ρ, lag-1 autocorrelation of the rotation residuals
  // s, the offset that a rotation error as large as the fit's residual could fake if it lay along
  // the offset's own signature: ‖r‖ √((JᵀJ)⁻¹)_td,td. Structure from motion's rotation errors
  // follow the motion and part of them is absorbed into td unseen by sigma (time_offset.cpp).
  double systematic = 0;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  double rms_deg = 0;  // rotation residual per frame
  size_t frames = 0;   // frames whose shifted interval the samples cover
};

/// `frame_t[k]`, `R_w_b[k]`: frame times (IMU clock as far as known) and body orientations;
/// `samples`: gyroscope samples in time order covering the window; `gyro_bias`: initial guess.
/// Only frames whose times moved by ±max_offset lie within the samples are used. nullopt (and
/// the reason) with fewer than 4 such frames or a singular system (no change of angular rate).
std::optional<TimeOffsetEstimate> estimateTimeOffset(const std::vector<double>& frame_t,
                                                     const std::vector<Eigen::Matrix3d>& R_w_b,
                                                     const std::vector<ImuSample>& samples,
                                                     const Eigen::Vector3d& gyro_bias,
                                                     double max_offset,
                                                     std::string* why_not = nullptr);

}  // namespace rpvio
