#include "mrpt_modules/loop/binary_vocabulary.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/core/hal/hal.hpp>
#include <random>
#include <set>

namespace rpvio {
namespace {

int hamming(const uint8_t* a, const uint8_t* b) {
  return cv::hal::normHamming(a, b, BinaryVocabulary::kDescriptorBytes);
}

/// The bitwise majority of the members (a tie gives 0).
std::array<uint8_t, BinaryVocabulary::kDescriptorBytes> majority(
    const std::vector<const uint8_t*>& members) {
  std::array<uint8_t, BinaryVocabulary::kDescriptorBytes> centre{};
  for (int byte = 0; byte < BinaryVocabulary::kDescriptorBytes; ++byte)
    for (int bit = 0; bit < 8; ++bit) {
      size_t ones = 0;
      for (const uint8_t* m : members) ones += (m[byte] >> bit) & 1;
      if (2 * ones > members.size()) centre[byte] |= static_cast<uint8_t>(1 << bit);
    }
  return centre;
}

/// k-means++ seeding (Arthur & Vassilvitskii 2007) with Hamming distances: fewer than k centres
/// when the descriptors hold fewer distinct values.
std::vector<std::array<uint8_t, BinaryVocabulary::kDescriptorBytes>> seedCentres(
    const std::vector<const uint8_t*>& descriptors, int k, std::mt19937& rng) {
  std::vector<std::array<uint8_t, BinaryVocabulary::kDescriptorBytes>> centres;
  auto add = [&](const uint8_t* d) {
    centres.emplace_back();
    std::copy(d, d + BinaryVocabulary::kDescriptorBytes, centres.back().begin());
  };
  add(descriptors[std::uniform_int_distribution<size_t>(0, descriptors.size() - 1)(rng)]);
  std::vector<double> nearest(descriptors.size());
  for (size_t i = 0; i < descriptors.size(); ++i)
    nearest[i] = hamming(descriptors[i], centres[0].data());
  while (static_cast<int>(centres.size()) < k) {
    std::vector<double> weights(nearest.size());
    std::transform(nearest.begin(), nearest.end(), weights.begin(), [](double d) { return d * d; });
    if (*std::max_element(weights.begin(), weights.end()) == 0) break;
    const size_t pick = std::discrete_distribution<size_t>(weights.begin(), weights.end())(rng);
    add(descriptors[pick]);
    for (size_t i = 0; i < descriptors.size(); ++i)
      nearest[i] = std::min<double>(nearest[i], hamming(descriptors[i], centres.back().data()));
  }
  return centres;
}

}  // namespace

double bowScore(const BowVector& a, const BowVector& b) {
  // For L1-normalized non-negative vectors 1 − ½‖a − b‖₁ = Σ over common words of min(a_w, b_w).
  double score = 0;
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (i->first < j->first) {
      ++i;
    } else if (j->first < i->first) {
      ++j;
    } else {
      score += std::min(i->second, j->second);
      ++i, ++j;
    }
  }
  return score;
}

BinaryVocabulary BinaryVocabulary::train(const std::vector<cv::Mat>& images,
                                         const VocabularyOptions& options) {
  BinaryVocabulary vocabulary;
  std::vector<const uint8_t*> all;
  for (const cv::Mat& d : images) {
    CV_Assert(d.empty() || (d.type() == CV_8U && d.cols == kDescriptorBytes));
    for (int r = 0; r < d.rows; ++r) all.push_back(d.ptr<uint8_t>(r));
  }
  if (all.empty()) return vocabulary;
  vocabulary.nodes_.emplace_back();
  std::mt19937 rng(1);
  vocabulary.grow(0, all, 0, options, rng());
  // idf_w = ln(N / n_w), n_w: training images holding word w.
  std::vector<int> images_with(vocabulary.words_, 0);
  for (const cv::Mat& d : images) {
    std::set<int> seen;
    for (int r = 0; r < d.rows; ++r) seen.insert(vocabulary.word(d.ptr<uint8_t>(r)));
    for (int w : seen) ++images_with[w];
  }
  vocabulary.idf_.resize(vocabulary.words_);
  for (int w = 0; w < vocabulary.words_; ++w)
    vocabulary.idf_[w] = std::log(static_cast<double>(images.size()) / std::max(images_with[w], 1));
  return vocabulary;
}

void BinaryVocabulary::grow(int node, const std::vector<const uint8_t*>& descriptors, int level,
                            const VocabularyOptions& options, uint32_t seed) {
  auto makeLeaf = [&] { nodes_[node].word = words_++; };
  if (level == options.depth || descriptors.size() <= 1) return makeLeaf();
  std::mt19937 rng(seed);
  auto centres = seedCentres(descriptors, options.branching, rng);
  if (centres.size() < 2) return makeLeaf();
  // k-majority: assign each descriptor to its nearest centre, move each centre to its members'
  // bitwise majority, until no assignment changes.
  std::vector<int> cluster(descriptors.size(), -1);
  for (int round = 0; round < options.iterations; ++round) {
    bool changed = false;
    for (size_t i = 0; i < descriptors.size(); ++i) {
      int best = 0;
      int best_distance = hamming(descriptors[i], centres[0].data());
      for (size_t c = 1; c < centres.size(); ++c) {
        const int distance = hamming(descriptors[i], centres[c].data());
        if (distance < best_distance) best = static_cast<int>(c), best_distance = distance;
      }
      changed |= cluster[i] != best;
      cluster[i] = best;
    }
    if (!changed) break;
    for (size_t c = 0; c < centres.size(); ++c) {
      std::vector<const uint8_t*> members;
      for (size_t i = 0; i < descriptors.size(); ++i)
        if (cluster[i] == static_cast<int>(c)) members.push_back(descriptors[i]);
      if (!members.empty()) centres[c] = majority(members);
    }
  }
  std::vector<std::vector<const uint8_t*>> members(centres.size());
  for (size_t i = 0; i < descriptors.size(); ++i) members[cluster[i]].push_back(descriptors[i]);
  for (size_t c = 0; c < centres.size(); ++c) {
    if (members[c].empty()) continue;
    const int child = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_[child].centre = centres[c];
    nodes_[node].children.push_back(child);
    grow(child, members[c], level + 1, options, static_cast<uint32_t>(rng()));
  }
}

int BinaryVocabulary::word(const uint8_t* descriptor) const {
  int node = 0;
  while (!nodes_[node].children.empty()) {
    int best = -1;
    int best_distance = 257;
    for (int child : nodes_[node].children) {
      const int distance = hamming(descriptor, nodes_[child].centre.data());
      if (distance < best_distance) best = child, best_distance = distance;
    }
    node = best;
  }
  return nodes_[node].word;
}

BowVector BinaryVocabulary::transform(const cv::Mat& descriptors) const {
  std::map<int, int> counts;
  for (int r = 0; r < descriptors.rows; ++r) ++counts[word(descriptors.ptr<uint8_t>(r))];
  BowVector bow;
  double sum = 0;
  for (const auto& [w, n] : counts) {
    const double weight = n * idf_[w] / descriptors.rows;  // tf · idf
    if (weight <= 0) continue;
    bow.emplace_back(w, weight);
    sum += weight;
  }
  for (auto& entry : bow) entry.second /= sum;
  return bow;
}

}  // namespace rpvio
