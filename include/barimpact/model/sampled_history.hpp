// A quantity sampled in time, such as a measured velocity imposed at a line's
// end (signal matching drives a pile's head with the record's velocity):
// linear between samples, held at the first or last sample outside them.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace barimpact {

struct SampledHistory {
  std::vector<double> t;      ///< strictly increasing
  std::vector<double> value;  ///< one per time
};

/// Reads a SampledHistory at increasing times in O(1) each (a cursor that
/// walks forward; a time before it restarts the walk). One per thread.
class HistoryReader {
 public:
  HistoryReader() = default;
  explicit HistoryReader(std::shared_ptr<const SampledHistory> h) : h_(std::move(h)) {}
  [[nodiscard]] explicit operator bool() const { return h_ != nullptr; }
  [[nodiscard]] double operator()(double t) const;

 private:
  std::shared_ptr<const SampledHistory> h_;
  mutable std::size_t k_ = 0;  // t[k_] <= t at the last read, once inside
};

}  // namespace barimpact
