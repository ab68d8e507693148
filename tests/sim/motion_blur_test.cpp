// Motion blur of a finite exposure against the motion that causes it: a known pan, a dancing
// character before a still camera, and the simulator's defaults (sharp, unchanged).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "sim/motion_blur.h"
#include "sim/simulator.h"

namespace rpvio::sim {
namespace {

/// Camera at `position` looking horizontally at azimuth `yaw` (camera z forward, y down).
Eigen::Isometry3d lookingAt(const Eigen::Vector3d& position, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
               CameraRig().T_BC().linear();
  T.translation() = position;
  return T;
}

SceneParams bareRoom() {
  SceneParams p;
  p.crates = 0;
  p.racks = false;
  p.texel_size = 0.05;
  return p;
}

/// Width of the rise of `profile` (0 → 1) from 10 % to 90 %, crossings interpolated, searched
/// leftwards from column `start`.
double riseWidth(const std::vector<double>& profile, int start) {
  auto crossing = [&](double level) {
    for (int c = start; c > 0; --c)
      if (profile[c - 1] < level && profile[c] >= level)
        return c - 1 + (level - profile[c - 1]) / (profile[c] - profile[c - 1]);
    return -1.0;
  };
  return crossing(0.9) - crossing(0.1);
}

TEST(MotionBlur, PanSmearsADiscByFocalTimesRateTimesExposure) {
  const double omega = 1.0, exposure = 0.03, t = 0;  // rad/s yaw, s
  const PinholeCamera cam;                           // f = 320 px
  const Eigen::Vector3d position(0, 0, 3);
  // A disc of 1.5 m radius on wall 2 (x = 20) straight ahead: 24 px in radius.
  auto discRadiance = [&](float intensity, const ShutterInterval* shutter) {
    SceneParams p = bareRoom();
    p.markers.push_back({Eigen::Vector3d(20, 0, 3), 1.5, intensity});
    const WarehouseScene scene(p);
    const Eigen::Isometry3d T_WC = lookingAt(position, 0);
    const SceneRadiance sharp = renderRadiance(scene, cam, T_WC, RenderOptions{});
    return shutter ? motionBlur(sharp, scene, cam, T_WC, *shutter, 0) : sharp.radiance;
  };
  const ShutterInterval pan{t - exposure / 2, t + exposure / 2,
                            lookingAt(position, -omega * exposure / 2),
                            lookingAt(position, omega * exposure / 2)};
  for (const ShutterInterval* shutter : {&pan, static_cast<const ShutterInterval*>(nullptr)}) {
    // The disc alone: the difference of a white and a black disc (the blur is linear).
    const cv::Mat disc = (discRadiance(255, shutter) - discRadiance(0, shutter)) / 255;
    std::vector<double> row(cam.width);
    for (int c = 0; c < cam.width; ++c) row[c] = disc.at<float>(239, c);
    // A box blur of length L makes the edge a linear ramp: 10-90 % over 0.8 L.
    const double width = riseWidth(row, 319) / 0.8;
    const double expected = shutter ? cam.fx * omega * exposure : 0.0;  // 9.6 px
    std::printf("edge ramp %.2f px, f w e = %.2f px\n", width, expected);
    if (shutter)
      EXPECT_NEAR(width, expected, 0.15 * expected);
    else
      EXPECT_LT(width, 1.25);  // sharp: the disc's edge within one pixel
  }
}

TEST(MotionBlur, MovingCharacterBlursBeforeAStillCamera) {
  SceneParams p = bareRoom();
  p.characters = 1;
  WarehouseScene scene(p);
  const double t = 0.7, exposure = 0.04;
  scene.setTime(t);
  PinholeCamera cam;
  cam.fx = cam.fy = 1200;  // the 1.8 m figure 10.5 m away: about 200 px tall
  const Eigen::Vector2d base = scene.characters()[0].figure().parts()[0].a.head<2>();  // head
  const Eigen::Isometry3d T_WC =
      lookingAt(Eigen::Vector3d(0, 0, 1), std::atan2(base.y(), base.x()));
  const SceneRadiance sharp = renderRadiance(scene, cam, T_WC, RenderOptions{});
  const ShutterInterval still{t - exposure / 2, t + exposure / 2, T_WC, T_WC};
  const cv::Mat blurred = motionBlur(sharp, scene, cam, T_WC, still, 0);

  double background_change = 0, edge_change = 0;
  int edge_pixels = 0, blended = 0;
  for (int r = 1; r + 1 < cam.height; ++r)
    for (int c = 1; c + 1 < cam.width; ++c) {
      const double change = std::abs(blurred.at<float>(r, c) - sharp.radiance.at<float>(r, c));
      auto character = [&](int rr, int cc) {
        return sharp.mask.at<uint8_t>(rr, cc) == kMaskCharacter;
      };
      if (!character(r, c)) {
        background_change = std::max(background_change, change);
        continue;
      }
      if (character(r - 1, c) && character(r + 1, c) && character(r, c - 1) && character(r, c + 1))
        continue;
      ++edge_pixels;
      edge_change += change;
      if (change > 5) ++blended;
    }
  std::printf("%d character edge pixels, %d blended, mean change %.1f\n", edge_pixels, blended,
              edge_change / edge_pixels);
  ASSERT_GT(edge_pixels, 200);
  EXPECT_LT(background_change, 0.05);   // the still background stays sharp
  EXPECT_GT(blended, edge_pixels / 4);  // the moving limbs' edges blend with the background
}

TEST(MotionBlur, SimulatorBlursOnlyWithAnExposureTime) {
  SimConfig config;
  config.scene.texel_size = 0.05;
  config.scene.characters = 2;
  const double t = 12.0;
  Simulator sharp_sim(config);
  const RenderedFrame sharp = sharp_sim.render(t, 3);
  // exposure_time 0 is today's image: renderFrame at the frame's pose.
  const RenderedFrame reference =
      renderFrame(sharp_sim.scene(), config.camera.intrinsics(), sharp_sim.cameraPose(t),
                  config.render, config.seed * 1000003ULL + 3);
  EXPECT_EQ(cv::norm(sharp.image, reference.image, cv::NORM_INF), 0);

  // The blur follows the true camera motion over [t − e/2, t + e/2]; noise comes after it.
  config.exposure_time = 0.1;
  Simulator blur_sim(config);
  const RenderedFrame blurred = blur_sim.render(t, 3);
  EXPECT_EQ(cv::norm(blurred.mask, sharp.mask, cv::NORM_INF), 0);  // labels stay sharp
  const double t_open = t - 0.05, t_close = t + 0.05;
  const ShutterInterval shutter{t_open, t_close, blur_sim.cameraPose(t_open),
                                blur_sim.cameraPose(t_close)};
  const SceneRadiance radiance = renderRadiance(blur_sim.scene(), config.camera.intrinsics(),
                                                blur_sim.cameraPose(t), config.render);
  const cv::Mat expected =
      exposeImage(motionBlur(radiance, blur_sim.scene(), config.camera.intrinsics(),
                             blur_sim.cameraPose(t), shutter, 0),
                  config.camera.intrinsics(), config.render, 1.0, config.seed * 1000003ULL + 3);
  EXPECT_EQ(cv::norm(blurred.image, expected, cv::NORM_INF), 0);
  // The flight pans horizontally: horizontal gradients lose energy.
  auto gradient = [](const cv::Mat& image) {
    cv::Mat dx;
    cv::Sobel(image, dx, CV_32F, 1, 0);
    return cv::norm(dx, cv::NORM_L1);
  };
  std::printf("horizontal gradient energy: blurred / sharp = %.3f\n",
              gradient(blurred.image) / gradient(sharp.image));
  EXPECT_LT(gradient(blurred.image), 0.9 * gradient(sharp.image));
}

}  // namespace
}  // namespace rpvio::sim
