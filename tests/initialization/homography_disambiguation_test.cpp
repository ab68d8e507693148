// The homography decomposition and its IMU disambiguation over random plane/motion configurations.
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/initialization/plane_motion_from_homography.h"

namespace rpvio {
namespace {

struct Scene {
  Eigen::Matrix3d R;
  Eigen::Vector3d t, n;
  double d;
  std::vector<Eigen::Vector2d> xi, xj;
};

double angleDeg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(A.transpose() * B).angle() * 180 / M_PI;
}

/// A random plane in front of camera i, a random motion with enough translational parallax (the
/// initializer's 30 px at f = 460 gate, after compensating the rotation), 60 features with 0.5 px
/// noise.
Scene randomScene(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  const double f = 460, noise = 0.5 / f;
  for (;;) {
    Scene s;
    const Eigen::Vector3d p0(u(rng), u(rng), 2 + 6.5 * (u(rng) + 1));
    Eigen::Vector3d n =
        (Eigen::Vector3d(0, 0, 1) + 1.2 * Eigen::Vector3d(u(rng), u(rng), 0)).normalized();
    s.n = n;
    s.d = n.dot(p0);
    if (s.d <= 0.5) continue;
    const Eigen::Vector3d axis = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    s.R = Eigen::AngleAxisd(0.26 * (u(rng) + 1) / 2, axis).toRotationMatrix();
    s.t = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized() * (0.2 + 0.8 * (u(rng) + 1) / 2);
    double parallax = 0;
    for (int k = 0; k < 200 && s.xi.size() < 60; ++k) {
      const Eigen::Vector3d ray(320 * u(rng) / f, 240 * u(rng) / f, 1);
      const double depth = s.d / n.dot(ray);
      if (depth <= 0.3 || depth > 60) continue;
      const Eigen::Vector3d Xj = s.R * (depth * ray) + s.t;
      if (Xj.z() <= 0.3) continue;
      const Eigen::Vector2d pj = Xj.head<2>() / Xj.z();
      if (std::abs(pj.x()) > 320 / f || std::abs(pj.y()) > 240 / f) continue;
      s.xi.push_back(ray.head<2>() + noise * Eigen::Vector2d(g(rng), g(rng)));
      s.xj.push_back(pj + noise * Eigen::Vector2d(g(rng), g(rng)));
      const Eigen::Vector3d rotated = s.R * ray;
      parallax += f * (pj - rotated.head<2>() / rotated.z()).norm();
    }
    if (s.xi.size() >= 40 && parallax / s.xi.size() > 30) return s;
  }
}

TEST(HomographyDisambiguation, ImuRotationPicksTheTrueSolution) {
  std::mt19937_64 rng(2021);
  std::normal_distribution<double> g(0, 1);
  int correct = 0, decided = 0;
  double worst_rotation = 0;
  const int trials = 1000;
  for (int k = 0; k < trials; ++k) {
    const Scene s = randomScene(rng);
    // Gyroscope rotation with 0.5° of error about a random axis.
    const Eigen::Vector3d axis = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const Eigen::Matrix3d R_gyro =
        s.R * Eigen::AngleAxisd(0.5 * M_PI / 180, axis).toRotationMatrix();
    std::vector<PlaneMotion> candidates;
    const auto chosen = planeMotionFromHomography(s.xi, s.xj, R_gyro, HomographyInitOptions{},
                                                  nullptr, &candidates);
    if (!chosen) continue;
    ++decided;
    // The true solution is the decomposition closest to the truth in rotation and normal.
    auto distance = [&](const PlaneMotion& m) {
      return angleDeg(m.R, s.R) + std::acos(std::clamp(m.n.dot(s.n), -1.0, 1.0)) * 180 / M_PI;
    };
    const auto truest =
        std::min_element(candidates.begin(), candidates.end(),
                         [&](const auto& a, const auto& b) { return distance(a) < distance(b); });
    correct += distance(*chosen) == distance(*truest);
    worst_rotation = std::max(worst_rotation, angleDeg(chosen->R, s.R));
  }
  std::printf("disambiguation: %d/%d decided, %d correct (%.2f%%), worst rotation error %.2f deg\n",
              decided, trials, correct, 100.0 * correct / trials, worst_rotation);
  EXPECT_GE(correct, 0.995 * trials);
}

TEST(HomographyDisambiguation, ScaleFreeTranslationAndPlaneAreRecovered) {
  std::mt19937_64 rng(7);
  const Scene s = randomScene(rng);
  const auto m = planeMotionFromHomography(s.xi, s.xj, s.R, HomographyInitOptions{});
  ASSERT_TRUE(m);
  EXPECT_LT((m->t_over_d - s.t / s.d).norm(), 0.05 * (s.t / s.d).norm() + 1e-3);
}

TEST(HomographyDisambiguation, BodyToCameraRotation) {
  // Camera looking along body x (the simulator's mount): a yaw of the body to the left is, for the
  // camera, a rotation about its −y axis; points move by the inverse.
  Eigen::Matrix3d R_BC;
  R_BC << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(0.1, -Eigen::Vector3d::UnitY()).toRotationMatrix().transpose();
  EXPECT_TRUE(cameraRotationFromBody(yaw, R_BC).isApprox(expected, 1e-12));
}

TEST(HomographyDisambiguation, TooFewFeaturesSaysWhy) {
  std::string why;
  EXPECT_FALSE(planeMotionFromHomography({{0, 0}}, {{0, 0}}, Eigen::Matrix3d::Identity(),
                                         HomographyInitOptions{}, &why));
  EXPECT_NE(why.find("too few plane features"), std::string::npos);
}

}  // namespace
}  // namespace rpvio
