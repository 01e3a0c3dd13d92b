// A scheme's state between steps, kept so that a step can be taken again
// from the same level (the elastic-plastic iteration of a one-step implicit
// scheme, plastic_iteration.hpp). The scheme names what its step changes;
// the copies are allocated when named, so save and restore never allocate.
#pragma once

#include <algorithm>
#include <type_traits>
#include <utility>
#include <vector>

namespace barimpact {

class StepSnapshot {
 public:
  /// Keeps `v` (at its present size and place, which must not change).
  void keep(std::vector<double>& v) {
    vectors_.push_back(&v);
    vector_copies_.emplace_back(v.size(), 0.0);
  }
  /// Any vector of a trivially copyable type (a link's branch), by bytes.
  template <class T>
  void keep(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.push_back({reinterpret_cast<unsigned char*>(v.data()), v.size() * sizeof(T)});
    byte_copies_.emplace_back(v.size() * sizeof(T), 0);
  }
  /// Any trivially copyable object (a scheme's level pointers), by bytes.
  template <class T>
  void keep_object(T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.push_back({reinterpret_cast<unsigned char*>(&x), sizeof(T)});
    byte_copies_.emplace_back(sizeof(T), 0);
  }
  void keep(double& x) {
    scalars_.push_back(&x);
    scalar_copies_.push_back(x);
  }
  void save() {
    for (std::size_t i = 0; i < vectors_.size(); ++i)
      std::copy(vectors_[i]->begin(), vectors_[i]->end(), vector_copies_[i].begin());
    for (std::size_t i = 0; i < scalars_.size(); ++i) scalar_copies_[i] = *scalars_[i];
    for (std::size_t i = 0; i < bytes_.size(); ++i)
      std::copy(bytes_[i].first, bytes_[i].first + bytes_[i].second, byte_copies_[i].begin());
  }
  void restore() {
    for (std::size_t i = 0; i < vectors_.size(); ++i)
      std::copy(vector_copies_[i].begin(), vector_copies_[i].end(), vectors_[i]->begin());
    for (std::size_t i = 0; i < scalars_.size(); ++i) *scalars_[i] = scalar_copies_[i];
    for (std::size_t i = 0; i < bytes_.size(); ++i)
      std::copy(byte_copies_[i].begin(), byte_copies_[i].end(), bytes_[i].first);
  }
  /// The saved copy of the `i`-th vector kept.
  [[nodiscard]] const std::vector<double>& saved(std::size_t i) const { return vector_copies_[i]; }

 private:
  std::vector<std::vector<double>*> vectors_;
  std::vector<std::vector<double>> vector_copies_;
  std::vector<double*> scalars_;
  std::vector<double> scalar_copies_;
  std::vector<std::pair<unsigned char*, std::size_t>> bytes_;  // other vectors: data and size, fixed
  std::vector<std::vector<unsigned char>> byte_copies_;
};

}  // namespace barimpact
