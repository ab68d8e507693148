#pragma once
// Marginalization (VINS-Mono §VI-A; Sibley et al. 2010): the factors that touch the states to
// remove are linearized at the current estimate, the removed blocks are eliminated by the Schur
// complement, and what remains is a linear prior on the other blocks,
//   r(x) = r0 + J (x ⊟ x0),
// with ⊟ the manifold minus (PoseManifold for 7-number pose blocks, Euclidean otherwise).
// Blocks are identified by their address; a block of 7 numbers is a pose ([p, q], right
// perturbation, parameter_blocks.h), every other block is Euclidean.
#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <Eigen/Core>
#include <memory>
#include <set>
#include <vector>

namespace rpvio {

/// The linear prior left by a marginalization on the kept blocks (in the order of blocks()).
struct MarginalizationPrior {
  std::vector<double*> blocks;
  std::vector<int> sizes;               // ambient sizes
  std::vector<std::vector<double>> x0;  // linearization point
  Eigen::MatrixXd J;                    // rows x total tangent size
  Eigen::VectorXd r0;

  bool involves(const double* block) const;
};

/// The prior as a Ceres cost function on prior->blocks (each problem owns its own factor; the
/// prior is shared).
class MarginalizationFactor : public ceres::CostFunction {
 public:
  explicit MarginalizationFactor(std::shared_ptr<const MarginalizationPrior> prior);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::shared_ptr<const MarginalizationPrior> prior_;
  std::vector<int> offsets_;  // tangent offset of each block
};

/// Collects linearized factors, then eliminates a set of blocks.
class Marginalizer {
 public:
  /// A factor evaluated at the blocks' current values (loss may be null).
  void addFactor(std::unique_ptr<ceres::CostFunction> cost,
                 std::shared_ptr<ceres::LossFunction> loss, std::vector<double*> blocks);
  /// A block held constant in the optimization (e.g. a fixed extrinsic): neither removed nor kept.
  void setConstant(const double* block) { constant_.insert(block); }
  /// The prior on the blocks the factors connect to the removed ones, or nullptr when no kept
  /// block remains. Factors not touching a removed block are ignored.
  std::shared_ptr<const MarginalizationPrior> marginalize(
      const std::set<const double*>& remove) const;

 private:
  struct Factor {
    std::unique_ptr<ceres::CostFunction> cost;
    std::shared_ptr<ceres::LossFunction> loss;
    std::vector<double*> blocks;
  };
  std::vector<Factor> factors_;
  std::set<const double*> constant_;
};

}  // namespace rpvio
