// The tests' independent reference for linear solves: dense Gaussian
// elimination without pivoting (the matrices tested are symmetric positive
// definite), written plainly so that it shares nothing with the library.
#pragma once

#include <cstddef>
#include <vector>

namespace barimpact::testing {

using DenseMatrix = std::vector<std::vector<double>>;

inline std::vector<double> dense_solve(DenseMatrix m, std::vector<double> r) {
  const std::size_t n = r.size();
  for (std::size_t c = 0; c < n; ++c)
    for (std::size_t i = c + 1; i < n; ++i) {
      const double f = m[i][c] / m[c][c];
      for (std::size_t j = c; j < n; ++j) m[i][j] -= f * m[c][j];
      r[i] -= f * r[c];
    }
  std::vector<double> x(n);
  for (std::size_t i = n; i-- > 0;) {
    double s = r[i];
    for (std::size_t j = i + 1; j < n; ++j) s -= m[i][j] * x[j];
    x[i] = s / m[i][i];
  }
  return x;
}

}  // namespace barimpact::testing
