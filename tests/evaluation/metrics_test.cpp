// ATE/RPE against published evo results on real trajectories (../shared/data/evo, KITTI:
// CC BY-NC-SA 3.0, TUM RGB-D: CC BY 4.0) and alignment invariants.
#include <gtest/gtest.h>

#include <random>

#include "evaluation/trajectory_metrics.h"
#include "rawlog_io/trajectory_io.h"
#include "tests/test_util.h"

namespace rpvio::eval {
namespace {

const std::string kEvo = test::dataDir() + "/evo/";

EvalResult evaluateKitti(const std::string& est_name) {
  EvalOptions opt;
  opt.associate_by_index = true;
  return evaluate(readKitti(kEvo + "KITTI_00_gt.txt"), readKitti(kEvo + est_name), opt);
}

TEST(AtePublished, Kitti00OrbSe3) {
  const EvalResult r = evaluateKitti("KITTI_00_ORB.txt");
  EXPECT_EQ(r.pairs.size(), 4541u);
  EXPECT_NEAR(r.ate.rmse, 1.3034497145650266, 1e-6);
  EXPECT_NEAR(r.ate.mean, 1.1569971285389768, 1e-6);
  EXPECT_NEAR(r.ate.max, 3.587949120678954, 1e-6);
}

TEST(AtePublished, Kitti00SptamSe3) {
  EXPECT_NEAR(evaluateKitti("KITTI_00_SPTAM.txt").ate.rmse, 3.738487907582613, 1e-6);
}

Trajectory transformed(const Trajectory& in, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                       double s) {
  Trajectory out = in;
  const Eigen::Quaterniond q(R);
  for (auto& p : out) {
    p.p = s * R * p.p + t;
    p.q = q * p.q;
  }
  return out;
}

TEST(Alignment, Sim3RecoversScale) {
  const Trajectory gt = readKitti(kEvo + "KITTI_00_gt.txt");
  const Trajectory est = readKitti(kEvo + "KITTI_00_ORB.txt");
  EvalOptions opt;
  opt.associate_by_index = true;
  opt.align = AlignMode::Sim3;
  const double k = 3.7;
  const EvalResult unscaled = evaluate(gt, est, opt);
  const EvalResult scaled =
      evaluate(gt, transformed(est, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), k), opt);
  EXPECT_NEAR(scaled.ate.rmse, unscaled.ate.rmse, 1e-9);
  EXPECT_NEAR(scaled.alignment.s, unscaled.alignment.s / k, 1e-9);
}

TEST(Alignment, RigidCopyAlignsExactly) {
  // A real hand-held trajectory with unique stamps (the ground-truth file repeats some stamps).
  const Trajectory gt = readTum(kEvo + "fr2_desk_ORB.txt");
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  EvalOptions opt;
  opt.align = AlignMode::SE3;
  EXPECT_LT(evaluate(gt, transformed(gt, R, {4, -2, 1}, 1.0), opt).ate.rmse, 1e-9);

  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(-2.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  opt.align = AlignMode::PosYaw;
  const EvalResult r = evaluate(gt, transformed(gt, yaw, {4, -2, 1}, 1.0), opt);
  EXPECT_LT(r.ate.rmse, 1e-9);
  EXPECT_LT(r.ate_rotation_rmse_deg, 1e-6);
  // Yaw-only alignment cannot undo a roll: the error must show.
  EXPECT_GT(evaluate(gt, transformed(gt, R, {4, -2, 1}, 1.0), opt).ate.rmse, 0.01);
}

TEST(Association, MatchesBruteForceOnFr2Desk) {
  const Trajectory gt = readTum(kEvo + "fr2_desk_groundtruth.txt");
  const Trajectory est = readTum(kEvo + "fr2_desk_ORB.txt");
  const double max_dt = 0.01;
  size_t brute = 0;
  for (const auto& e : est) {
    double best = 1e9;
    for (const auto& g : gt) best = std::min(best, std::abs(g.t - e.t));
    if (best <= max_dt) ++brute;
  }
  const Association pairs = associateByTime(gt, est, max_dt);
  EXPECT_EQ(pairs.size(), brute);
  for (const auto& [g, e] : pairs) EXPECT_LE(std::abs(gt[g].t - est[e].t), max_dt);
  EvalOptions opt;
  opt.align = AlignMode::Sim3;  // monocular ORB: scale is arbitrary
  const EvalResult r = evaluate(gt, est, opt);
  EXPECT_LT(r.ate.rmse, 0.01);
  EXPECT_GT(r.coverage, 0.5);
}

TEST(Coverage, LostTrackIsVisible) {
  const Trajectory gt = readTum(kEvo + "fr2_desk_ORB.txt");
  const Trajectory half(gt.begin(), gt.begin() + gt.size() / 2);
  EvalOptions opt;
  const EvalResult r = evaluate(gt, half, opt);
  EXPECT_NEAR(r.coverage, 0.5, 0.02);
  EXPECT_LT(r.ate.rmse, 1e-9);
}

TEST(Rpe, RigidCopyHasZeroRelativeError) {
  const Trajectory gt = readKitti(kEvo + "KITTI_00_gt.txt");
  EvalOptions opt;
  opt.associate_by_index = true;
  const EvalResult r =
      evaluate(gt, transformed(gt, Eigen::Matrix3d::Identity(), {1, 2, 3}, 1), opt);
  EXPECT_LT(r.rpe_distance.translation.max, 1e-9);
  EXPECT_GT(r.rpe_distance.translation.count, 1000u);
  const EvalResult orb = evaluateKitti("KITTI_00_ORB.txt");
  EXPECT_GT(orb.rpe_distance.translation.rmse, 0.0);
}

TEST(Evaluate, NoOverlapThrows) {
  Trajectory a(5), b(5);
  for (int i = 0; i < 5; ++i) a[i].t = i, b[i].t = 100 + i;
  EXPECT_THROW(evaluate(a, b, EvalOptions{}), std::runtime_error);
}

}  // namespace
}  // namespace rpvio::eval
