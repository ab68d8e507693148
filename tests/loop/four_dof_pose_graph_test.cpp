// The 4-DoF pose graph: its residual's derivatives against numeric ones, and drift removed from a
// circle flown twice with revisits.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <random>

#include "mrpt_modules/loop/four_dof_pose_graph.h"

namespace rpvio {
namespace {

TEST(YawPitchRoll, RoundTripsThroughARotation) {
  const Eigen::Matrix3d R = fromYawPitchRoll(2.5, -0.3, 0.2);
  const Eigen::Vector3d ypr = yawPitchRoll(R);
  EXPECT_NEAR(ypr.x(), 2.5, 1e-12);
  EXPECT_NEAR(ypr.y(), -0.3, 1e-12);
  EXPECT_NEAR(ypr.z(), 0.2, 1e-12);
}

TEST(FourDofEdgeResidual, AutomaticDerivativesMatchNumericOnes) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 20; ++trial) {
    const FourDofEdgeResidual residual(Eigen::Vector3d(u(rng), u(rng), u(rng)), u(rng),
                                       0.1 * u(rng), 0.1 * u(rng), 10);
    ceres::AutoDiffCostFunction<FourDofEdgeResidual, 4, 1, 3, 1, 3> exact(
        new FourDofEdgeResidual(residual));
    ceres::NumericDiffCostFunction<FourDofEdgeResidual, ceres::CENTRAL, 4, 1, 3, 1, 3> numeric(
        new FourDofEdgeResidual(residual));
    double yaw_i = u(rng), yaw_j = u(rng), p_i[3] = {u(rng), u(rng), u(rng)},
           p_j[3] = {u(rng), u(rng), u(rng)};
    const double* blocks[] = {&yaw_i, p_i, &yaw_j, p_j};
    double r_exact[4], r_numeric[4];
    double j_exact[4][12], j_numeric[4][12];
    double* je[] = {j_exact[0], j_exact[1], j_exact[2], j_exact[3]};
    double* jn[] = {j_numeric[0], j_numeric[1], j_numeric[2], j_numeric[3]};
    ASSERT_TRUE(exact.Evaluate(blocks, r_exact, je));
    ASSERT_TRUE(numeric.Evaluate(blocks, r_numeric, jn));
    const int sizes[] = {1, 3, 1, 3};
    for (int b = 0; b < 4; ++b)
      for (int k = 0; k < 4 * sizes[b]; ++k)
        EXPECT_NEAR(j_exact[b][k], j_numeric[b][k], 1e-6) << "block " << b << " entry " << k;
  }
}

/// A body flying a circle of radius 10 m, heading along it, slightly tilted, height oscillating.
Eigen::Isometry3d circlePose(double angle) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() =
      Eigen::Vector3d(10 * std::cos(angle), 10 * std::sin(angle), 1.5 + 0.3 * std::sin(3 * angle));
  T.linear() = fromYawPitchRoll(angle + M_PI / 2, 0.05 * std::sin(angle), 0.08);
  return T;
}

TEST(FourDofPoseGraph, RevisitsRemoveTheDriftOfTheSecondLap) {
  // Odometry that drifts by 0.3° of yaw per keyframe and 2 % of each step's length; 60 keyframes
  // per lap, two laps; each keyframe of the second lap revisits the first's (the loop measured
  // exactly).
  constexpr int kPerLap = 60;
  std::vector<Eigen::Isometry3d> truth, odometry;
  for (int k = 0; k < 2 * kPerLap; ++k) {
    truth.push_back(circlePose(2 * M_PI * k / kPerLap));
    if (k > 0) {
      // The step the odometry measured: the true one, turned and lengthened a little.
      const Eigen::Isometry3d step = truth[k - 1].inverse() * truth[k];
      Eigen::Isometry3d measured = step;
      measured.translation() *= 1.02;
      const Eigen::Isometry3d previous = odometry.back();
      Eigen::Isometry3d next = previous * measured;
      next.linear() =
          Eigen::AngleAxisd(0.3 * M_PI / 180, Eigen::Vector3d::UnitZ()).matrix() * next.linear();
      // Roll and pitch stay observable: keep the truth's.
      const Eigen::Vector3d ypr = yawPitchRoll(next.linear());
      const Eigen::Vector3d true_ypr = yawPitchRoll(truth[k].linear());
      next.linear() = fromYawPitchRoll(ypr.x(), true_ypr.y(), true_ypr.z());
      odometry.push_back(next);
    } else {
      odometry.push_back(truth[0]);
    }
  }
  FourDofPoseGraph graph(PoseGraphOptions{});
  for (int k = 0; k < 2 * kPerLap; ++k) {
    graph.addKeyframe(odometry[k]);
    if (k >= kPerLap) {
      // The old body in the query's (odometry) world: the true relative pose from the query.
      const Eigen::Isometry3d old_body = odometry[k] * truth[k].inverse() * truth[k - kPerLap];
      graph.addLoop(k - kPerLap, k, old_body);
    }
  }
  double before = 0, after = 0;
  for (int k = 0; k < 2 * kPerLap; ++k)
    before = std::max(before, (odometry[k].translation() - truth[k].translation()).norm());
  graph.optimize();
  for (int k = 0; k < 2 * kPerLap; ++k)
    after = std::max(after, (graph.corrected(k).translation() - truth[k].translation()).norm());
  EXPECT_GT(before, 5.0);  // the odometry's error after two laps
  EXPECT_LT(after, 0.25 * before);
  // The correction moves the odometry's pose onto the graph's.
  const Eigen::Isometry3d moved = graph.correction(100) * odometry[100];
  EXPECT_LT((moved.translation() - graph.corrected(100).translation()).norm(), 1e-9);
  EXPECT_LT(Eigen::AngleAxisd(moved.linear().transpose() * graph.corrected(100).linear()).angle(),
            1e-9);
}

TEST(FourDofPoseGraph, WithoutLoopsTheOdometryIsKept) {
  FourDofPoseGraph graph(PoseGraphOptions{});
  for (int k = 0; k < 10; ++k) graph.addKeyframe(circlePose(0.1 * k));
  graph.optimize();
  for (int k = 0; k < 10; ++k)
    EXPECT_LT((graph.corrected(k).translation() - circlePose(0.1 * k).translation()).norm(), 1e-9);
}

TEST(FourDofPoseGraph, ARevisitOfAMapMovesTheRunIntoTheMapsFrame) {
  // A map of one lap held where it was saved; a second run flies the lap again in a world turned
  // by 1.2 rad and moved by (30, -4, 0.5) m (another start), its odometry turning 0.1° too far at
  // each step. Every keyframe of the run revisits the map's (measured exactly).
  constexpr int kKeyframes = 40;
  Eigen::Isometry3d world_to_run = Eigen::Isometry3d::Identity();
  world_to_run.linear() = fromYawPitchRoll(1.2, 0, 0);
  world_to_run.translation() = Eigen::Vector3d(30, -4, 0.5);
  FourDofPoseGraph graph(PoseGraphOptions{});
  for (int k = 0; k < kKeyframes; ++k) graph.addMapKeyframe(circlePose(0.15 * k));
  Eigen::Isometry3d drifted = world_to_run * circlePose(0);
  double odometry_error = 0;
  for (int k = 0; k < kKeyframes; ++k) {
    if (k > 0) {
      const Eigen::Isometry3d step = circlePose(0.15 * (k - 1)).inverse() * circlePose(0.15 * k);
      drifted = drifted * step;
      const Eigen::Vector3d ypr = yawPitchRoll(drifted.linear());
      const Eigen::Vector3d true_ypr = yawPitchRoll(circlePose(0.15 * k).linear());
      drifted.linear() = fromYawPitchRoll(ypr.x() + 0.1 * M_PI / 180, true_ypr.y(), true_ypr.z());
    }
    odometry_error = std::max(odometry_error, (world_to_run.inverse() * drifted.translation() -
                                               circlePose(0.15 * k).translation())
                                                  .norm());
    const size_t index = graph.addKeyframe(drifted);
    ASSERT_EQ(index, static_cast<size_t>(kKeyframes + k));
    EXPECT_EQ(graph.relocalized(), k > 0);
    // Before the first revisit the run is in its own world.
    if (k == 0) {
      EXPECT_GT((graph.corrected(index).translation() - circlePose(0).translation()).norm(), 10);
    }
    graph.addLoop(k, index, drifted);  // the same place: the old body is the query's
  }
  graph.optimize();
  double error = 0;
  for (int k = 0; k < kKeyframes; ++k) {
    // The map's keyframes are held; the run's are where the map has the same place.
    EXPECT_LT((graph.corrected(k).translation() - circlePose(0.15 * k).translation()).norm(),
              1e-12);
    error = std::max(
        error, (graph.corrected(kKeyframes + k).translation() - circlePose(0.15 * k).translation())
                   .norm());
  }
  EXPECT_GT(odometry_error, 0.5);
  EXPECT_LT(error, 0.1 * odometry_error);
  std::printf("the run's keyframes off the map's by %.3f m at most (odometry %.3f m)\n", error,
              odometry_error);
  // A new world (a reset) forgets the run, not the map.
  graph.clearSession();
  EXPECT_EQ(graph.size(), static_cast<size_t>(kKeyframes));
  EXPECT_FALSE(graph.relocalized());
}

}  // namespace
}  // namespace rpvio
