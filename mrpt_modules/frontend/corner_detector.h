#pragma once
// Shi–Tomasi corners (Shi & Tomasi 1994), the exact selection of cv::goodFeaturesToTrack (block
// 3, Sobel aperture 3, no Harris), with its image-sized buffers kept between calls. OpenCV
// allocates ~8 MB of temporaries per call at 640x480; freed at the top of the heap they are
// returned to the kernel and faulted in again every frame, which cost more than the arithmetic
// inside rpvio-slam.
#include <array>
#include <opencv2/core.hpp>
#include <vector>

namespace rpvio {

class CornerDetector {
 public:
  /// The `max_corners` strongest corners of `image` (CV_8UC1) where `allowed` (CV_8UC1, same
  /// size) is non-zero, strongest first: 3x3 local maxima of the minimum eigenvalue above
  /// `quality_level` times the strongest allowed one, each at least `min_distance` px from every
  /// stronger accepted corner (min_distance >= 1). Same corners, same order as
  /// cv::goodFeaturesToTrack(image, corners, max_corners, quality_level, min_distance, allowed).
  std::vector<cv::Point2f> detect(const cv::Mat& image, const cv::Mat& allowed, int max_corners,
                                  double quality_level, double min_distance);

 private:
  struct Candidate {
    float response;
    int index;  // y * width + x
  };
  struct Span {
    int begin, end;  // columns [begin, end)
  };
  /// Column spans per image row, row y's in spans[first[y] .. first[y + 1]).
  struct RowSpans {
    std::vector<int> first;
    std::vector<Span> spans;
    struct Range {
      const Span *from, *to;
      const Span* begin() const { return from; }
      const Span* end() const { return to; }
      bool empty() const { return from == to; }
    };
    Range of(int y) const { return {spans.data() + first[y], spans.data() + first[y + 1]}; }
  };
  static constexpr int kChunk = 16;  // columns: the granularity of the spans
  /// The spans (of kChunk-column chunks) where responses and gradient products are needed to
  /// test the allowed pixels.
  void findSpans(const cv::Mat& allowed);
  /// Fills min_eigenvalue_; returns the strongest response where `allowed` (0 if none is positive).
  float computeMinEigenvalues(const cv::Mat& image, const cv::Mat& allowed);
  void collectLocalMaxima(const cv::Mat& allowed, float threshold);
  /// Greedy over the candidates, strongest first: keeps those min_distance from every kept one.
  std::vector<cv::Point2f> takeStrongestSpaced(cv::Size size, int max_corners, double min_distance);

  cv::Mat dx_, dy_, min_eigenvalue_;                // CV_32F
  std::array<std::vector<float>, 3> product_rows_;  // gx², gx·gy, gy² of three rows
  std::array<std::vector<double>, 3> column_sums_;  // of product_rows_ over 3 rows, padded by 1
  std::vector<uint8_t> near_allowed_, within_one_row_, within_two_rows_;  // per row and chunk
  RowSpans responses_, products_;
  std::vector<Candidate> candidates_;
  std::vector<float> column_maxima_;            // of one row's 3x1 neighbourhoods
  std::vector<uint8_t> is_candidate_;           // one row's local maxima above the threshold
  std::vector<std::vector<cv::Point2f>> grid_;  // accepted corners per min_distance cell
};

}  // namespace rpvio
