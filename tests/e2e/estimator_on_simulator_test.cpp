// The estimator fed by the front-end on a simulated sequence (no rawlog): trajectory accuracy and
// what its plane map claims of itself.
#include <gtest/gtest.h>

#include <algorithm>

#include "apps/lib/sim_app.h"
#include "evaluation/plane_map_accuracy.h"
#include "evaluation/trajectory_metrics.h"
#include "mrpt_modules/estimator/map_builder.h"
#include "mrpt_modules/estimator/sliding_window_estimator.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "sim/sequence_name.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

struct SimulatorRun {
  eval::EvalResult trajectory;
  size_t resets = 0;
  double first_pose_t = -1;    // time of the first estimated pose (−1: never initialized)
  double initialized_at = -1;  // of the frame that initialized (the window's poses come with it)
  double path_length = 0;    // of the true trajectory, m
  size_t tracked_frames = 0, camera_height_frames = 0;  // frames with a state; of them, with
                                                        // camera-height factors
  // Frames that were not keyframes (their second newest frame was dropped), and those of them
  // whose solve moved a plane the window already had.
  size_t between_keyframes = 0, between_keyframes_moving_planes = 0;
  eval::PlaneMapAccuracy planes;
  double max_tilt_error_deg = 0;  // the estimated gravity direction's, in the body frame
};

/// What differs from the defaults (rpvio-single without verification, 20 Hz).
struct RunSetup {
  HomographyPlanes homography = EstimatorOptions{}.homography_planes;
  bool discover_planes = false;   // rpvio-auto: no masks, 250 features, init_window_s 2.5 (its
                                  // config's)
  double camera_rate = 20;        // Hz, the simulator's default
  std::string profile = "paper";  // the simulator's (its camera rate then the profile's)
  double camera_height_sigma = EstimatorOptions{}.camera_height_sigma;
  double accel_bias_prior_sigma = EstimatorOptions{}.accel_bias_prior_sigma;
  bool motion_only_between_keyframes = EstimatorOptions{}.motion_only_between_keyframes;
  bool moving_objects = false;  // the MP sequences' pallet trucks and sliding panels
  bool verify_planes = false;
};

/// Whether a plane of `before` has other parameters in `after`.
bool anyPlaneMoved(const PlaneEstimates& before, const PlaneEstimates& after) {
  for (const auto& [id, plane] : before) {
    const auto it = after.find(id);
    if (it == after.end()) continue;
    if (!std::equal(plane.normal, plane.normal + 3, it->second.normal) ||
        plane.distance[0] != it->second.distance[0])
      return true;
  }
  return false;
}

SimulatorRun runOnSimulator(int characters, double duration, const RunSetup& setup = {}) {
  sim::SimConfig config = sim::SimConfig::profile(setup.profile);
  config.duration = duration;
  if (setup.profile == "paper") config.camera_rate = setup.camera_rate;
  config = sim::withSequenceContent(config, {characters, setup.moving_objects});
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  TrackerOptions tracking;
  tracking.use_masks = !setup.discover_planes;
  if (setup.discover_planes) tracking.max_features = 250;
  FeatureTracker tracker(sim.calibration().camera, tracking);
  EstimatorOptions options;
  options.homography_planes = setup.homography;
  options.discover_planes = setup.discover_planes;
  if (setup.discover_planes) options.init_window_s = 2.5;
  options.camera_height_sigma = setup.camera_height_sigma;
  options.accel_bias_prior_sigma = setup.accel_bias_prior_sigma;
  options.motion_only_between_keyframes = setup.motion_only_between_keyframes;
  options.verify_planes = setup.verify_planes;
  MapBuilder map(PlanesMapOptions{}, MapBuilderOptions{});
  SlidingWindowEstimator estimator(sim.calibration(), options, map);
  SimulatorRun run;
  Trajectory estimate, truth;
  size_t previous = 0;
  const auto times = sim.frameTimes();
  for (size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    const auto image = sim.render(t, static_cast<int>(k));
    const FeatureFrame features = tracker.track(t, image.image, image.mask);
    const size_t now = static_cast<size_t>(std::llround(t * config.imu.rate_hz));
    std::vector<ImuSample> samples(imu.begin() + previous, imu.begin() + now + 1);
    previous = now;
    const PlaneEstimates planes_before = estimator.planes();
    const auto states = estimator.addFrame(features, k == 0 ? std::vector<ImuSample>{} : samples);
    if (states.size() == 1 && !states.back().keyframe) {
      ++run.between_keyframes;
      run.between_keyframes_moving_planes += anyPlaneMoved(planes_before, estimator.planes());
    }
    StampedPose gt;
    gt.t = t;
    gt.p = sim.state(t).p;
    gt.q = Eigen::Quaterniond(sim.state(t).R_wb);
    if (!truth.empty()) run.path_length += (gt.p - truth.back().p).norm();
    truth.push_back(gt);
    if (!states.empty()) {
      ++run.tracked_frames;
      run.camera_height_frames += estimator.lastReport().ground_plane >= 0;
      if (run.initialized_at < 0) run.initialized_at = t;
    }
    for (const StateEstimate& state : states) {  // the frame's, or its initialization window's
      if (estimate.empty()) run.first_pose_t = state.t;
      StampedPose e;
      e.t = state.t;
      e.p = Eigen::Vector3d(state.pose[0], state.pose[1], state.pose[2]);
      e.q = Eigen::Quaterniond(state.pose[6], state.pose[3], state.pose[4], state.pose[5]);
      estimate.push_back(e);
      const Eigen::Vector3d up_estimated = e.q.conjugate() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d up_true =
          Eigen::Quaterniond(sim.state(state.t).R_wb).conjugate() * Eigen::Vector3d::UnitZ();
      run.max_tilt_error_deg = std::max(
          run.max_tilt_error_deg, std::acos(std::min(1.0, up_estimated.dot(up_true))) * 180 / M_PI);
    }
  }
  estimator.finishMap();  // as rpvio-slam does at the end
  run.resets = estimator.resets();
  eval::EvalOptions opt;
  opt.align = eval::AlignMode::SE3;
  run.trajectory = eval::evaluate(truth, estimate, opt);
  run.planes =
      eval::evaluatePlaneMap(map.planesMap().confirmedPlanes(),
                             apps::truePlanes(sim.scene(), duration), run.trajectory.alignment);
  return run;
}

TEST(EstimatorOnSimulator, StaticTwentySeconds) {
  const SimulatorRun run = runOnSimulator(0, 20.0);
  const auto& r = run.trajectory;
  const size_t resets = run.resets;
  std::printf("static 20 s: ATE RMSE %.3f m, coverage %.1f%%, resets %zu\n", r.ate.rmse,
              100 * r.coverage, resets);
  // Issue 7's target for the 80 s sequences, ≤ 0.20 m, holds over these 20 s (~50 m): measured
  // 0.046 m (0.097 m before the front-end warped its anchored patches by the planes).
  EXPECT_LT(r.ate.rmse, 0.20);
  EXPECT_GT(r.coverage, 0.85);  // initialization takes the first 2 s
  EXPECT_EQ(resets, 0u);
}

// On C1 the homography's window structure fails at the take-off (the floor, the largest plane, only
// keeps its features for ~8 frames, so the chained PnP loses the far frames); the essential-matrix
// method is then tried on the same window. Without that fallback the planar mode never
// initialized on the 80 s C1 sequence (the take-off is the only scale-observable window).
TEST(EstimatorOnSimulator, PlanarModeInitializesAtTheTakeOffWithOneCharacter) {
  const SimulatorRun run = runOnSimulator(1, 3.0);
  const auto& r = run.trajectory;
  const size_t resets = run.resets;
  const double first_pose_t = run.initialized_at;
  std::printf("C1 3 s: initialized at %.2f s, ATE RMSE %.3f m, resets %zu\n", first_pose_t,
              r.ate.rmse, resets);
  EXPECT_GE(first_pose_t, 1.99);  // a 2 s window is needed
  EXPECT_LE(first_pose_t, 2.2);
  EXPECT_LT(r.ate.rmse, 0.05);  // over the first second of tracking (~2.5 m)
  EXPECT_EQ(resets, 0u);
}

// A camera faster than 20 Hz: the initialization window keeps 2 s of frames, not 41 frames
// (1.4 s at 30 Hz: it never initialized).
TEST(EstimatorOnSimulator, PlanarModeInitializesAtThirtyHertz) {
  RunSetup setup;
  setup.camera_rate = 30;
  const SimulatorRun run = runOnSimulator(0, 3.0, setup);
  std::printf("static 3 s at 30 Hz: initialized at %.2f s, ATE RMSE %.3f m\n", run.initialized_at,
              run.trajectory.ate.rmse);
  EXPECT_GE(run.initialized_at, 1.99);
  EXPECT_LE(run.initialized_at, 2.2);
  EXPECT_LT(run.trajectory.ate.rmse, 0.05);
}

// The car (10 Hz, 0 → 10 m/s, then constant speed: the IMU stops observing the scale): its
// camera's known height above the road holds the scale and the height in the window.
TEST(EstimatorOnSimulator, TheCameraHeightHoldsTheCarsScale) {
  RunSetup setup;
  setup.profile = "car";
  const SimulatorRun with = runOnSimulator(0, 25.0, setup);
  setup.camera_height_sigma = 0;
  const SimulatorRun without = runOnSimulator(0, 25.0, setup);
  const double path = with.path_length;
  std::printf(
      "car 25 s (%.0f m): ATE RMSE %.3f m with the camera-height factor, %.3f m "
      "without; first pose at %.2f s\n",
      path, with.trajectory.ate.rmse, without.trajectory.ate.rmse, with.first_pose_t);
  EXPECT_LT(with.trajectory.ate.rmse, 0.005 * path);  // issue #36's target
  EXPECT_LT(with.trajectory.ate.rmse, 0.5 * without.trajectory.ate.rmse);
  // The road is the window's ground all along; never without the factor.
  EXPECT_GT(with.camera_height_frames, 0.95 * with.tracked_frames);
  EXPECT_EQ(without.camera_height_frames, 0u);
  EXPECT_EQ(with.resets, 0u);
}

// A car at constant heading cannot tell its tilt from a horizontal accelerometer bias; without a
// prior on the bias the first window solves walked along that direction (10° of roll against
// 1.1 m/s² of bias on the 60 s car, until the turn at 26 s).
TEST(EstimatorOnSimulator, TheAccelBiasPriorKeepsTheCarsTilt) {
  RunSetup setup;
  setup.profile = "car";
  const SimulatorRun with = runOnSimulator(0, 25.0, setup);
  setup.accel_bias_prior_sigma = 0;
  const SimulatorRun without = runOnSimulator(0, 25.0, setup);
  std::printf(
      "car 25 s (%.0f m): tilt error at most %.2f deg with the bias prior, %.2f deg "
      "without; ATE RMSE %.3f / %.3f m\n",
      with.path_length, with.max_tilt_error_deg, without.max_tilt_error_deg,
      with.trajectory.ate.rmse, without.trajectory.ate.rmse);
  EXPECT_LT(with.max_tilt_error_deg, 1.0);
  EXPECT_LT(with.max_tilt_error_deg, 0.25 * without.max_tilt_error_deg);
  EXPECT_LT(with.trajectory.ate.rmse, 0.005 * with.path_length);  // issue #36's target
  EXPECT_EQ(with.resets, 0u);
}

// Between keyframes only the two newest frames are solved (the window, its depths and planes held):
// the planes do not move then, and the trajectory is as accurate as with the whole window solved
// on every frame.
TEST(EstimatorOnSimulator, BetweenKeyframesOnlyTheNewestFramesAreSolved) {
  RunSetup setup;
  const SimulatorRun motion_only = runOnSimulator(4, 20.0, setup);
  setup.motion_only_between_keyframes = false;
  const SimulatorRun whole_window = runOnSimulator(4, 20.0, setup);
  std::printf(
      "C4 20 s: ATE RMSE %.4f m with motion-only solves between keyframes (%zu of %zu frames), "
      "%.4f m with the whole window solved on every frame\n",
      motion_only.trajectory.ate.rmse, motion_only.between_keyframes, motion_only.tracked_frames,
      whole_window.trajectory.ate.rmse);
  EXPECT_GT(motion_only.between_keyframes, motion_only.tracked_frames / 3);
  EXPECT_EQ(motion_only.between_keyframes_moving_planes, 0u);
  EXPECT_GT(whole_window.between_keyframes_moving_planes, whole_window.between_keyframes / 2);
  EXPECT_LT(motion_only.trajectory.ate.rmse, 1.25 * whole_window.trajectory.ate.rmse);
  EXPECT_GT(motion_only.trajectory.coverage, 0.85);
  EXPECT_EQ(motion_only.resets, 0u);
}

// rpvio-auto: no masks; the planes it discovers carry the estimator from the take-off on.
TEST(EstimatorOnSimulator, AutoModeFindsItsPlanesAndTracksWithoutMasks) {
  RunSetup setup;
  setup.discover_planes = true;
  const SimulatorRun run = runOnSimulator(1, 20.0, setup);
  std::printf("C1 20 s, rpvio-auto: initialized at %.2f s, ATE RMSE %.3f m, resets %zu\n",
              run.initialized_at, run.trajectory.ate.rmse, run.resets);
  EXPECT_GE(run.initialized_at, 2.49);  // a 2.5 s window
  EXPECT_LE(run.initialized_at, 3.0);
  // Measured 0.038 m (rpvio-single: 0.03–0.05 m; 0.044 m before discover_adopt_young, 0.082 m
  // before the plane test followed the tracks' noise, discover_plane_sigmas). Issue #34's target
  // on the 80 s sequences: 0.08 m.
  EXPECT_LT(run.trajectory.ate.rmse, 0.08);
  EXPECT_EQ(run.resets, 0u);
}

// rpvio-multi with plane verification on the hard profile's moving planar objects: the pallet
// trucks' small faces, too small to be judged, get no homography factors and no map entry.
// Measured 0.050 m and none; with homography factors on unjudged planes too, 0.176 m and 2.
TEST(EstimatorOnSimulator, PlanesNeverJudgedStaticStayOutOfTheMap) {
  RunSetup setup;
  setup.homography = HomographyPlanes::kAll;
  setup.profile = "hard";
  setup.moving_objects = true;
  setup.verify_planes = true;
  const SimulatorRun run = runOnSimulator(0, 20.0, setup);
  std::printf("hard MP 20 s, rpvio-multi: ATE RMSE %.3f m, map entries on moving objects %zu\n",
              run.trajectory.ate.rmse, run.planes.on_moving);
  EXPECT_EQ(run.planes.on_moving, 0u);
  EXPECT_LT(run.trajectory.ate.rmse, 0.10);
}

// The plane map's covariances (the windows' information, fused over visits) against the truth,
// every plane in the estimator (rpvio-multi): errors within 3 sigma, and sigmas that say something
// (not vacuously large).
TEST(EstimatorOnSimulator, PlaneMapCovariancesAreConsistent) {
  const SimulatorRun run = runOnSimulator(0, 20.0, {HomographyPlanes::kAll});
  ASSERT_GE(run.planes.planes.size(), 4u);
  std::vector<double> normal_sigmas;
  for (const auto& p : run.planes.planes) {
    std::printf("plane %3d: normal %.2f deg (sigma %.2f), offset %.3f m (sigma %.3f)\n", p.true_id,
                p.normal_error_deg, p.normal_sigma_deg, p.distance_error_m, p.distance_sigma_m);
    EXPECT_LT(p.normal_error_deg, 3 * p.normal_sigma_deg) << "plane " << p.true_id;
    EXPECT_LT(p.distance_error_m, 3 * p.distance_sigma_m) << "plane " << p.true_id;
    normal_sigmas.push_back(p.normal_sigma_deg);
  }
  std::sort(normal_sigmas.begin(), normal_sigmas.end());
  EXPECT_LT(normal_sigmas[normal_sigmas.size() / 2],
            1.0);  // the floor and walls: fractions of a degree
}

}  // namespace
}  // namespace rpvio
