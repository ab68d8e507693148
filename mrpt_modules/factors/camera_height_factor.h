#pragma once
// The camera's known height h above the ground (calib.ini [ground] camera_height) as a factor on
// a keyframe: the camera centre c = p_wb + R_wb t_BC stays h from the ground plane n·X = d of the
// window (parameter_blocks.h), on the side s = ±1 it is on:
//   r = sqrt_info · (s (n·c − d) − h).
// The plane's homography factors tie the camera's distance to it to the window's own scale, so
// this holds the metric scale and the height where the IMU's accelerations do not (a car or a
// robot at constant velocity).
// Blocks: pose [7], T_BC [7], plane normal [3] (ambient), plane distance [1]. Residual: 1.
// Analytic Jacobians (right perturbation of the poses, pose_manifold.h): ∂c/∂δp = I,
// ∂c/∂δθ = −R_wb [t_BC]×, ∂c/∂δp_BC = R_wb.
#include <ceres/sized_cost_function.h>

namespace rpvio {

class CameraHeightResidual : public ceres::SizedCostFunction<1, 7, 7, 3, 1> {
 public:
  CameraHeightResidual(double height, double side, double sqrt_info)
      : height_(height), side_(side), sqrt_info_(sqrt_info) {}
  /// The caller owns it.
  static ceres::CostFunction* create(double height, double side, double sqrt_info) {
    return new CameraHeightResidual(height, side, sqrt_info);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double height_, side_, sqrt_info_;
};

}  // namespace rpvio
