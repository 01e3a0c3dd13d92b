#include "barimpact/schemes/plastic_bonds.hpp"

#include <algorithm>
#include <cmath>

#include "yield_check.hpp"

namespace barimpact {

namespace {

// The return map of material.hpp, branch-free so that it vectorises, over
// bonds [first, last): p^{m+1} and alpha^{m+1} from eps^{m+1} and level m's
// state; returns sum sigma^m (p^{m+1} - p^{m-1}).
template <bool isotropic>
double return_map(std::size_t first, std::size_t last, const Plasticity& law, double inv_h, const double* __restrict u,
                  const double* __restrict up, const double* __restrict pm, const double* __restrict am,
                  const double* __restrict p_before, double* __restrict pn, double* __restrict an) {
  const double e = law.modulus, hm = law.plastic_modulus, sy = law.yield_stress;
  const double inv = 1.0 / (e + hm);
  auto element = [&](std::size_t j) {  // returns sigma^m (p^{m+1} - p^{m-1})
    const double sigma = e * ((u[j + 1] - u[j]) * inv_h - pm[j]);
    double p = pm[j], alpha = isotropic ? am[j] : 0.0;  // kinematic hardening needs no alpha
    (void)Plasticity::return_map<isotropic>(e * ((up[j + 1] - up[j]) * inv_h - pm[j]), hm, sy, inv, p, alpha);
    pn[j] = p;
    if constexpr (isotropic) an[j] = alpha;
    return sigma * (p - p_before[j]);
  };
  // Eight partial sums in a fixed order: the sum vectorises (one chain of
  // additions would bind the loop to their latency) and stays deterministic.
  double partial[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  std::size_t j = first;
  for (; j + 8 <= last; j += 8)
    for (std::size_t k = 0; k < 8; ++k) partial[k] += element(j + k);
  double work = 0.0;
  for (; j < last; ++j) work += element(j);
  for (double x : partial) work += x;
  return work;
}

}  // namespace

PlasticBonds::PlasticBonds(const Line& line, double alpha) : alpha_(alpha) {
  ranges_ = plastic_bodies(line);
  for (auto* levels : {&p_, &accumulated_})
    for (auto& level : *levels) level.assign(line.bonds.size(), 0.0);
  half_.assign(line.bodies.size(), 0.0);
  last_.assign(line.bodies.size(), 0.0);
  hardening0_.assign(line.bodies.size(), 0.0);
}

void PlasticBonds::start(const double* u0) {
  prev_ = 2;
  cur_ = 0;
  next_ = 1;
  for (auto* levels : {&p_, &accumulated_})
    for (auto& level : *levels) std::fill(level.begin(), level.end(), 0.0);
  // From a virgin state: u0 as level m + 1 of a material at rest at u = 0.
  const std::vector<double> zero(p_[0].size() + 1, 0.0);
  for (const Range& r : ranges_)
    (void)(r.law.isotropic ? return_map<true> : return_map<false>)(r.first, r.last, r.law, r.inv_h, zero.data(), u0,
                                                                   zero.data(), zero.data(), zero.data(),
                                                                   p_[next_].data(), accumulated_[next_].data());
  p_[cur_] = p_[next_];
  accumulated_[cur_] = accumulated_[next_];
  quiet_ = false;  // the start's step books its work whatever happens
  pristine_ = std::all_of(p_[cur_].begin(), p_[cur_].end(), [](double x) { return x == 0.0; });
  std::fill(half_.begin(), half_.end(), 0.0);
  std::fill(last_.begin(), last_.end(), 0.0);
  load_half_ = load_last_ = 0.0;
  for (const Range& r : ranges_) hardening0_[r.body] = hardening_energy(r);
}

void PlasticBonds::record(const double* p, const double* a, bool yielded, const double* um, const double* u,
                          const double* up, const std::array<double, 3>& w, bool first) {
  if (yielded) {
    fresh_ = 0;
    while (fresh_ == cur_ || fresh_ == next_) ++fresh_;
    std::copy(p, p + p_[fresh_].size(), p_[fresh_].begin());
    std::copy(a, a + accumulated_[fresh_].size(), accumulated_[fresh_].begin());
  } else {
    fresh_ = next_;  // p^{m+1} = p^m: the same array
  }
  const bool moved = yielded || !quiet_;  // p^{m+1} != p^{m-1}
  quiet_ = !yielded;
  pristine_ = pristine_ && !yielded;     // then every p is 0: no work, and u is not read
  const double* pp = p_[fresh_].data();  // levels m + 1, m, m - 1
  const double* p0 = p_[next_].data();
  const double* pm = p_[cur_].data();
  double load = 0.0;
  for (const Range& r : ranges_) {
    double plastic = 0.0, loading = 0.0;
    const double e = r.law.modulus, inv_h = r.inv_h;
    for (std::size_t j = r.first; moved && !pristine_ && j < r.last; ++j) {
      const double sp = e * ((up[j + 1] - up[j]) * inv_h - pp[j]), s0 = e * ((u[j + 1] - u[j]) * inv_h - p0[j]);
      const double sm = e * ((um[j + 1] - um[j]) * inv_h - pm[j]);
      plastic += (w[0] * sp + w[1] * s0 + w[2] * sm) * (pp[j] - pm[j]);
    }
    for (std::size_t j = r.first; !pristine_ && j < r.last; ++j)
      loading += (w[0] * pp[j] + w[1] * p0[j] + w[2] * pm[j]) * ((up[j + 1] - up[j]) - (um[j + 1] - um[j]));
    const double wp = 0.5 * r.volume * plastic;
    half_[r.body] += wp;
    last_[r.body] = first ? 0.0 : wp;
    load += 0.5 * r.axial * loading;  // h A E p (deps) = E A p (d du)
  }
  load_half_ += load;
  load_last_ = first ? 0.0 : load;
  rotate();
}

double PlasticBonds::load_work() const {
  return load_half_ - 0.5 * load_last_;
}

void PlasticBonds::advance(const double* u, const double* up, bool first) {
  const bool yielding = detail::any_yields(ranges_, pristine_, 1.0, up, p_[next_].data(), accumulated_[next_].data());
  if (!yielding && quiet_) {  // p^{m+1} = p^m = p^{m-1}: level m + 1 is level m's arrays, its work 0
    fresh_ = next_;
    for (const Range& r : ranges_) last_[r.body] = 0.0;
    rotate();
    return;
  }
  fresh_ = 0;
  while (fresh_ == cur_ || fresh_ == next_) ++fresh_;  // three arrays, at most two levels in use
  quiet_ = !yielding;
  pristine_ = pristine_ && !yielding;
  for (const Range& r : ranges_) {
    const double w = 0.5 * r.volume *
                     (r.law.isotropic ? return_map<true>
                                      : return_map<false>)(r.first, r.last, r.law, r.inv_h, u, up, p_[next_].data(),
                                                           accumulated_[next_].data(), p_[cur_].data(),
                                                           p_[fresh_].data(), accumulated_[fresh_].data());
    half_[r.body] += w;
    last_[r.body] = first ? 0.0 : w;  // the start's share is already half a level's, as W_ext's
  }
  rotate();
}

void PlasticBonds::rotate() {
  prev_ = cur_;
  cur_ = next_;
  next_ = fresh_;
}

double PlasticBonds::energy_correction(const double* a, const double* pa, const double* b, const double* pb) const {
  double sum = 0.0;
  for (const Range& r : ranges_) {
    const double h = 1.0 / r.inv_h;
    double s = 0.0;
    for (std::size_t j = r.first; j < r.last; ++j)
      s += h * (pa[j] * pb[j] * h - pa[j] * (b[j + 1] - b[j]) - pb[j] * (a[j + 1] - a[j]));
    if (alpha_ != 0.0) {  // alpha ((d - h dp)^2 - d^2), d the elongation's change
      double t = 0.0;
      for (std::size_t j = r.first; j < r.last; ++j) {
        const double dp = pb[j] - pa[j], d = (b[j + 1] - b[j]) - (a[j + 1] - a[j]);
        t += h * dp * (h * dp - 2.0 * d);
      }
      s += alpha_ * t;
    }
    sum += 0.5 * r.k * s;
  }
  return sum;
}

double PlasticBonds::hardening_energy(const Range& r) const {
  if (r.law.plastic_modulus == 0.0) return 0.0;
  const std::vector<double>& a = r.law.isotropic ? accumulated_[cur_] : p_[cur_];
  double s = 0.0;
  for (std::size_t j = r.first; j < r.last; ++j) s += a[j] * a[j];
  return 0.5 * r.law.plastic_modulus * r.volume * s;
}

double PlasticBonds::hardening_energy() const {
  double s = 0.0;
  for (const Range& r : ranges_) s += hardening_energy(r);
  return s;
}

double PlasticBonds::strain_energy(const double* u0) const {
  return energy_correction(u0, current(), u0, current()) + hardening_energy();
}

double PlasticBonds::strain_energy(const double* um, const double* u, const double* up) const {
  if (pristine_) return 0.0;  // every level's p is 0: the correction is +0 (and costs a pass over the bonds)
  return 0.5 * (energy_correction(um, previous(), u, current()) + energy_correction(u, current(), up, next())) +
         hardening_energy();
}

double PlasticBonds::body_work(const Range& r) const {
  return half_[r.body] - 0.5 * last_[r.body] - (hardening_energy(r) - hardening0_[r.body]);
}

double PlasticBonds::work() const {
  double s = 0.0;
  for (const Range& r : ranges_) s += body_work(r);
  return s;
}

double PlasticBonds::body_work(std::size_t body) const {
  for (const Range& r : ranges_)
    if (r.body == body) return body_work(r);
  return 0.0;
}

}  // namespace barimpact
