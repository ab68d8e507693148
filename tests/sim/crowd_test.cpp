// The hard profile's crowd (issue #40): the fraction of the image moving people cover, measured by
// the simulator itself on the first 20 s, against the targets the profile exists for.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "sim/dynamic_coverage.h"
#include "sim/simulator.h"

namespace rpvio::sim {
namespace {

constexpr double kSpan = 20;  // s

CoverageSummary hardCoverage(int characters, uint64_t seed = 1) {
  SimConfig config = SimConfig::profile("hard");
  config.scene.characters = characters;
  config.seed = seed;
  config.duration = kSpan;
  Simulator sim(config);
  std::vector<CoverageSample> samples;
  for (double t = 0; t < kSpan; t += 0.25) samples.push_back({t, sim.dynamicFraction(t, 4)});
  const CoverageSummary s = summarizeCoverage(samples);
  std::printf("C%d seed %d: median %.3f p90 %.3f peak %.3f first 2 s %.3f mean %.3f\n", characters,
              static_cast<int>(seed), s.median, s.p90, s.peak, s.first_2s_mean, s.mean);
  return s;
}

TEST(Crowd, EightPeopleFillAQuarterOfTheViewFromTheStart) {
  for (uint64_t seed : {1, 2}) {
    const CoverageSummary c8 = hardCoverage(8, seed);
    EXPECT_GE(c8.median, 0.25);
    EXPECT_GE(c8.p90, 0.45);
    EXPECT_GE(c8.first_2s_mean, 0.20);
  }
}

TEST(Crowd, FourPeopleCoverAnEighth) { EXPECT_GE(hardCoverage(4).median, 0.12); }

TEST(Crowd, OnePersonIsSometimesClose) { EXPECT_GE(hardCoverage(1).peak, 0.15); }

TEST(Crowd, CoverageGrowsWithTheCount) {
  double previous = 0;
  for (int n : {0, 1, 2, 4, 6, 8}) {
    const double mean = hardCoverage(n).mean;
    if (n == 0)
      EXPECT_EQ(mean, 0);
    else
      EXPECT_GT(mean, previous) << n << " people";
    previous = mean;
  }
}

/// Walkers move at human speeds while on stage, and come on stage outside the image (no one pops up
/// in view).
TEST(Crowd, PeopleWalkContinuouslyAndEnterFromOutsideTheView) {
  SimConfig config = SimConfig::profile("hard");
  config.scene.characters = 8;
  config.duration = kSpan;
  Simulator sim(config);
  const PinholeCamera cam = config.camera.intrinsics();
  auto outsideImage = [&](double t, const CapsuleFigure& figure) {
    for (const Capsule& part : figure.parts())
      for (const Eigen::Vector3d& end : {part.a, part.b}) {
        const auto px = sim.project(t, end);
        if (!px) continue;
        const double depth = (sim.cameraPose(t).inverse() * end).z();
        const double margin = part.radius * cam.fx / depth;
        if (px->x() > -margin && px->x() < cam.width + margin && px->y() > -margin &&
            px->y() < cam.height + margin)
          return false;
      }
    return true;
  };
  const double dt = 0.05;
  std::vector<Eigen::Vector3d> last(8);
  std::vector<bool> was_on(8, false);
  int entries = 0;
  for (double t = 0; t < kSpan; t += dt) {
    sim.dynamicFraction(t, 64);  // poses the scene at t
    const auto& people = sim.scene().characters();
    ASSERT_EQ(people.size(), 8u);
    for (size_t k = 0; k < people.size(); ++k) {
      const bool on = people[k].onStage();
      if (!on) {
        was_on[k] = false;
        continue;
      }
      const Eigen::Vector3d hip = people[k].figure().parts()[1].a;
      if (was_on[k]) {  // no faster than a jog: 4.5 m/s
        EXPECT_LT((hip - last[k]).norm(), 4.5 * dt) << "person " << k << " at " << t;
      }
      if (!was_on[k] && t > 0) {
        ++entries;
        EXPECT_TRUE(outsideImage(t, people[k].figure())) << "person " << k << " at " << t;
      }
      last[k] = hip, was_on[k] = true;
    }
  }
  EXPECT_GE(entries, 8);  // crossers and the group come and go
}

}  // namespace
}  // namespace rpvio::sim
