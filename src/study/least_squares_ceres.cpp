// The fitting module: least_squares.hpp's problems solved by Ceres Solver,
// built as a module of its own (it needs no symbol of the library: the
// residual blocks are called through their virtual functions).
#include <ceres/ceres.h>

#include <cmath>

#include "least_squares.hpp"

namespace barimpact::detail {

namespace {

// A residual block as Ceres' cost function of the one parameter block x.
class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const ResidualBlock& block, std::size_t parameters) : block_(block) {
    set_num_residuals(static_cast<int>(block.residuals()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(parameters));
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return block_.evaluate(parameters[0], residuals, jacobians != nullptr ? jacobians[0] : nullptr);
  }

 private:
  const ResidualBlock& block_;
};

// Ends the solve at its next iteration once `interrupt` is set (a signal).
class StopOnSignal final : public ceres::IterationCallback {
 public:
  explicit StopOnSignal(const std::atomic<bool>* interrupt) : interrupt_(interrupt) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return interrupt_ != nullptr && interrupt_->load() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::atomic<bool>* interrupt_;
};

LeastSquaresSummary solve(const LeastSquaresProblem& p, double* x) {
  ceres::Problem problem;
  for (const ResidualBlock* block : p.blocks) problem.AddResidualBlock(new BlockCost(*block, p.parameters), nullptr, x);
  for (std::size_t k = 0; k < p.parameters; ++k) {
    if (std::isfinite(p.lower[k])) problem.SetParameterLowerBound(x, static_cast<int>(k), p.lower[k]);
    if (std::isfinite(p.upper[k])) problem.SetParameterUpperBound(x, static_cast<int>(k), p.upper[k]);
  }
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = p.max_iterations;
  options.function_tolerance = p.function_tolerance;
  options.parameter_tolerance = p.parameter_tolerance;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  StopOnSignal stop(p.interrupt);
  options.callbacks.push_back(&stop);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return {summary.iterations.size(), summary.termination_type == ceres::CONVERGENCE, summary.message,
          summary.final_cost};
}

}  // namespace

}  // namespace barimpact::detail

extern "C" __attribute__((visibility("default"))) const barimpact::detail::FitModule* barimpact_fit_module() {
  static const barimpact::detail::FitModule module{barimpact::detail::solve};
  return &module;
}
