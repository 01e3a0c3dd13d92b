// The time loop never allocates: every byte a run needs is taken before
// step 1. Counted by replacing the global operator new in this test program.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <new>

#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/observer.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  if (counting) ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace barimpact {
namespace {

TEST(TimeLoop, NeverAllocates) {
  // Every branch of the step: viscosity, shift, a load that depends on t,
  // contact with a gap; observers recording every row and two snapshots.
  const Case c = testing::case_from(R"toml([bar]
viscosity = 0.01
elements = 50
[load]
body_force = "-1 - x * t"
[initial]
velocity = "-1"
[obstacle]
gap = 0.001
[time]
end = 3
lambda = 0.25
[output]
fields_at = [1.0, 2.5]
)toml");
  auto scheme = make_scheme(c);
  const Line line = build_line(c);
  const Probes probes(c, line);
  HistoryRecorder history(c.output.every, &probes);
  FieldRecorder fields(c, line, c.output.fields_at);
  ContactMonitor contact(c.obstacle);
  LinkMonitor links(line);
  const std::array<Observer*, 4> observers{&history, &fields, &contact, &links};
  const long long steps = c.step_count();
  for (auto* o : observers) o->begin(*scheme, steps);
  scheme->start();
  counting = true;
  for (long long n = 0; n <= steps; ++n) {
    if (n > 0) scheme->advance();
    for (auto* o : observers) o->observe(*scheme);
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_EQ(history.rows().size(), static_cast<std::size_t>(steps + 1));
  EXPECT_EQ(fields.taken(), 2u);
  EXPECT_GE(contact.intervals().size(), 1u);
}

}  // namespace
}  // namespace barimpact
