#include "barimpact/schemes/penalty_links.hpp"

#include <algorithm>
#include <cmath>

namespace barimpact {

namespace {

constexpr int passes_per_round = 8;
constexpr int rounds = 4;
constexpr double tolerance = 1e-12;

// p for one link alone: c = cbar - alpha p, dc/dt = rbar - gamma p (alpha,
// gamma already times W_ii), the law's piecewise-linear equation solved in
// closed form on each branch.
double closed_form(const ContactLaw& law, double cbar, double rbar, double alpha, double gamma, double c_max) {
  if (cbar <= 0.0) return 0.0;
  const double k = law.stiffness;
  switch (law.kind) {
    case LawKind::elastic:
      return k * cbar / (1.0 + k * alpha);
    case LawKind::viscoelastic: {
      const double s = k * cbar + law.viscosity * rbar;
      if (s <= 0.0) return 0.0;
      const double p = s / (1.0 + k * alpha + law.viscosity * gamma);
      return (alpha > 0.0 && cbar - alpha * p <= 0.0) ? cbar / alpha : p;  // stops at the face
    }
    case LawKind::cushion: {
      const double loading = k * cbar / (1.0 + k * alpha);
      if (cbar - alpha * loading >= c_max) return loading;
      const double e2 = law.restitution * law.restitution, kk = k / e2;
      return std::max(0.0, kk * (cbar - (1.0 - e2) * c_max) / (1.0 + kk * alpha));
    }
    case LawKind::rigid:
    case LawKind::smith:   // not a penalty law of the implicit schemes (line_scheme_misfit refuses it)
    case LawKind::diesel:  // nor a diesel cylinder (registry.cpp's diesel_misfit)
      break;
  }
  return 0.0;
}

}  // namespace

bool solve_dense(std::size_t m, double* a, double* b) {
  for (std::size_t col = 0; col < m; ++col) {
    std::size_t best = col;
    for (std::size_t r = col + 1; r < m; ++r)
      if (std::abs(a[r * m + col]) > std::abs(a[best * m + col])) best = r;
    const double pivot = a[best * m + col];
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot)) return false;
    if (best != col) {
      for (std::size_t s = 0; s < m; ++s) std::swap(a[best * m + s], a[col * m + s]);
      std::swap(b[best], b[col]);
    }
    for (std::size_t r = col + 1; r < m; ++r) {
      const double f = a[r * m + col] / pivot;
      if (f == 0.0) continue;
      for (std::size_t s = col; s < m; ++s) a[r * m + s] -= f * a[col * m + s];
      b[r] -= f * b[col];
    }
  }
  for (std::size_t r = m; r-- > 0;) {
    double x = b[r];
    for (std::size_t s = r + 1; s < m; ++s) x -= a[r * m + s] * b[s];
    b[r] = x / a[r * m + r];
  }
  return true;
}

PenaltyLinks::PenaltyLinks(std::vector<ContactLaw> laws, std::vector<double> delassus, double alpha, double gamma)
    : laws_(std::move(laws)), w_(std::move(delassus)), alpha_(alpha), gamma_(gamma) {
  const std::size_t n = laws_.size();
  branch_.assign(n, Branch::off);
  active_.reserve(n);
  matrix_.assign(n * n, 0.0);
  rhs_.assign(n, 0.0);
}

int PenaltyLinks::solve(const double* cbar, const double* rbar, const double* c_max, double* p) {
  const std::size_t n = laws_.size();
  double c_scale = 0.0, p_scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const ContactLaw& law = laws_[i];
    const double k = law.largest_stiffness();
    c_scale = std::max(c_scale, std::abs(cbar[i]));
    p_scale = std::max(p_scale, k * std::abs(cbar[i]) + law.viscosity * std::abs(rbar[i]));
  }
  tol_c_ = tolerance * c_scale;
  tol_p_ = tolerance * p_scale;
  int passes = 0;
  double sweeps_to = 1e-6;
  for (int round = 0; round < rounds; ++round) {
    for (int pass = 0; pass < passes_per_round; ++pass) {
      ++passes;
      if (!solve_branches(cbar, rbar, c_max, p)) break;
      if (!move_branches(cbar, rbar, c_max, p, false)) return passes;
    }
    // A cycle: Gauss-Seidel towards the solution, then its branches.
    gauss_seidel(cbar, rbar, c_max, p, sweeps_to);
    (void)move_branches(cbar, rbar, c_max, p, true);
    sweeps_to *= 1e-3;
  }
  gauss_seidel(cbar, rbar, c_max, p, 1e-14);
  return 0;
}

// Every link to the branch its (c, dc/dt, p) indicate; `afresh`: whatever
// branch it was on (after Gauss-Seidel), else keeping it within the
// tolerances. Returns whether a link moved.
bool PenaltyLinks::move_branches(const double* cbar, const double* rbar, const double* c_max, const double* p,
                                 bool afresh) {
  const std::size_t n = laws_.size();
  bool moved = false;
  for (std::size_t i = 0; i < n; ++i) {
    double wp = 0.0;
    for (std::size_t j = 0; j < n; ++j)
      if (p[j] != 0.0) wp += w_[i * n + j] * p[j];
    const double c = cbar[i] - alpha_ * wp, rate = rbar[i] - gamma_ * wp;
    const Branch b = afresh ? branch_of(i, c, rate, p[i], c_max[i]) : indicated(i, c, rate, p[i], c_max[i]);
    moved = moved || b != branch_[i];
    branch_[i] = b;
  }
  return moved;
}

PenaltyLinks::Branch PenaltyLinks::branch_of(std::size_t i, double c, double rate, double p, double c_max) const {
  const ContactLaw& law = laws_[i];
  switch (law.kind) {
    case LawKind::elastic:
      return c > 0.0 ? Branch::on : Branch::off;
    case LawKind::cushion: {
      const double c_off = (1.0 - law.restitution * law.restitution) * c_max;
      return c <= c_off ? Branch::off : c >= c_max ? Branch::on : Branch::unloading;
    }
    case LawKind::viscoelastic:
      if (p <= 0.0) return Branch::off;
      return (alpha_ > 0.0 && p < law.stiffness * c + law.viscosity * rate - tol_p_) ? Branch::face : Branch::on;
    case LawKind::rigid:
    case LawKind::smith:   // not a penalty law of the implicit schemes (line_scheme_misfit refuses it)
    case LawKind::diesel:  // nor a diesel cylinder (registry.cpp's diesel_misfit)
      break;
  }
  return Branch::off;
}

PenaltyLinks::Branch PenaltyLinks::indicated(std::size_t i, double c, double rate, double p, double c_max) const {
  const ContactLaw& law = laws_[i];
  const Branch now = branch_[i];
  const double tc = tol_c_, tp = tol_p_;
  switch (law.kind) {
    case LawKind::elastic:
      if ((now == Branch::on && c >= -tc) || (now == Branch::off && c <= tc)) return now;
      return c > 0.0 ? Branch::on : Branch::off;
    case LawKind::cushion: {
      const double c_off = (1.0 - law.restitution * law.restitution) * c_max;
      const bool holds = (now == Branch::off && c <= c_off + tc) || (now == Branch::on && c >= c_max - tc) ||
                         (now == Branch::unloading && c_max > 0.0 && c >= c_off - tc && c <= c_max + tc);
      if (holds) return now;
      return c <= c_off ? Branch::off : c >= c_max ? Branch::on : Branch::unloading;
    }
    case LawKind::viscoelastic: {
      const double l = law.viscosity;
      switch (now) {
        case Branch::off:
          return (c <= tc || law.stiffness * c + l * rate <= tp) ? Branch::off : Branch::on;
        case Branch::on:
          if (c >= -tc && p >= -tp) return Branch::on;
          return (p < -tp || alpha_ <= 0.0) ? Branch::off : Branch::face;
        case Branch::face:
          if (p < -tp) return Branch::off;
          return p <= l * rate + tp ? Branch::face : Branch::on;
        case Branch::unloading:
          break;
      }
      return Branch::off;
    }
    case LawKind::rigid:
    case LawKind::smith:   // not a penalty law of the implicit schemes (line_scheme_misfit refuses it)
    case LawKind::diesel:  // nor a diesel cylinder (registry.cpp's diesel_misfit)
      break;
  }
  return Branch::off;
}

// One equation per link not off, on its branch:
//   on         p_i + (k alpha + l gamma)(W p)_i = k cbar_i + l rbar_i   (l = 0 but viscoelastic)
//   unloading  p_i + kk alpha (W p)_i = kk (cbar_i - (1 - e^2) c_max_i),   kk = k / e^2
//   face       alpha (W p)_i = cbar_i
bool PenaltyLinks::solve_branches(const double* cbar, const double* rbar, const double* c_max, double* p) {
  const std::size_t n = laws_.size();
  active_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = 0.0;
    if (branch_[i] != Branch::off) active_.push_back(i);
  }
  const std::size_t m = active_.size();
  for (std::size_t r = 0; r < m; ++r) {
    const std::size_t i = active_[r];
    const ContactLaw& law = laws_[i];
    const double k = law.stiffness, l = law.kind == LawKind::viscoelastic ? law.viscosity : 0.0;
    double diagonal = 1.0, slope = k * alpha_ + l * gamma_, b = k * cbar[i] + l * rbar[i];
    if (branch_[i] == Branch::unloading) {
      const double e2 = law.restitution * law.restitution, kk = k / e2;
      slope = kk * alpha_;
      b = kk * (cbar[i] - (1.0 - e2) * c_max[i]);
    } else if (branch_[i] == Branch::face) {
      diagonal = 0.0;
      slope = alpha_;
      b = cbar[i];
    }
    for (std::size_t s = 0; s < m; ++s) matrix_[r * m + s] = slope * w_[i * n + active_[s]] + (r == s ? diagonal : 0.0);
    rhs_[r] = b;
  }
  if (!solve_dense(m, matrix_.data(), rhs_.data())) return false;
  for (std::size_t r = 0; r < m; ++r) p[active_[r]] = rhs_[r];
  return true;
}

// Gauss-Seidel: each link's closed form against the others' current
// forces (exact minimisation of the problem's strictly convex energy along
// each link in turn, so it converges), until no sweep changes a force by
// more than `to` of the largest.
void PenaltyLinks::gauss_seidel(const double* cbar, const double* rbar, const double* c_max, double* p,
                                double to) const {
  const std::size_t n = laws_.size();
  for (int sweep = 0; sweep < 100'000; ++sweep) {
    double change = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double cb = cbar[i], rb = rbar[i];
      for (std::size_t j = 0; j < n; ++j)
        if (j != i && p[j] != 0.0) {
          cb -= alpha_ * w_[i * n + j] * p[j];
          rb -= gamma_ * w_[i * n + j] * p[j];
        }
      const double w = w_[i * n + i];
      const double q = closed_form(laws_[i], cb, rb, alpha_ * w, gamma_ * w, c_max[i]);
      change = std::max(change, std::abs(q - p[i]));
      scale = std::max(scale, std::abs(q));
      p[i] = q;
    }
    if (change <= to * scale) break;
  }
}

}  // namespace barimpact
