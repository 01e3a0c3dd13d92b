// The SIMD batch of `sweep`: up to four one-bar cases of the paper's
// scheme stepped together, one per lane of a register, each lane the
// scheme's own one-bar kernel (paper_scheme.hpp) to the last bit. It lives
// with the study that uses it; the schemes know nothing of it.
#pragma once

#include <atomic>
#include <memory>
#include <new>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/paper_scheme.hpp"
#include "barimpact/schemes/simd.hpp"

namespace barimpact {

/// Up to `width` paper-scheme cases stepped together, one per lane of a
/// SIMD register: their levels, pivots and loads interleaved
/// (node j of lane l at [width j + l]), the same arithmetic as PaperScheme's
/// kernel lane by lane, so that each lane's results are PaperScheme's to the
/// last bit (tested). The sweeps are latency-bound; `width` independent
/// chains in one register make them several times cheaper per case.
/// Each lane stays a PaperScheme: observers see it through the Scheme
/// interface.
class PaperBatch final : public LaneStepper {
 public:
  /// Cases per register: 4 doubles, one AVX2 register (two SSE2 ones; the
  /// path is chosen at run time, simd.hpp). (Eight, one AVX-512
  /// register, measured no faster on AMD Zen 4, which runs it as two halves,
  /// and slower from M = 10^5, where eight cases leave the cache.)
  static constexpr std::size_t width = 4;
  /// The largest mesh worth batching: beyond it the lanes' levels and
  /// factors leave the cache and a batch is no faster per case than single
  /// runs (measured 2.0-2.4x at M = 10^5, 0.8-1.3x at 10^6; docs/benchmarks.md).
  static constexpr int largest_mesh = 200'000;
  /// Storage aligned to a register: every load of all lanes is one aligned access.
  template <class T>
  struct RegisterAligned {
    using value_type = T;
    RegisterAligned() = default;
    template <class U>
    explicit RegisterAligned(const RegisterAligned<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{8 * width})); }
    void deallocate(T* p, std::size_t) { ::operator delete (p, std::align_val_t{8 * width}); }
    friend bool operator==(const RegisterAligned&, const RegisterAligned&) = default;
  };
  using Lanes = std::vector<double, RegisterAligned<double>>;

  /// 1 to `width` cases, pairwise batchable. Throws InputError otherwise.
  explicit PaperBatch(const std::vector<const Case*>& cases);
  void start() override;
  void advance() override;
  [[nodiscard]] std::size_t size() const { return lanes_.size(); }
  [[nodiscard]] std::size_t lanes() const override { return lanes_.size(); }
  [[nodiscard]] PaperScheme& lane(std::size_t i) override { return *lanes_[i]; }

 private:
  std::vector<std::unique_ptr<PaperScheme>> lanes_;
  std::array<Lanes, 3> levels_;
  Lanes inv_, up_, load_;
  std::size_t nodes_ = 0;
  bool steady_load_ = false;
  SimdPath path_ = SimdPath::scalar;  // the kernel's instructions (simd.hpp), chosen at construction
};

/// Whether `a` and `b` can share a PaperBatch: both run by the paper's
/// scheme's one-bar kernel (registry.hpp), on meshes of one size, for one
/// step count, under a load that does not depend on t, without a dashpot.
[[nodiscard]] bool batchable(const Case& a, const Case& b);

/// Runs up to four batchable cases together in a PaperBatch: the same
/// results as run() on each, bit for bit, for about a third of the cost per case.
[[nodiscard]] std::vector<RunResult> run_batch(const std::vector<const Case*>& cases,
                                               const std::atomic<bool>* interrupt = nullptr);

}  // namespace barimpact
