#include "barimpact/model/sampled_history.hpp"

namespace barimpact {

double HistoryReader::operator()(double t) const {
  const auto& s = *h_;
  const std::size_t n = s.t.size();
  if (n == 0) return 0.0;
  if (t <= s.t.front()) return s.value.front();
  if (t >= s.t.back()) return s.value.back();
  if (s.t[k_] > t) k_ = 0;
  while (s.t[k_ + 1] < t) ++k_;
  const double w = (t - s.t[k_]) / (s.t[k_ + 1] - s.t[k_]);
  return (1.0 - w) * s.value[k_] + w * s.value[k_ + 1];
}

}  // namespace barimpact
