// A scheme's state between steps as one value: the members its step
// changes, named once (a `std::tie` of them), copied whole to keep a level
// and copied back to take a step again (the elastic-plastic and soil
// iterations, line_scheme.hpp). Copy-assigning a vector of the same size
// reuses its storage, so once primed (the first keep, at the start) keeping
// and restoring never allocate.
#pragma once

#include <cstddef>
#include <tuple>

namespace barimpact {

template <class... T>
class KeptState {
 public:
  /// Copies the live state in.
  void keep(const std::tuple<T&...>& live) { kept_ = live; }
  /// Copies the kept state back over the live one.
  void restore(std::tuple<T&...> live) const { live = kept_; }
  /// The kept copy of the I-th member.
  template <std::size_t I>
  [[nodiscard]] const auto& get() const {
    return std::get<I>(kept_);
  }

 private:
  std::tuple<T...> kept_;
};

}  // namespace barimpact
