// Reading a long line: N masses joined by springs, from the case file's text
// to a validated Case (Case::from_string), and on to the line the schemes
// step (build_line). Reading is O(N log N): 10^5 bodies in well under a
// second. Reported: seconds per body (the `per_body` counter).
//
//   build/release/bench/barimpact_bench --benchmark_filter=BM_ReadLine
#include <benchmark/benchmark.h>

#include <fmt/format.h>

#include <string>

#include "barimpact/case/case.hpp"
#include "barimpact/case/line_builder.hpp"

namespace {

// The line of issue 36: N unit masses, each joined to the next by a spring,
// the last one moving towards a clamped near end.
std::string long_line(long long bodies) {
  std::string text;
  for (long long i = 1; i <= bodies; ++i)
    text += fmt::format("[[body]]\nname = \"m{}\"\nkind = \"mass\"\nmass = 1.0\nvelocity = {}\n", i,
                        i == bodies ? -1.0 : 0.0);
  for (long long i = 1; i < bodies; ++i)
    text += fmt::format("[[joint]]\nbetween = [\"m{}\", \"m{}\"]\nlaw = \"spring\"\nstiffness = 1e4\n", i, i + 1);
  text += "[near_end]\nlaw = \"clamped\"\n[time]\nend = 0.01\nstep = 0.001\nscheme = \"central-difference\"\n";
  return text;
}

void per_body(benchmark::State& state) {
  state.counters["per_body"] = benchmark::Counter(
      static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ReadLine(benchmark::State& state) {
  const std::string text = long_line(state.range(0));
  for (auto _ : state) {
    const auto c = barimpact::Case::from_string(text, {}, "line.toml");
    benchmark::DoNotOptimize(c.joints.data());
  }
  per_body(state);
}

void BM_BuildLine(benchmark::State& state) {
  const auto c = barimpact::Case::from_string(long_line(state.range(0)), {}, "line.toml");
  for (auto _ : state) {
    const auto line = barimpact::build_line(c);
    benchmark::DoNotOptimize(line.x.data());
  }
  per_body(state);
}

}  // namespace

BENCHMARK(BM_ReadLine)->RangeMultiplier(10)->Range(1'000, 100'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuildLine)->RangeMultiplier(10)->Range(1'000, 100'000)->Unit(benchmark::kMillisecond);
