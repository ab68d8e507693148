#pragma once
// A bag-of-words vocabulary for 256-bit binary descriptors (ORB): a tree of k-majority clusters
// (Gálvez-López & Tardós, "Bags of Binary Words", T-RO 2012). A descriptor's word is the leaf
// reached by descending to the nearest centre (Hamming distance) at each level; a word's weight is
// its inverse document frequency over the training images, idf_w = ln(N / n_w).
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace rpvio {

/// Sparse, L1-normalized tf-idf weights by word id, sorted by word.
using BowVector = std::vector<std::pair<int, double>>;

/// Similarity of two L1-normalized BoW vectors: 1 − ½‖a − b‖₁, in [0, 1] (DBoW2's L1 score).
double bowScore(const BowVector& a, const BowVector& b);

struct VocabularyOptions {
  int branching = 10;  // k: children per node
  int depth = 3;       // levels: up to k^depth words
  int iterations = 8;  // k-majority assignment rounds per node
};

class BinaryVocabulary {
 public:
  static constexpr int kDescriptorBytes = 32;

  /// Trains on `images`, one matrix of descriptors (rows of 32 CV_8U bytes) per image. Seeding by
  /// k-means++ with a fixed seed: the same input gives the same vocabulary.
  static BinaryVocabulary train(const std::vector<cv::Mat>& images,
                                const VocabularyOptions& options);

  bool empty() const { return words_ == 0; }
  int words() const { return words_; }
  /// The word of one descriptor (32 bytes).
  int word(const uint8_t* descriptor) const;
  /// The image's tf-idf vector, L1-normalized; empty without descriptors.
  BowVector transform(const cv::Mat& descriptors) const;

 private:
  using Centre = std::array<uint8_t, kDescriptorBytes>;
  struct Node {
    Centre centre{};
    std::vector<int> children;  // node indices; empty at a leaf
    int word = -1;              // leaves only
  };
  void grow(int node, const std::vector<const uint8_t*>& descriptors, int level,
            const VocabularyOptions& options, uint32_t seed);

  std::vector<Node> nodes_;  // nodes_[0]: the root, without a centre
  std::vector<double> idf_;  // by word
  int words_ = 0;
};

}  // namespace rpvio
