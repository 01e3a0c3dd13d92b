// A bounded nonlinear least-squares problem and its solver (internal to
// src/): signal matching states its fit here (match.cpp); Ceres Solver
// solves it in the fitting module (least_squares_ceres.cpp), a module of
// its own that the library loads (dlopen) the first time a match fits
// (least_squares_loader.cpp), so that a process that never matches loads
// neither Ceres nor the ~19 libraries it pulls in.
#pragma once

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

namespace barimpact::detail {

/// Residuals r(x) of all the problem's parameters.
class ResidualBlock {
 public:
  virtual ~ResidualBlock() = default;
  /// How many residuals the block has.
  [[nodiscard]] virtual std::size_t residuals() const = 0;
  /// The residuals at `x`, and where `jacobian` is not null their
  /// Jacobian, row-major (residual by parameter). False: not computable at `x`.
  virtual bool evaluate(const double* x, double* residuals, double* jacobian) const = 0;
};

/// min 1/2 sum |r_b(x)|^2 over the blocks, lower <= x <= upper.
struct LeastSquaresProblem {
  std::size_t parameters = 0;
  std::vector<const ResidualBlock*> blocks;  ///< the caller's, in order
  std::vector<double> lower, upper;          ///< each parameter's bounds; infinite: none
  /// Levenberg-Marquardt's trust region, dense QR, silent; these limits.
  int max_iterations = 60;
  double function_tolerance = 1e-9;
  double parameter_tolerance = 1e-8;
  /// Once set (a signal), the solve ends at its next iteration.
  const std::atomic<bool>* interrupt = nullptr;
};

struct LeastSquaresSummary {
  std::size_t iterations = 0;  ///< the iterations' records, the start's included
  bool converged = false;      ///< within a tolerance (not out of iterations, nor aborted)
  std::string message;
  double final_cost = 0.0;  ///< 1/2 sum r^2 at the solution
};

/// Loads the fitting module, once per process: MissingModule (one line)
/// if it cannot be. Before the threads that solve (which must not throw).
void load_least_squares();

/// Solves `p` from `x` (p.parameters values), leaving the solution there:
/// the fitting module's (load_least_squares).
LeastSquaresSummary solve_least_squares(const LeastSquaresProblem& p, double* x);

struct FitModule {
  LeastSquaresSummary (*solve)(const LeastSquaresProblem& p, double* x);
};

/// The module's one exported symbol.
inline constexpr const char* fit_module_entry = "barimpact_fit_module";

}  // namespace barimpact::detail

extern "C" const barimpact::detail::FitModule* barimpact_fit_module();
