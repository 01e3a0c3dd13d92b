// One time step of the paper's scheme against the bare loop it must match:
// the same fused stencil right-hand side + prefactored tridiagonal solve,
// written flat with no scheme object, no contact term, no checks.
// Reported: seconds per node-step (the `per_node_step` counter).
//
//   build/release/bench/barimpact_bench --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true   (or: make bench)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <utility>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/line_mass_redistribution.hpp"
#include "barimpact/schemes/paper_scheme.hpp"
#include "barimpact/schemes/registry.hpp"
#include "barimpact/schemes/simd.hpp"
#include "barimpact/study/paper_batch.hpp"

#include <initializer_list>
#include <string>
#include <utility>

namespace {

barimpact::Case bench_case(long long elements) {
  // Example 1's data at M elements, dt tied to h as in the paper (dt = h).
  return barimpact::Case::from_string(fmt::format(R"toml([bar]
elements = {}
[initial]
velocity = "-1"
[time]
step = {}
end = 1
)toml",
                                                  elements, 1.0 / static_cast<double>(elements)));
}

void per_node_step(benchmark::State& state, std::size_t nodes) {
  state.counters["per_node_step"] = benchmark::Counter(
      static_cast<double>(nodes), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Times the steps of case `c` through the library's scheme object
// (`sequential`: the paper's one-bar kernel held to its two-ended solve).
void time_steps(benchmark::State& state, const barimpact::Case& c, bool sequential = false) {
  auto s = barimpact::make_scheme(c);
  if (auto* paper = dynamic_cast<barimpact::PaperScheme*>(s.get()); paper != nullptr && sequential)
    paper->use_partitions(0);
  s->start();
  for (auto _ : state) {
    s->advance();
    benchmark::DoNotOptimize(s->end_displacement());
  }
  per_node_step(state, s->nodes());
}

// Bars named by `parts` (name, elements) of M elements in all, welded end
// to end on [0, 1], all moving at `velocity`; the line engine runs them.
barimpact::Case bars(long long M, std::initializer_list<std::pair<const char*, long long>> parts,
                     const std::string& velocity = "-1") {
  barimpact::Case c;
  for (auto [name, elements] : parts) {
    barimpact::BodyData b;
    b.name = name;
    b.length = static_cast<double>(elements) / static_cast<double>(M);
    b.elements = static_cast<int>(elements);
    b.velocity = velocity;
    c.bodies.push_back(b);
  }
  return c;
}

// The one-bar kernel's step; BM_PaperStepSequential forces the two-ended
// solve and BM_PaperStepPartitioned Wang's partitioned one (P = range(1)) at
// every M, to measure paper_scheme.hpp's partition_threshold.
// partitions < 0: the scheme's own choice.
void paper_step(benchmark::State& state, long long partitions) {
  barimpact::PaperScheme scheme(bench_case(state.range(0)));
  if (partitions >= 0) scheme.use_partitions(static_cast<std::size_t>(partitions));
  scheme.start();
  for (auto _ : state) {
    scheme.advance();
    benchmark::DoNotOptimize(scheme.next_level());
  }
  per_node_step(state, scheme.nodes());
}

void BM_PaperStep(benchmark::State& state) {
  paper_step(state, -1);
}

void BM_PaperStepSequential(benchmark::State& state) {
  paper_step(state, 0);
}

void BM_PaperStepPartitioned(benchmark::State& state) {
  paper_step(state, state.range(1));
}

// PaperBatch::width cases in one batch (one SIMD register): time per
// node-step per case, to compare with BM_PaperStep.
void BM_PaperBatch(benchmark::State& state) {
  std::vector<barimpact::Case> cases;
  for (std::size_t l = 0; l < barimpact::PaperBatch::width; ++l) {
    cases.push_back(bench_case(state.range(0)));
    cases.back().near_end.stiffness = 100.0 * static_cast<double>(l + 1);  // different cases
  }
  std::vector<const barimpact::Case*> lanes;
  for (const auto& c : cases) lanes.push_back(&c);
  barimpact::PaperBatch batch(lanes);
  batch.start();
  for (auto _ : state) {
    batch.advance();
    benchmark::DoNotOptimize(batch.lane(0).next_level());
  }
  per_node_step(state, barimpact::PaperBatch::width * batch.lane(0).nodes());
}

// The batch kernel on each SIMD path this processor runs (simd.hpp), forced:
// BM_PaperBatchPath/<path>/<M>, per node-step per case.
void BM_PaperBatchPath(benchmark::State& state, barimpact::SimdPath path) {
  barimpact::force_simd_path(path);
  BM_PaperBatch(state);
  barimpact::force_simd_path(std::nullopt);
}

// The bare loop: the right-hand side B1 z^n + B0 z^{n-1} formed inside the
// first sweep of the two-ended solve (rows 0..k-1 from the top, k+1..M from
// the bottom, row k = M/2 last; M even here), then the sweep back outwards
// from row k; constants as for Example 1.
void BM_BareLoop(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0)) + 1, l = n - 1, k = l / 2;
  const double h = 1.0 / static_cast<double>(l), dt = h, alpha = 0.25;
  const double m_d = 2.0 * h / 3.0, m_o = h / 6.0, k_d = 2.0 / h, k_o = -1.0 / h;
  const double a_o = m_o / (dt * dt) + alpha * k_o, a_d = m_d / (dt * dt) + alpha * k_d;
  const double b1d = 2.0 * m_d / (dt * dt) - 0.5 * k_d, b1o = 2.0 * m_o / (dt * dt) - 0.5 * k_o;
  const double b0d = -m_d / (dt * dt) - alpha * k_d, b0o = -m_o / (dt * dt) - alpha * k_o;
  std::vector<double> inv(n), up(n), z0(n, 0.0), z1(n, -dt), z2(n, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    inv[j] = 1.0 / ((j == 0 ? 0.5 * a_d + 50.0 : a_d) - (j > 0 ? a_o * up[j - 1] : 0.0));
    up[j] = a_o * inv[j];
  }
  for (std::size_t j = l; j > k; --j) {
    inv[j] = 1.0 / ((j == l ? 0.5 * a_d : a_d) - (j < l ? a_o * up[j + 1] : 0.0));
    up[j] = a_o * inv[j];
  }
  inv[k] = 1.0 / (a_d - a_o * up[k - 1] - a_o * up[k + 1]);
  double* zo = z0.data();
  double* zc = z1.data();
  double* zn = z2.data();
  for (auto _ : state) {
    const double* __restrict c = zc;
    const double* __restrict o = zo;
    double* __restrict w = zn;
    auto r = [&](std::size_t j) {
      return b1d * c[j] + b1o * (c[j - 1] + c[j + 1]) + b0d * o[j] + b0o * (o[j - 1] + o[j + 1]);
    };
    double yt = (0.5 * b1d * c[0] + b1o * c[1] + 0.5 * b0d * o[0] + b0o * o[1]) * inv[0];
    double yb = (0.5 * b1d * c[l] + b1o * c[l - 1] + 0.5 * b0d * o[l] + b0o * o[l - 1]) * inv[l];
    w[0] = yt;
    w[l] = yb;
    for (std::size_t j = 1; j < k; ++j) {
      yt = r(j) * inv[j] - up[j] * yt;
      w[j] = yt;
      yb = r(l - j) * inv[l - j] - up[l - j] * yb;
      w[l - j] = yb;
    }
    double xt = (r(k) - a_o * (yt + yb)) * inv[k], xb = xt;
    w[k] = xt;
    for (std::size_t i = 1; i <= k; ++i) {
      xt = w[k - i] - up[k - i] * xt;
      w[k - i] = xt;
      xb = w[k + i] - up[k + i] * xb;
      w[k + i] = xb;
    }
    std::swap(zo, zc);
    std::swap(zc, zn);
    benchmark::DoNotOptimize(zc);
  }
  per_node_step(state, n);
}

// Every scheme's step on Example 1 (rigid obstacle for the rigid schemes,
// k = 100 for the penalty ones), dt = h/2 (h for characteristic).
void BM_SchemeStep(benchmark::State& state, const std::string& scheme, bool rigid, bool sequential) {
  const long long M = state.range(0);
  const double h = 1.0 / static_cast<double>(M);
  auto c = barimpact::Case::from_string(fmt::format(
      "[bar]\nelements = {}\n[initial]\nvelocity = \"-1\"\n[obstacle]\nkind = \"{}\"\n[time]\n"
      "scheme = \"{}\"\n{}end = 1\n",
      M, rigid ? "rigid" : "elastic", scheme, scheme == "characteristic" ? "" : fmt::format("step = {}\n", h / 2)));
  time_steps(state, c, sequential);
}

// A line of three bars of M elements in all (M/3, M/3, the rest; a rigid
// joint, a welded one, the rigid obstacle at x = 0 — elastic, k = 100, for
// the penalty schemes), all moving at -1: the line engine's step, to set
// beside the single bar's bare loop of M elements.
void BM_LineStep(benchmark::State& state, const std::string& scheme) {
  const long long M = state.range(0), third = M / 3;
  barimpact::Case c = bars(M, {{"a", third}, {"b", third}, {"c", M - 2 * third}});
  barimpact::JointData j{std::string("a-b"), std::string("a"), std::string("b"), barimpact::LawData{}, {}};
  const bool rigid = scheme != "newmark" && scheme != "paper";
  j.law.law = rigid ? barimpact::JointLaw::rigid : barimpact::JointLaw::elastic;
  c.joints = {j};
  c.near_end.law = j.law.law;
  c.time.scheme = scheme;
  c.time.step = (scheme == "characteristic" ? 1.0 : 0.5) / static_cast<double>(M);  // h/c, or h/2
  c.time.end = 1.0;
  time_steps(state, c);
}

// A scheme through the elastic-plastic path (plastic_bonds.hpp for the
// explicit schemes, plastic_iteration.hpp for the implicit ones) against the
// same line elastic: two welded bars of M elements in all, moving at -1 onto
// a rigid wall (paper and newmark: elastic, k = 100), dt = h/2. `elastic`: the
// material the paper's; `unyielded`: plastic with a yield stress never
// reached (the yield check, and the implicit schemes' snapshot of the
// level); `yielding`: sigma_y = 0.05 and E_t = 0.1, the bar yielding from
// the wall on.
void BM_PlasticLineStep(benchmark::State& state, const std::string& scheme, const std::string& material) {
  const long long M = state.range(0), half = M / 2;
  barimpact::Case c = bars(M, {{"a", half}, {"b", M - half}});
  for (barimpact::BodyData& b : c.bodies)
    if (material != "elastic") {
      b.material.kind = barimpact::MaterialKind::plastic;
      b.material.yield_stress = material == "yielding" ? 0.05 : 1e9;
      b.material.hardening_modulus = 0.1;
    }
  c.near_end.law = scheme == "newmark" || scheme == "paper" ? barimpact::JointLaw::elastic : barimpact::JointLaw::rigid;
  c.time.scheme = scheme;
  c.time.step = 0.5 / static_cast<double>(M);
  c.time.end = 1.0;
  c.time.partitions = 1;  // like for like: the plastic path has no partitioned solve, nor does the elastic one here
  time_steps(state, c);
}

// The rigid-contact schemes (moreau-jean, paoli-schatzman,
// mass-redistribution) on a line of three bars of M elements in all (M/3,
// M/3, the rest: a rigid joint, a welded one, a rigid near end), dt = h/2,
// against the same scheme's step on one bar of M elements. `idle`: every body
// moves at +1 away from the wall and the rigid joint has a gap, so no link is
// ever active (the line's step against the bar's: the ratio to report);
// `active`: the line moving at -1 onto the wall and pushed by a far-end force
// of -1, so the near end (from the first step) and the joint (once the
// wave has crossed body a) carry impulses at every step.
barimpact::Case rigid_line_case(long long M, const std::string& scheme, bool active) {
  const long long third = M / 3;
  barimpact::Case c = bars(M, {{"a", third}, {"b", third}, {"c", M - 2 * third}}, active ? "-1" : "1");
  // Strings by construction: GCC 12 warns (-Wrestrict, a false positive) on
  // assigning these literals once inlined.
  barimpact::JointData j{"a-b", "a", "b", {}, {}};
  j.law.law = barimpact::JointLaw::rigid;
  j.law.gap = active ? 0.0 : 0.01;
  c.joints = {j};
  c.near_end.law = barimpact::JointLaw::rigid;
  if (active) {
    c.far_end.law = barimpact::JointLaw::force;
    c.far_end.value = "-1";
  }
  c.time.scheme = scheme;
  c.time.step = 0.5 / static_cast<double>(M);
  c.time.end = 1.0;
  return c;
}

void BM_RigidLineStep(benchmark::State& state, const std::string& scheme, bool active) {
  time_steps(state, rigid_line_case(state.range(0), scheme, active));
}

// The single bar of M elements moving at +1 away from the rigid obstacle:
// the same scheme's step with its obstacle idle, dt = h/2.
void BM_RigidBarStep(benchmark::State& state, const std::string& scheme) {
  const long long M = state.range(0);
  auto c = barimpact::Case::from_string(
      fmt::format("[bar]\nelements = {}\n[initial]\nvelocity = \"1\"\n[obstacle]\nkind = \"rigid\"\n[time]\n"
                  "scheme = \"{}\"\nstep = {}\nend = 1\n",
                  M, scheme, 0.5 / static_cast<double>(M)));
  time_steps(state, c);
}

// The three-level bare loops' shared pieces: u^{n+1} over u^{n-1}, and the
// interior rows of the lumped pass (constant stencils, vectorised).
void rotate_levels(double*& um, double*& u, double*& up) {
  double* oldest = um;
  um = u;
  u = up;
  up = oldest;
}

inline void lumped_interior(const double* __restrict pm, const double* __restrict pu, double* __restrict pn,
                            std::size_t l, double kd, double ko, double dt2, double inv_m) {
  for (std::size_t j = 1; j < l; ++j)
    pn[j] = 2.0 * pu[j] - pm[j] + dt2 * (-(kd * pu[j] + ko * (pu[j - 1] + pu[j + 1])) * inv_m);
}

// The bare loop of lumped central differences: one fused, vectorisable pass
// u^{n+1}_j = 2u_j - u^{n-1}_j - (dt^2/m_j) (K u)_j, interior stencils constant.
void BM_BareCentralDifference(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0)) + 1, l = n - 1;
  const double h = 1.0 / static_cast<double>(n - 1), dt = h / 2, dt2 = dt * dt;
  const double kd = 2.0 / h, ko = -1.0 / h, inv_m = 1.0 / h;
  std::vector<double> a(n, 0.0), b(n, -dt), c(n, 0.0);
  double *um = a.data(), *u = b.data(), *up = c.data();
  for (auto _ : state) {
    const double* __restrict pu = u;
    const double* __restrict pm = um;
    double* __restrict pn = up;
    lumped_interior(pm, pu, pn, l, kd, ko, dt2, inv_m);
    pn[0] = 2.0 * pu[0] - pm[0] + dt2 * (-(0.5 * kd * pu[0] + ko * pu[1]) * 2.0 * inv_m);
    pn[l] = 2.0 * pu[l] - pm[l] + dt2 * (-(0.5 * kd * pu[l] + ko * pu[l - 1]) * 2.0 * inv_m);
    if (pn[0] < 0.0) pn[0] = 0.0;
    rotate_levels(um, u, up);
    benchmark::DoNotOptimize(u);
  }
  per_node_step(state, n);
}

// The bare loop of the characteristic scheme: the lumped pass at Courant 1
// and the free end advanced in characteristic variables (G read off the
// grid, F from the boundary condition), as the characteristic scheme does.
void BM_BareCharacteristic(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0)) + 1, l = n - 1;
  const double h = 1.0 / static_cast<double>(n - 1), dt = h, dt2 = dt * dt;
  const double kd = 2.0 / h, ko = -1.0 / h, inv_m = 1.0 / h;
  std::vector<double> a(n, 0.0), b(n, -dt), c(n, 0.0);
  double *um = a.data(), *u = b.data(), *up = c.data();
  double F[2] = {0.0, 0.0}, G[2] = {0.0, 0.0};
  for (auto _ : state) {
    const double* __restrict pu = u;
    const double* __restrict pm = um;
    double* __restrict pn = up;
    pn[l] = 2.0 * pu[l] - pm[l] + dt2 * (-(0.5 * kd * pu[l] + ko * pu[l - 1]) * 2.0 * inv_m);
    const double G_new = pu[1] - F[0], F_new = F[1] + G_new - G[1];
    pn[0] = F_new + G_new;
    F[0] = F[1], G[0] = G[1], F[1] = F_new, G[1] = G_new;
    lumped_interior(pm, pu, pn, l, kd, ko, dt2, inv_m);
    rotate_levels(um, u, up);
    benchmark::DoNotOptimize(u);
  }
  per_node_step(state, n);
}

// The bare loops of the implicit schemes below: the arithmetic of their
// steps on Example 1 (b = 0, f = 0, dt = h/2) written flat, with factors
// from the library's FactoredTridiagonal (eliminated from the far end), no
// contact, no budget, no checks. Each forms its right-hand side inside the
// sweep towards x = 0 and its update inside the sweep back.
struct BareSetup {
  explicit BareSetup(const benchmark::State& state)
      : line(barimpact::build_line(bench_case(state.range(0)))),
        n(line.nodes()),
        l(n - 1),
        h(1.0 / static_cast<double>(state.range(0))),
        dt(h / 2),
        mass(line.mass(true)),
        ka(line.stiffness()) {}
  barimpact::Line line;  // the one bar of bench_case (rho = E = 1 on [0, 1])
  std::size_t n, l;
  double h, dt;
  barimpact::Tridiagonal mass, ka;
};

using barimpact::FactoredTridiagonal;
using barimpact::Tridiagonal;

void BM_BareNewmark(benchmark::State& state) {
  const BareSetup s(state);
  const std::size_t n = s.n, l = s.l;
  const double dt = s.dt, bdt2 = 0.25 * dt * dt, gdt = 0.5 * dt, c1 = 0.25 * dt * dt, c2 = 0.5 * dt;
  const FactoredTridiagonal A(Tridiagonal::combine(1.0, s.mass, bdt2, s.ka), false);
  const double *inv = A.inverse_pivots(), *cp = A.coupling();
  const double kd = s.ka.diag[1], ko = s.ka.off[0];
  std::vector<double> uu(n, 0.0), vv(n, -1.0), aa(n, 0.0), yy(n, 0.0);
  for (auto _ : state) {
    double* __restrict u = uu.data();
    double* __restrict v = vv.data();
    double* __restrict acc = aa.data();
    double* __restrict y = yy.data();
    auto pred = [&](std::size_t j) { return u[j] + dt * v[j] + c1 * acc[j]; };
    double p_r = pred(l), p_c = pred(l - 1);
    double carry = -(0.5 * kd * p_r + ko * p_c);
    y[l] = carry;
    for (std::size_t j = l - 1; j > 0; --j) {
      const double p_l = pred(j - 1);
      const double r = -(kd * p_c + ko * (p_l + p_r));
      p_r = p_c;
      p_c = p_l;
      carry = r - cp[j + 1] * carry;
      y[j] = carry;
    }
    double x = (-(0.5 * kd * p_c + ko * p_r) - cp[1] * carry) * inv[0];
    for (std::size_t j = 0; j < n; ++j) {
      if (j > 0) x = y[j] * inv[j] - cp[j] * x;
      const double uj = pred(j), vj = v[j] + c2 * acc[j];
      acc[j] = x;
      u[j] = uj + bdt2 * x;
      v[j] = vj + gdt * x;
    }
    benchmark::DoNotOptimize(u[0]);
  }
  per_node_step(state, n);
}

void BM_BareMoreauJean(benchmark::State& state) {
  const BareSetup s(state);
  const std::size_t n = s.n, l = s.l;
  const double dt = s.dt, th = 0.5;
  const FactoredTridiagonal W(Tridiagonal::combine(1.0, s.mass, th * th * dt * dt, s.ka), false);
  const double *inv = W.inverse_pivots(), *cp = W.coupling();
  const Tridiagonal P = Tridiagonal::combine(1.0, s.mass, -dt * dt * th * (1.0 - th), s.ka);
  const double pd = P.diag[1], po = P.off[0], qd = -dt * s.ka.diag[1], qo = -dt * s.ka.off[0];
  std::vector<double> uu(n, 0.0), vv(n, -1.0), yy(n, 0.0);
  for (auto _ : state) {
    double* __restrict u = uu.data();
    double* __restrict v = vv.data();
    double* __restrict y = yy.data();
    double carry = 0.5 * pd * v[l] + po * v[l - 1] + (0.5 * qd * u[l] + qo * u[l - 1]);
    y[l] = carry;
    for (std::size_t j = l - 1; j > 0; --j) {
      const double r = pd * v[j] + po * (v[j - 1] + v[j + 1]) + (qd * u[j] + qo * (u[j - 1] + u[j + 1]));
      carry = r - cp[j + 1] * carry;
      y[j] = carry;
    }
    double x = (0.5 * pd * v[0] + po * v[1] + (0.5 * qd * u[0] + qo * u[1]) - cp[1] * carry) * inv[0];
    for (std::size_t j = 0; j < n; ++j) {
      if (j > 0) x = y[j] * inv[j] - cp[j] * x;
      u[j] += dt * (th * x + (1.0 - th) * v[j]);
      v[j] = x;
    }
    benchmark::DoNotOptimize(u[0]);
  }
  per_node_step(state, n);
}

void BM_BarePaoliSchatzman(benchmark::State& state) {
  const BareSetup s(state);
  const std::size_t n = s.n, l = s.l;
  const double dt2 = s.dt * s.dt;
  const FactoredTridiagonal M(s.mass, false);
  const double *inv = M.inverse_pivots(), *cp = M.coupling();
  const double kd = s.ka.diag[1], ko = s.ka.off[0];
  std::vector<double> a(n, 0.0), b(n, -s.dt), c(n, 0.0);
  double *um = a.data(), *u = b.data(), *up = c.data();
  for (auto _ : state) {
    const double* __restrict pu = u;
    const double* __restrict pm = um;
    double* __restrict pn = up;
    double y = -(0.5 * kd * pu[l] + ko * pu[l - 1]);
    pn[l] = y;
    for (std::size_t j = l - 1; j > 0; --j) {
      y = -(kd * pu[j] + ko * (pu[j - 1] + pu[j + 1])) - cp[j + 1] * y;
      pn[j] = y;
    }
    double x = (-(0.5 * kd * pu[0] + ko * pu[1]) - cp[1] * y) * inv[0];
    pn[0] = 2.0 * pu[0] - pm[0] + dt2 * x;
    for (std::size_t j = 1; j < n; ++j) {
      x = pn[j] * inv[j] - cp[j] * x;
      pn[j] = 2.0 * pu[j] - pm[j] + dt2 * x;
    }
    rotate_levels(um, u, up);
    benchmark::DoNotOptimize(u);
  }
  per_node_step(state, n);
}

void BM_BareMassRedistribution(benchmark::State& state) {
  const BareSetup s(state);
  const std::size_t n = s.n, l = s.l;
  const double dt = s.dt, c2 = 2.0 / (dt * dt);
  // The one bar of bench_case (rho = 1 on [0, 1]) as the line engine builds it.
  const Tridiagonal mt = barimpact::redistributed_mass(barimpact::build_line(bench_case(state.range(0))));
  Tridiagonal reduced{std::vector<double>(l), std::vector<double>(l - 1)};
  for (std::size_t j = 0; j < l; ++j) {
    reduced.diag[j] = c2 * mt.diag[j + 1] + 0.5 * s.ka.diag[j + 1];
    if (j + 1 < l) reduced.off[j] = c2 * mt.off[j + 1] + 0.5 * s.ka.off[j + 1];
  }
  const FactoredTridiagonal A(reduced, false);
  const double *inv = A.inverse_pivots(), *cp = A.coupling();
  const double md = mt.diag[2], mo = mt.off[2], kd = s.ka.diag[1], ko = s.ka.off[0];
  const double coupling = -0.5 / s.h, face = 0.0;
  std::vector<double> uu(n, 0.0), vv(n, -1.0), yy(n, 0.0);
  for (auto _ : state) {
    double* __restrict u = uu.data();
    double* __restrict v = vv.data();
    double* __restrict y = yy.data();
    auto sv = [&](std::size_t j) { return u[j] + dt * v[j]; };
    double carry = c2 * (0.5 * md * sv(l) + mo * sv(l - 1)) - 0.5 * (0.5 * kd * u[l] + ko * u[l - 1]);
    y[l - 1] = carry;
    for (std::size_t j = l - 1; j > 1; --j) {
      const double r =
          c2 * (md * sv(j) + mo * (sv(j - 1) + sv(j + 1))) - 0.5 * (kd * u[j] + ko * (u[j - 1] + u[j + 1]));
      carry = r - cp[j] * carry;
      y[j - 1] = carry;
    }
    const double r1 = c2 * (mt.diag[1] * sv(1) + mo * sv(2)) - 0.5 * (kd * u[1] + ko * (u[0] + u[2]));
    double x = (r1 - cp[1] * carry - coupling * face) * inv[0];  // node 0 on the obstacle
    v[0] = (face - u[0]) / dt;
    u[0] = face;
    for (std::size_t j = 1; j < n; ++j) {
      if (j > 1) x = y[j - 1] * inv[j - 1] - cp[j - 1] * x;
      v[j] = 2.0 * (x - u[j]) / dt - v[j];
      u[j] = x;
    }
    benchmark::DoNotOptimize(u[0]);
  }
  per_node_step(state, n);
}

}  // namespace

BENCHMARK(BM_PaperStep)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_PaperStepSequential)->RangeMultiplier(10)->Range(1000, 1'000'000);
BENCHMARK(BM_PaperStepPartitioned)->ArgsProduct({{1000, 3000, 10'000, 100'000, 1'000'000}, {8, 16, 32}});
BENCHMARK(BM_BareLoop)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_PaperBatch)->RangeMultiplier(10)->Range(100, 1'000'000);
const bool simd_paths_registered = [] {
  for (auto path : barimpact::supported_simd_paths())
    benchmark::RegisterBenchmark(fmt::format("BM_PaperBatchPath/{}", barimpact::to_string(path)).c_str(),
                                 BM_PaperBatchPath, path)
        ->Arg(1'000)
        ->Arg(10'000);
  return true;
}();
BENCHMARK(BM_BareCentralDifference)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_BareCharacteristic)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_BareNewmark)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_BareMoreauJean)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_BarePaoliSchatzman)->RangeMultiplier(10)->Range(100, 1'000'000);
BENCHMARK(BM_BareMassRedistribution)->RangeMultiplier(10)->Range(100, 1'000'000);

namespace {
// A pile of M elements driven into Smith's soil (central differences, dt
// the line's "auto" step): `soil` puts a side spring on every node and a
// Smith toe (the pile moving into the soil at 1 m/s, so that the springs
// load and slip), else the same pile with a free toe and no soil.
void BM_PileStep(benchmark::State& state, bool soil) {
  const long long M = state.range(0);
  std::string text = fmt::format(
      "[[body]]\nname = \"pile\"\nlength = 20.0\nelements = {}\narea = 0.01\nmodulus = 210e9\ndensity = 7850.0\n"
      "velocity = -1.0\n",
      M);
  if (soil)
    text +=
        "[body.shaft]\nultimate = 1e6\nquake = 0.0025\ndamping = 0.16\n[near_end]\nlaw = \"smith\"\n"
        "ultimate = 1e6\nquake = 0.0025\ndamping = 0.5\n";
  text += "[time]\nend = 1.0\nstep = \"auto\"\nscheme = \"central-difference\"\n";
  time_steps(state, barimpact::Case::from_string(text));
}

// The bare loop of a pile in Smith's soil: one fused pass of the lumped
// stencil and every node's side spring (slip, static force, Smith damping
// from the backward rate, the slip's and the damping's work), the arithmetic
// LineCentralDifference's stretch does.
void BM_BareSmithPile(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0)) + 1, l = n - 1;
  const double h = 1.0 / static_cast<double>(n - 1), dt = h / 2, dt2 = dt * dt, inv_dt = 1.0 / dt;
  const double kd = 2.0 / h, ko = -1.0 / h, inv_m = 1.0 / h;
  std::vector<double> a(n, 0.0), b(n, -dt), c(n, 0.0), slip(n, 0.0), ru(n, 1e-3), ks(n, 0.4), q(n, 2.5e-3), js(n, 0.16);
  double *um = a.data(), *u = b.data(), *up = c.data();
  double slip_work = 0.0, damping_work = 0.0;
  for (auto _ : state) {
    const double* __restrict pu = u;
    const double* __restrict pm = um;
    double* __restrict pn = up;
    double* __restrict ps = slip.data();
    double sw = 0.0, dw = 0.0;
    for (std::size_t j = 1; j < l; ++j) {
      double r = -(kd * pu[j] + ko * (pu[j - 1] + pu[j + 1]));
      const double w = -pu[j];
      const double sj = std::min(std::max(ps[j], w - q[j]), w + q[j]);
      sw += ru[j] * std::abs(sj - ps[j]);
      ps[j] = sj;
      const double rs = ks[j] * (w - sj), rd = js[j] * std::abs(rs) * (pm[j] - pu[j]) * inv_dt;
      r += rs + rd;
      pn[j] = 2.0 * pu[j] - pm[j] + dt2 * inv_m * r;
      dw += rd * 0.5 * (pm[j] - pn[j]);
    }
    pn[0] = 2.0 * pu[0] - pm[0] + dt2 * (-(0.5 * kd * pu[0] + ko * pu[1]) * 2.0 * inv_m);
    pn[l] = 2.0 * pu[l] - pm[l] + dt2 * (-(0.5 * kd * pu[l] + ko * pu[l - 1]) * 2.0 * inv_m);
    slip_work += sw;
    damping_work += dw;
    rotate_levels(um, u, up);
    benchmark::DoNotOptimize(u);
    benchmark::DoNotOptimize(slip_work);
    benchmark::DoNotOptimize(damping_work);
  }
  per_node_step(state, n);
}

const bool registered = [] {
  for (auto [scheme, rigid] :
       {std::pair{"paper", false}, std::pair{"newmark", false}, std::pair{"central-difference", false},
        std::pair{"central-difference", true}, std::pair{"characteristic", true}, std::pair{"paoli-schatzman", true},
        std::pair{"moreau-jean", true}, std::pair{"mass-redistribution", true}}) {
    const std::string name = fmt::format("BM_Scheme/{}/{}", scheme, rigid ? "rigid" : "elastic");
    benchmark::RegisterBenchmark(name.c_str(), BM_SchemeStep, std::string(scheme), rigid, false)
        ->RangeMultiplier(10)
        ->Range(100, 1'000'000);
  }
  // The paper's step with its two-ended solve at every M (BM_Scheme/paper/elastic partitions large bars).
  benchmark::RegisterBenchmark("BM_SchemeSequential/paper/elastic", BM_SchemeStep, std::string("paper"), false, true)
      ->RangeMultiplier(10)
      ->Range(100, 1'000'000);
  for (const char* scheme : {"central-difference", "newmark", "paper", "characteristic"}) {
    const std::string name = fmt::format("BM_Line/{}", scheme);
    benchmark::RegisterBenchmark(name.c_str(), BM_LineStep, std::string(scheme))
        ->RangeMultiplier(10)
        ->Range(100, 1'000'000);
  }
  for (const char* scheme : {"central-difference", "paper", "newmark", "moreau-jean", "mass-redistribution"})
    for (const char* material : {"elastic", "unyielded", "yielding"}) {
      const std::string name = fmt::format("BM_PlasticLine/{}/{}", scheme, material);
      benchmark::RegisterBenchmark(name.c_str(), BM_PlasticLineStep, std::string(scheme), std::string(material))
          ->RangeMultiplier(10)
          ->Range(100, 1'000'000);
    }
  for (bool soil : {false, true})
    benchmark::RegisterBenchmark(soil ? "BM_Pile/smith-soil" : "BM_Pile/no-soil", BM_PileStep, soil)
        ->RangeMultiplier(10)
        ->Range(100, 100'000);
  benchmark::RegisterBenchmark("BM_BareSmithPile", BM_BareSmithPile)->RangeMultiplier(10)->Range(100, 100'000);
  for (const char* scheme : {"moreau-jean", "paoli-schatzman", "mass-redistribution"}) {
    for (bool active : {false, true}) {
      const std::string name = fmt::format("BM_RigidLine/{}/{}", scheme, active ? "active" : "idle");
      benchmark::RegisterBenchmark(name.c_str(), BM_RigidLineStep, std::string(scheme), active)
          ->RangeMultiplier(10)
          ->Range(1000, 1'000'000);
    }
    const std::string name = fmt::format("BM_RigidBar/{}", scheme);
    benchmark::RegisterBenchmark(name.c_str(), BM_RigidBarStep, std::string(scheme))
        ->RangeMultiplier(10)
        ->Range(1000, 1'000'000);
  }
  return true;
}();
}  // namespace
BENCHMARK_MAIN();
