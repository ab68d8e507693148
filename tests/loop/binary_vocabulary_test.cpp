// The bag-of-words vocabulary and database against descriptors whose clusters are known.
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/loop/binary_vocabulary.h"
#include "mrpt_modules/loop/keyframe_database.h"

namespace rpvio {
namespace {

/// `prototypes` random 256-bit descriptors; each image holds `copies` copies of some of them with
/// up to `flips` bits flipped.
struct Clusters {
  std::vector<cv::Mat> prototypes;
  std::mt19937 rng{7};

  explicit Clusters(int n) {
    for (int i = 0; i < n; ++i) {
      cv::Mat d(1, 32, CV_8U);
      for (int b = 0; b < 32; ++b) d.at<uint8_t>(b) = static_cast<uint8_t>(rng());
      prototypes.push_back(d);
    }
  }
  cv::Mat noisyCopy(int prototype, int flips) {
    cv::Mat d = prototypes[prototype].clone();
    for (int f = 0; f < flips; ++f) {
      const int bit = static_cast<int>(rng() % 256);
      d.at<uint8_t>(bit / 8) ^= static_cast<uint8_t>(1 << (bit % 8));
    }
    return d;
  }
  cv::Mat image(const std::vector<int>& which, int copies, int flips) {
    cv::Mat out;
    for (int p : which)
      for (int c = 0; c < copies; ++c) out.push_back(noisyCopy(p, flips));
    return out;
  }
};

TEST(BinaryVocabulary, NoisyCopiesOfOneDescriptorShareAWordAndOthersDoNot) {
  Clusters clusters(40);
  std::vector<cv::Mat> images;
  for (int i = 0; i < 8; ++i) {
    std::vector<int> which;
    for (int p = i * 5; p < i * 5 + 5; ++p) which.push_back(p);
    images.push_back(clusters.image(which, 20, 8));
  }
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(images, {8, 2, 10});
  ASSERT_GE(vocabulary.words(), 40);
  std::vector<int> word_of(40);
  int same = 0, total = 0;
  for (int p = 0; p < 40; ++p) {
    word_of[p] = vocabulary.word(clusters.prototypes[p].ptr<uint8_t>());
    for (int c = 0; c < 10; ++c, ++total)
      same += vocabulary.word(clusters.noisyCopy(p, 8).ptr<uint8_t>()) == word_of[p];
  }
  // 8 of 256 bits flipped: ~96 bits from any other prototype, so nearly always the same word.
  EXPECT_GE(same, total * 95 / 100);
  std::sort(word_of.begin(), word_of.end());
  EXPECT_EQ(std::unique(word_of.begin(), word_of.end()) - word_of.begin(), 40)
      << "two prototypes share a word";
}

TEST(BinaryVocabulary, TheSameTrainingGivesTheSameWords) {
  Clusters clusters(30);
  std::vector<cv::Mat> images{clusters.image({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, 10, 10),
                              clusters.image({10, 11, 12, 13, 14, 15, 16, 17, 18, 19}, 10, 10),
                              clusters.image({20, 21, 22, 23, 24, 25, 26, 27, 28, 29}, 10, 10)};
  const BinaryVocabulary a = BinaryVocabulary::train(images, {});
  const BinaryVocabulary b = BinaryVocabulary::train(images, {});
  ASSERT_EQ(a.words(), b.words());
  for (const cv::Mat& image : images)
    for (int r = 0; r < image.rows; ++r)
      EXPECT_EQ(a.word(image.ptr<uint8_t>(r)), b.word(image.ptr<uint8_t>(r)));
}

TEST(BowScore, OneForTheSameVectorZeroWithoutSharedWordsAndHalfForHalfTheWeight) {
  const BowVector a{{1, 0.5}, {4, 0.5}};
  const BowVector b{{2, 0.25}, {3, 0.75}};
  const BowVector c{{1, 0.5}, {7, 0.5}};
  EXPECT_DOUBLE_EQ(bowScore(a, a), 1.0);
  EXPECT_DOUBLE_EQ(bowScore(a, b), 0.0);
  EXPECT_DOUBLE_EQ(bowScore(a, c), 0.5);  // 1 − ½‖a − c‖₁ = 1 − ½ (0.5 + 0.5)
}

TEST(KeyframeDatabase, TheImageOfTheSamePlaceScoresBestAndNewerKeyframesAreLeftOut) {
  Clusters clusters(60);
  std::vector<cv::Mat> images;
  for (int place = 0; place < 6; ++place) {
    std::vector<int> which;
    for (int p = place * 10; p < place * 10 + 10; ++p) which.push_back(p);
    images.push_back(clusters.image(which, 5, 12));
  }
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(images, {});
  KeyframeDatabase database;
  for (const cv::Mat& image : images) database.add(vocabulary.transform(image));
  // Place 3 seen again (new noise), and half of place 1 with half of place 5.
  const BowVector again =
      vocabulary.transform(clusters.image({30, 31, 32, 33, 34, 35, 36, 37, 38, 39}, 5, 12));
  const auto matches = database.query(again, database.size(), 0.0);
  ASSERT_FALSE(matches.empty());
  EXPECT_EQ(matches.front().keyframe, 3u);
  EXPECT_NEAR(matches.front().score, bowScore(again, database.vector(3)), 1e-12);
  EXPECT_GT(matches.front().score, 0.5);
  for (const auto& m : database.query(again, 3, 0.0)) EXPECT_LT(m.keyframe, 3u);
  const BowVector mixed =
      vocabulary.transform(clusters.image({10, 11, 12, 13, 14, 50, 51, 52, 53, 54}, 5, 12));
  const auto two = database.query(mixed, database.size(), 0.2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(std::min(two[0].keyframe, two[1].keyframe), 1u);
  EXPECT_EQ(std::max(two[0].keyframe, two[1].keyframe), 5u);
}

}  // namespace
}  // namespace rpvio
