// Which true planes a sequence shows for more than 2 s, and which of those a plane map lacks
// (issue 8's "every plane seen for more than 2 s is in the map").
#include <gtest/gtest.h>

#include "evaluation/plane_visibility.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "planes_map/plane_map_exporters.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

/// A 20x10 mask: `label` on its first `pixels` pixels (row-major), 0 elsewhere.
cv::Mat maskWith(int label, int pixels) {
  cv::Mat m(10, 20, CV_8U, cv::Scalar(0));
  for (int k = 0; k < pixels; ++k) m.at<uint8_t>(k / 20, k % 20) = static_cast<uint8_t>(label);
  return m;
}

TEST(PlaneVisibility, CountsFramesWhereALabelCoversEnoughPixels) {
  eval::PlaneVisibility visibility(100, 0);  // no margin: every pixel of a plane is trackable
  double t = 0;
  for (int k = 0; k < 60; ++k) {
    // One frame dropped (a 0.1 s gap): the frame interval is still the median, 0.05 s.
    t += k == 30 ? 0.1 : 0.05;
    cv::Mat m = maskWith(3, k < 50 ? 100 : 99);  // label 3: 50 frames at 100 px, then 99
    if (k < 20) m.at<uint8_t>(9, 19) = 4;        // label 4: one pixel, 20 frames
    visibility.addMask(t, m);
  }
  const auto seconds = visibility.seconds();
  ASSERT_EQ(seconds.count(3), 1u);
  EXPECT_NEAR(seconds.at(3).seen_s, 50 * 0.05, 1e-9);
  EXPECT_NEAR(seconds.at(3).trackable_s, 50 * 0.05, 1e-9);
  EXPECT_EQ(seconds.count(4), 0u);  // below 100 px: never seen
  EXPECT_EQ(seconds.count(0), 0u);  // 0: not a plane
}

TEST(PlaneVisibility, ASmallFaceIsSeenButHasNoRoomForTenTracks) {
  // The tracker's default margin and spacing: 10 px, 10 KLT windows of 21 px.
  const TrackerOptions tracker;
  ASSERT_EQ(tracker.window_margin, 10);
  ASSERT_EQ(eval::minVisiblePlanePixels(tracker.klt_window), 4410);
  // Label 5: a 70 px square (4900 px), 50 x 50 px away from the background's 10 px margin.
  // Label 6: a 90 px square, 70 x 70 = 4900 px trackable.
  cv::Mat m(200, 200, CV_8U, cv::Scalar(0));
  m(cv::Rect(10, 10, 70, 70)) = 5;
  m(cv::Rect(100, 100, 90, 90)) = 6;
  eval::PlaneVisibility visibility(eval::minVisiblePlanePixels(tracker.klt_window),
                                   tracker.window_margin);
  for (int k = 0; k < 40; ++k) visibility.addMask(0.05 * k, m);
  const auto seconds = visibility.seconds();
  EXPECT_NEAR(seconds.at(5).seen_s, 2.0, 1e-9);
  EXPECT_EQ(seconds.at(5).trackable_s, 0.0);
  EXPECT_NEAR(seconds.at(6).seen_s, 2.0, 1e-9);
  EXPECT_NEAR(seconds.at(6).trackable_s, 2.0, 1e-9);
}

TEST(PlaneVisibility, MissingPlanesAreTheLongVisibleOnesWithoutAnEntry) {
  std::vector<Plane> truth(5);
  for (int k = 0; k < 5; ++k) truth[k].id = k + 1;
  eval::PlaneMapAccuracy accuracy;
  accuracy.planes.resize(1);
  accuracy.planes[0].true_id = 1;
  const std::map<int, eval::LabelVisibility> visible = {
      {1, {10.0, 10.0}}, {2, {2.5, 2.5}}, {3, {2.0, 2.0}}, {5, {7.5, 1.0}}, {9, {30.0, 30.0}}};
  const auto missing = eval::missingPlanes(accuracy, truth, visible);
  // 1 is in the map, 3 not more than 2 s, 4 never, 9 no plane; 5 seen but not trackable.
  ASSERT_EQ(missing.missing.size(), 1u);
  EXPECT_EQ(missing.missing[0].true_id, 2);
  EXPECT_DOUBLE_EQ(missing.missing[0].visible.trackable_s, 2.5);
  ASSERT_EQ(missing.untrackable.size(), 1u);
  EXPECT_EQ(missing.untrackable[0].true_id, 5);
  EXPECT_DOUBLE_EQ(missing.untrackable[0].visible.seen_s, 7.5);
}

TEST(PlaneVisibility, EvalAppNamesATruePlaneTheMapLacks) {
  test::TempDir dir;
  std::string out;
  ASSERT_EQ(
      test::runCommand(
          test::binDir() + "/rpvio-sim --characters 0 --duration 3 --out " + dir.file("seq"), out),
      0)
      << out;
  // The map is the truth without the floor (id 1), which is in view the whole 3 s.
  std::vector<Plane> map = readPlanesYaml(dir.file("seq/groundtruth_planes.yaml"));
  ASSERT_EQ(map.front().id, 1);
  map.erase(map.begin());
  writePlanesYaml(dir.file("map.yaml"), map);
  const std::string gt = dir.file("seq/groundtruth.tum");
  const std::string planes = " --planes " + dir.file("map.yaml") + " --gt-planes " +
                             dir.file("seq/groundtruth_planes.yaml");
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-eval --gt " + gt + " --est " + gt + planes +
                                 " --rawlog " + dir.file("seq/seq.rawlog") + " --json " +
                                 dir.file("r.json"),
                             out),
            0)
      << out;
  EXPECT_NE(out.find("have no map entry: 1 ("), std::string::npos) << out;
  const std::string json = test::readFile(dir.file("r.json"));
  EXPECT_NE(json.find("\"missing\": [{\"id\": 1, \"seen_s\": "), std::string::npos) << json;
  // The floor is trackable, and every other true plane has an entry.
  EXPECT_NE(json.find("\"untrackable\": []"), std::string::npos) << json;
  // With a mode whose tracker keeps 300 px from other labels, nothing is trackable: the floor is
  // seen only.
  test::writeText(dir.file("wide.ini"), "[FeatureTrackerModule]\nwindow_margin = 300\n");
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-eval --gt " + gt + " --est " + gt + planes +
                                 " --rawlog " + dir.file("seq/seq.rawlog") + " --config " +
                                 dir.file("wide.ini") + " --json " + dir.file("w.json"),
                             out),
            0)
      << out;
  const std::string wide = test::readFile(dir.file("w.json"));
  EXPECT_NE(wide.find("\"missing\": []"), std::string::npos) << wide;
  EXPECT_NE(wide.find("\"untrackable\": [{\"id\": 1, "), std::string::npos) << wide;
  // --rawlog without a plane map is a usage error; a missing rawlog an input error naming it.
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-eval --gt " + gt + " --est " + gt +
                                 " --rawlog " + dir.file("seq/seq.rawlog"),
                             out),
            2)
      << out;
  EXPECT_NE(test::runCommand(test::binDir() + "/rpvio-eval --gt " + gt + " --est " + gt + planes +
                                 " --rawlog " + dir.file("none.rawlog"),
                             out),
            0);
  EXPECT_NE(out.find(dir.file("none.rawlog")), std::string::npos) << out;
}

}  // namespace
}  // namespace rpvio
