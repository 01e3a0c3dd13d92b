// The prefactored tridiagonal solve alone, sequential (FactoredTridiagonal:
// one chain of multiply-subtracts per sweep) against partitioned
// (PartitionedTridiagonal: P chunks' chains side by side), and a STREAM-like
// triad for the machine's memory bandwidth. Reported: seconds per node of
// one solve (the `per_node_step` counter, as step_benchmark.cpp), and the
// triad's bytes per second (24 per element: two read, one written).
//
//   build/release/bench/barimpact_bench --benchmark_filter='BM_(TridiagonalSolve|Triad)'
//       --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true
#include <benchmark/benchmark.h>

#include <fmt/format.h>

#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/partitioned_tridiagonal.hpp"
#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/line_newmark.hpp"
#include "barimpact/schemes/registry.hpp"

namespace {

using barimpact::Tridiagonal;

void per_node(benchmark::State& state, std::size_t nodes) {
  state.counters["per_node_step"] = benchmark::Counter(
      static_cast<double>(nodes), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// (M + dt^2 K) / h of a uniform bar held at both ends, dt = h: its smallest
// eigenvalue is just above 1, so repeated solves of one vector neither
// overflow nor decay to denormals (the low modes keep their size), and the
// solve's cost does not depend on the values.
Tridiagonal bar_matrix(std::size_t n) {
  return Tridiagonal{std::vector<double>(n, 4.0 / 6.0 + 2.0), std::vector<double>(n - 1, 1.0 / 6.0 - 1.0)};
}

std::vector<double> start_vector(std::size_t n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.5, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = u(rng);
  return x;
}

// One solve of the bar's matrix per iteration, factored by `factor(A)`.
template <class Factor>
void time_solves(benchmark::State& state, Factor factor) {
  const auto n = static_cast<std::size_t>(state.range(0));
  auto a = factor(bar_matrix(n));
  std::vector<double> x = start_vector(n);
  for (auto _ : state) {
    a.solve(x);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  per_node(state, n);
}

void BM_SequentialSolve(benchmark::State& state) {
  time_solves(state, [](const Tridiagonal& a) { return barimpact::FactoredTridiagonal(a, false); });
}

void BM_PartitionedSolve(benchmark::State& state, std::size_t partitions) {
  time_solves(state,
              [partitions](const Tridiagonal& a) { return barimpact::PartitionedTridiagonal(a, false, partitions); });
}

void BM_Triad(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 0.0), b = start_vector(n), c = start_vector(n);
  const double s = 0.5;
  for (auto _ : state) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(pa);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(24 * n));
  per_node(state, n);
}

// Newmark's step on BM_Scheme/newmark/elastic's case (a bar of M elements
// at -1 against an elastic obstacle, dt = h/2), its solve sequential or in
// `partitions` chunks: where the partitioned step starts to pay.
void BM_NewmarkStep(benchmark::State& state, std::size_t partitions) {
  const long long m = state.range(0);
  const auto c = barimpact::Case::from_string(
      fmt::format("[bar]\nelements = {}\n[initial]\nvelocity = \"-1\"\n[obstacle]\nkind = \"elastic\"\n[time]\n"
                  "scheme = \"newmark\"\nstep = {}\nend = 1\n",
                  m, 0.5 / static_cast<double>(m)));
  auto s = barimpact::make_scheme(c);
  auto& newmark = dynamic_cast<barimpact::LineNewmark&>(*s);
  if (newmark.use_partitions(partitions) != partitions) state.SkipWithError("the line cannot take the chunks asked");
  s->start();
  for (auto _ : state) {
    s->advance();
    benchmark::DoNotOptimize(s->end_displacement());
  }
  per_node(state, s->nodes());
}

// The partitions the partitioned solve takes by default in this benchmark
// (the fastest of the sweep below on the machine measured).
constexpr std::size_t best_partitions = 8;

const bool registered = [] {
  benchmark::RegisterBenchmark("BM_TridiagonalSolve/sequential", BM_SequentialSolve)
      ->RangeMultiplier(10)
      ->Range(10'000, 1'000'000);
  benchmark::RegisterBenchmark("BM_TridiagonalSolve/partitioned", BM_PartitionedSolve, best_partitions)
      ->RangeMultiplier(10)
      ->Range(10'000, 1'000'000);
  for (std::size_t p : {4, 16, 32, 64, 256}) {
    const std::string name = fmt::format("BM_TridiagonalSolve/partitioned/P{}", p);
    benchmark::RegisterBenchmark(name.c_str(), BM_PartitionedSolve, p)->RangeMultiplier(10)->Range(10'000, 1'000'000);
  }
  for (std::size_t p : {std::size_t{0}, best_partitions}) {
    const std::string name = p == 0 ? "BM_NewmarkStep/sequential" : "BM_NewmarkStep/partitioned";
    auto* b = benchmark::RegisterBenchmark(name.c_str(), BM_NewmarkStep, p);
    for (long long m : {100, 200, 500, 1000, 2000, 10'000, 100'000, 1'000'000}) b->Arg(m);
  }
  // 10^7 elements: three arrays of 80 MB, beyond the last-level cache.
  benchmark::RegisterBenchmark("BM_Triad", BM_Triad)->RangeMultiplier(10)->Range(10'000, 10'000'000);
  return true;
}();

}  // namespace
