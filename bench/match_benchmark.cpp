// Signal matching's cost: one forward blow of the match's model (the steel
// pipe's record, its matched soil), and a whole match on 1 and 2 threads.
// Reported: blows per second of the fit (`blows_per_s`) against the single
// blow's rate, which says what the fit's bookkeeping and threads cost.
//
//   build/release/bench/barimpact_bench --benchmark_filter=BM_Match
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "barimpact/study/match.hpp"

namespace {

const char* const record_file = BARIMPACT_SOURCE_DIR "/examples/pda/steel-pipe.toml";

void BM_MatchForwardBlow(benchmark::State& state) {
  const auto record = barimpact::PileRecord::from_file(record_file);
  const auto signals = barimpact::read_pile_signals(record, record.match.low_pass);
  const auto m = barimpact::match_pile(record, 1);
  // The fit's own model: at rest from one rise time before the foot.
  const double rise = signals.t1() - signals.t_foot();
  const barimpact::MatchModel model(record, signals, std::max(signals.t.front(), signals.t_foot() - rise),
                                    signals.t.back());
  std::vector<double> force(m.computed.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(model.head_force(m.soil, m.first, force));
    benchmark::ClobberMemory();
  }
  state.counters["blows_per_s"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MatchForwardBlow)->Unit(benchmark::kMillisecond);

void BM_Match(benchmark::State& state) {
  const auto record = barimpact::PileRecord::from_file(record_file);
  long long blows = 0;
  for (auto _ : state) {
    const auto m = barimpact::match_pile(record, static_cast<int>(state.range(0)));
    blows += m.evaluations;
  }
  state.counters["blows_per_s"] = benchmark::Counter(static_cast<double>(blows), benchmark::Counter::kIsRate);
  state.counters["blows"] = benchmark::Counter(static_cast<double>(blows), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_Match)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
