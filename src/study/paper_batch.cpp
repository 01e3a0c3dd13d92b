#include "barimpact/study/paper_batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "barimpact/model/expression.hpp"
#include "barimpact/schemes/registry.hpp"
#include "paper_batch_kernel.hpp"

namespace barimpact {

bool batchable(const Case& a, const Case& b) {
  auto fits = [](const Case& c) {
    const auto one = c.one_bar();
    return one && scheme_info(c.time.scheme).one_bar && one->obstacle.kind != ObstacleKind::viscoelastic &&
           !Expression(c.load.body_force).depends_on_t();
  };
  return fits(a) && fits(b) && a.bar_elements() == b.bar_elements() && a.step_count() == b.step_count() &&
         Expression(a.load.body_force).is_zero() == Expression(b.load.body_force).is_zero();
}

static_assert(PaperBatch::width == batch_kernel::width, "one register of lanes");

PaperBatch::PaperBatch(const std::vector<const Case*>& cases) {
  if (cases.empty() || cases.size() > width) throw InputError(fmt::format("PaperBatch: 1 to {} cases", width));
  for (const auto* c : cases) {
    if (!batchable(*cases.front(), *c)) throw InputError("PaperBatch: the cases cannot share a batch");
    lanes_.push_back(std::make_unique<PaperScheme>(*c));
  }
  nodes_ = lanes_.front()->nodes();
  path_ = simd_path();
  steady_load_ = lanes_.front()->load_mode_ == PaperScheme::LoadMode::steady;
  for (auto& l : levels_) l.assign(width * nodes_, 0.0);
  inv_.assign(width * nodes_, 0.0);
  up_.assign(width * nodes_, 0.0);
  load_.assign(width * nodes_, 0.0);
  // Unused lanes repeat lane 0: they compute what it computes, and are ignored.
  for (std::size_t l = 0; l < width; ++l) {
    const PaperScheme& s = *lanes_[std::min(l, lanes_.size() - 1)];
    for (std::size_t j = 0; j < nodes_; ++j) {
      inv_[width * j + l] = s.inv_[j];
      up_[width * j + l] = s.upper_[j];
    }
  }
  for (std::size_t l = 0; l < lanes_.size(); ++l) {
    PaperScheme& s = *lanes_[l];
    s.use_partitions(0);  // the batch's kernel is the two-ended solve; its lanes' chunks would be unused
    s.batched_ = true;
    s.stride_ = width;
    s.prev_ = levels_[2].data() + l;
    s.cur_ = levels_[0].data() + l;
    s.next_ = levels_[1].data() + l;
  }
}

void PaperBatch::start() {
  for (auto& s : lanes_) s->start();
  for (std::size_t l = lanes_.size(); l < width; ++l)  // padding lanes copy lane 0
    for (auto& level : levels_)
      for (std::size_t j = 0; j < nodes_; ++j) level[width * j + l] = level[width * j];
  if (steady_load_)
    for (std::size_t l = 0; l < width; ++l)
      for (std::size_t j = 0; j < nodes_; ++j)
        load_[width * j + l] = lanes_[std::min(l, lanes_.size() - 1)]->loads_[0][j];
}

// PaperScheme::solve_level with `width` lanes, on the SIMD path chosen at
// run time (simd.hpp): every path the same operations in the same order,
// so that every lane's result is bit-for-bit the scalar kernel's.
void PaperBatch::advance() {
  const long long m = lanes_.front()->n_ + 1;
  batch_kernel::Level level;
  for (std::size_t l = 0; l < width; ++l) {
    const PaperScheme& s = *lanes_[std::min(l, lanes_.size() - 1)];
    const double em1 = 1.0 / s.scale(m - 1), e0 = 1.0 / s.scale(m), ep1 = 1.0 / s.scale(m + 1);
    const double ebar = s.alpha_ * ep1 + (1.0 - 2.0 * s.alpha_) * e0 + s.alpha_ * em1;
    const double k = s.k_, g = s.gap_;
    level.contact[l] = 0.5 * k * (std::abs(s.next_[0] + g * e0) - g * ebar);
    level.load_weight[l] = steady_load_ ? ebar : 0.0;
    level.b1_first[l] = s.b1_diag_[0], level.b1_inner[l] = s.b1_diag_[1], level.b1_last[l] = s.b1_diag_[2];
    level.b0_first[l] = s.b0_diag_[0], level.b0_inner[l] = s.b0_diag_[1], level.b0_last[l] = s.b0_diag_[2];
    level.b1_off[l] = s.b1_off_, level.b0_off[l] = s.b0_off_;
    level.a_off[l] = s.a_off_;
  }
  const PaperScheme& first = *lanes_.front();  // lane 0's pointers are the interleaved arrays' starts
  level.z_now = first.next_;
  level.z_previous = first.cur_;
  level.z_next = first.prev_;
  level.inverse_pivot = inv_.data();
  level.upper = up_.data();
  level.load = steady_load_ ? load_.data() : nullptr;
  level.last = nodes_ - 1;
  switch (path_) {
    case SimdPath::scalar:
      batch_kernel::advance_scalar(level);
      break;
    case SimdPath::sse2:
      batch_kernel::advance_sse2(level);
      break;
    case SimdPath::avx2:
      batch_kernel::advance_avx2(level);
      break;
  }
  for (auto& s : lanes_) s->finish_level(m);
}

std::vector<RunResult> run_batch(const std::vector<const Case*>& cases, const std::atomic<bool>* interrupt) {
  const auto started = std::chrono::steady_clock::now();
  PaperBatch batch(cases);
  const long long steps = cases.front()->step_count();
  std::vector<std::unique_ptr<RunRecorder>> rec;
  std::vector<std::vector<Observer*>> observers;
  for (std::size_t l = 0; l < cases.size(); ++l) {
    rec.push_back(std::make_unique<RunRecorder>(*cases[l], batch.lane(l)));
    observers.push_back(rec[l]->observers());
  }
  // The one time loop, its lanes the batch's: a lane that turns non-finite
  // stops being observed (its numbers are computed on, and ignored).
  const std::vector<LoopResult> loops = simulate(batch, steps, observers, interrupt);
  std::vector<RunResult> out;
  for (std::size_t l = 0; l < cases.size(); ++l) {
    out.push_back(rec[l]->finish(loops[l], steps, started));
    out.back().summary.run_seconds /= static_cast<double>(cases.size());  // each lane's share of the batch
  }
  return out;
}

}  // namespace barimpact
