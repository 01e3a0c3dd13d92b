// The time loop never allocates: every byte a run needs is taken before
// step 1. Counted by replacing the global operator new in this test program.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <functional>
#include <new>
#include <string>
#include <utility>

#include "../support/line_parts.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/partitioned_tridiagonal.hpp"
#include "barimpact/run/blow.hpp"
#include "barimpact/run/observer.hpp"
#include "barimpact/schemes/registry.hpp"

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

using testing::bar;
using testing::joint;
using testing::law_joint;
using testing::mass;

// What stepping a case through a run's observers left: the allocations
// counted from step 0 on, the rows and snapshots recorded, the contact
// episodes at x = 0, the largest plastic strain and the last row's D_plastic.
struct Counted {
  long allocations = 0;
  std::size_t rows = 0, snapshots = 0, contacts = 0;
  double largest_plastic_strain = 0.0, plastic_work = 0.0;
};

// Steps case `c` with the observers a run uses (history, fields, contact,
// links, plastic); `each` sees the scheme after every step, inside the count.
Counted count_loop(const Case& c, const std::function<void(const Scheme&)>& each = nullptr, Observer* extra = nullptr) {
  auto s = make_scheme(c);
  const Line line = build_line(c);
  const Probes probes(c, line);
  HistoryRecorder history(c.output.every, &probes);
  FieldRecorder fields(c, line, c.output.fields_at);
  ContactMonitor contact(line, c.time.step);
  LinkMonitor links(line);
  PlasticMonitor plastic(line, c.output.every);
  const std::array<Observer*, 5> observers{&history, &fields, &contact, &links, &plastic};
  const long long steps = c.step_count();
  for (auto* o : observers) o->begin(*s, steps);
  if (extra) extra->begin(*s, steps);
  s->start();
  allocations = 0;
  counting = true;
  for (long long n = 0; n <= steps; ++n) {
    if (n > 0) s->advance();
    for (auto* o : observers) o->observe(*s);
    if (extra) extra->observe(*s);
    if (each) each(*s);
  }
  counting = false;
  return {allocations.load(), history.rows().size(),
          fields.taken(),     contact.intervals().size(),
          plastic.largest(),  history.rows().empty() ? 0.0 : history.rows().back().D_plastic};
}

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
  const long long steps = c.step_count();
  const Counted r = count_loop(c);
  EXPECT_EQ(r.allocations, 0);
  EXPECT_EQ(r.rows, static_cast<std::size_t>(steps + 1));
  EXPECT_EQ(r.snapshots, 2u);
  EXPECT_GE(r.contacts, 1u);
}

// The rigid-contact schemes on a line of several bodies: rigid joints and a
// rigid near end that all close, a spring to a mass, gravity and a body force
// in t (the load recomputed every step), a far end driven at v(t); the same
// observers. Every step that settles contacts runs too.
TEST(TimeLoop, RigidContactLineSchemesNeverAllocate) {
  for (const char* scheme : {"moreau-jean", "paoli-schatzman", "mass-redistribution"}) {
    Case c;
    const bool redistribution = std::string(scheme) == "mass-redistribution";
    c.bodies = {bar("a", 1.0, 30, "-1"), bar("b", 1.0, 30, "-2"), mass("m", 0.5, -1.0)};
    c.joints = {joint("a", "b", JointLaw::rigid, 0.01),
                joint("b", "m", redistribution ? JointLaw::spring : JointLaw::rigid)};
    c.near_end.law = JointLaw::rigid;
    c.far_end.law = JointLaw::velocity;
    c.far_end.value = "-0.1 * t";
    c.load.gravity = 1.0;
    c.load.body_force = "-0.5 * t";
    c.time.scheme = scheme;
    c.time.step = redistribution || std::string(scheme) == "moreau-jean" ? 0.02 : 0.01;
    c.time.end = 3.0;
    c.output.fields_at = {1.0, 2.5};
    const long long steps = c.step_count();
    double largest = 0.0;
    const Counted r = count_loop(c, [&](const Scheme& s) { largest = std::max(largest, s.link_force(1)); });
    EXPECT_EQ(r.allocations, 0) << scheme;
    EXPECT_EQ(r.rows, static_cast<std::size_t>(steps + 1));
    EXPECT_GT(largest, 0.0) << scheme;  // the joint a-b pushed
  }
}

// The implicit penalty schemes on a line: an elastic near end, a
// viscoelastic joint with a gap, a cushion to a mass, a spring to a second
// mass, gravity and a body force in t, a far end driven at v(t); the paper
// scheme with its shift lambda. The near end and both unilateral joints push.
TEST(TimeLoop, ImplicitPenaltyLineSchemesNeverAllocate) {
  for (const char* scheme : {"paper", "newmark"}) {
    Case c;
    c.bodies = {bar("a", 1.0, 30, "-1"), bar("b", 1.0, 30, "-2"), mass("m", 0.5, -3.0), mass("n", 0.5, -3.0)};
    JointData ab = law_joint("a", "b", JointLaw::viscoelastic, 300.0, 3.0);
    ab.law.gap = 0.01;
    c.joints = {ab, law_joint("b", "m", JointLaw::cushion, 200.0, 0.5), law_joint("m", "n", JointLaw::spring, 50.0)};
    c.near_end.law = JointLaw::elastic;
    c.near_end.stiffness = 500.0;
    c.far_end.law = JointLaw::velocity;
    c.far_end.value = "-0.1 * t";
    c.load.gravity = 1.0;
    c.load.body_force = "-0.5 * t";
    c.time.scheme = scheme;
    c.time.lambda = std::string(scheme) == "paper" ? 0.25 : 0.0;
    c.time.step = 0.005;
    c.time.end = 3.0;
    c.output.fields_at = {1.0, 2.5};
    const long long steps = c.step_count();
    double largest[3] = {0, 0, 0};
    const Counted r = count_loop(c, [&](const Scheme& s) {
      for (std::size_t i = 0; i < 3; ++i) largest[i] = std::max(largest[i], s.link_force(i));
    });
    EXPECT_EQ(r.allocations, 0) << scheme;
    EXPECT_EQ(r.rows, static_cast<std::size_t>(steps + 1));
    for (double f : largest) EXPECT_GT(f, 0.0) << scheme;
  }
}

// `characteristic` on a line: a welded impedance jump, a mass welded on a
// bar's end, a free mass between two rigid joints with gaps (the links'
// Gauss-Seidel), a bar with a mass on its far end pushed by f(t), the near
// end driven at v(t); the same observers.
TEST(TimeLoop, CharacteristicLineSchemeNeverAllocates) {
  const Case c = testing::case_from(R"toml([[body]]
name = "a"
elements = 50
[[body]]
name = "b"
elements = 25
modulus = 4.0
[[body]]
name = "m1"
kind = "mass"
mass = 0.5
[[body]]
name = "m2"
kind = "mass"
mass = 0.3
velocity = -1.0
[[body]]
name = "c"
length = 0.5
elements = 50
density = 4.0
velocity = "-0.5"
[[body]]
name = "m3"
kind = "mass"
mass = 0.2
velocity = -0.5
[[joint]]
between = ["m1", "m2"]
law = "rigid"
gap = 0.01
[[joint]]
between = ["m2", "c"]
law = "rigid"
gap = 0.02
[near_end]
law = "velocity"
value = "0.1 * sin(3 * t)"
[far_end]
law = "force"
value = "-0.5 * t"
[time]
scheme = "characteristic"
step = 0.02
end = 5
[output]
fields_at = [1.0, 2.5]
)toml");
  const long long steps = c.step_count();
  double largest = 0.0;
  const Counted r = count_loop(c, [&](const Scheme& s) { largest = std::max(largest, s.link_force(1)); });
  EXPECT_EQ(r.allocations, 0);
  EXPECT_EQ(r.rows, static_cast<std::size_t>(steps + 1));
  EXPECT_GT(largest, 0.0);  // the joint m2-c pushed
}

// Two elastic-plastic bars onto a wall: `scheme`, `wall` the [near_end] table's keys.
std::string plastic_line(const char* scheme, const char* wall) {
  return fmt::format(R"toml([[body]]
name = "a"
elements = 40
velocity = "-1"
material = "plastic"
yield_stress = 0.2
hardening_modulus = 0.1
hardening = "isotropic"
[[body]]
name = "b"
elements = 20
velocity = "-1"
material = "plastic"
yield_stress = 0.3
[near_end]
{}
[time]
scheme = "{}"
step = 0.005
end = 3
[output]
fields_at = [1.0, 2.5]
)toml",
                     wall, scheme);
}

// Elastic-plastic bodies under central differences: the return map's pass,
// the plastic strains' forces and the monitor of the largest plastic strain.
TEST(TimeLoop, PlasticCentralDifferencesNeverAllocate) {
  const Case c = testing::case_from(plastic_line("central-difference", "law = \"rigid\""));
  const Counted r = count_loop(c);
  EXPECT_EQ(r.allocations, 0);
  EXPECT_LT(r.largest_plastic_strain, 0.0);  // it yielded, in compression
  EXPECT_GT(r.plastic_work, 0.0);
}

// The implicit schemes' plastic iteration: the snapshot's copies, the
// loads, the tangent's solve (plastic_iteration.hpp), with the links each
// can run.
TEST(TimeLoop, PlasticImplicitSchemesNeverAllocate) {
  for (const auto& [scheme, wall] :
       {std::pair{"newmark", "law = \"elastic\"\nstiffness = 50.0"}, std::pair{"moreau-jean", "law = \"rigid\""},
        std::pair{"mass-redistribution", "law = \"rigid\""},
        std::pair{"paper", "law = \"elastic\"\nstiffness = 50.0"}}) {
    std::string text = plastic_line(scheme, wall);
    // paper under the exponential shift too: u = exp(lambda t) z into arrays of its own
    if (std::string(scheme) == "paper") text.insert(text.find("step = "), "lambda = 0.5\n");
    const Counted r = count_loop(testing::case_from(text));
    EXPECT_EQ(r.allocations, 0) << scheme;
    EXPECT_LT(r.largest_plastic_strain, 0.0) << scheme;
    EXPECT_GT(r.plastic_work, 0.0) << scheme;
  }
}

}  // namespace
}  // namespace barimpact

namespace barimpact {
namespace {

// A blow of the example pile (Smith's toe and shaft, two cushions) under
// central differences, newmark and the paper's scheme (their soil
// iterations taking steps again), with the blow's monitor beside the run's observers.
TEST(TimeLoop, PileDrivingNeverAllocates) {
  for (const char* scheme : {"central-difference", "newmark", "paper"}) {
    const bool implicit = scheme != std::string("central-difference");
    const Case c = testing::example(
        "pile/steel-pipe-sand.toml",
        {fmt::format("time.scheme={}", scheme), implicit ? "time.step=1e-5" : "time.step=auto", "time.end=0.03"});
    const Line line = build_line(c);
    BlowMonitor blow(c, line);
    const Counted r = count_loop(c, nullptr, &blow);
    EXPECT_EQ(r.allocations, 0) << scheme;
    EXPECT_GT(blow.summary().set, 0.0) << scheme;
  }
}

// A diesel hammer's blow on the pile (its gas's pressure in the history, the
// ram's rebound watched) up to the ram's return past its ports.
TEST(TimeLoop, DieselBlowNeverAllocates) {
  const Case c = testing::example("pile/diesel-pipe-sand.toml", {"time.end=0.25"});
  const Line line = build_line(c);
  BlowMonitor blow(c, line);
  const Counted r = count_loop(c, nullptr, &blow);
  EXPECT_EQ(r.allocations, 0);
  EXPECT_GT(blow.summary().next_stroke, 0.0);
}

// The partitioned tridiagonal solve's workspace is sized when it is
// factored: its phases allocate nothing (a scheme calls them every step).
TEST(TimeLoop, PartitionedTridiagonalSolveNeverAllocates) {
  const std::size_t n = 1000;
  const Tridiagonal a{std::vector<double>(n, 3.0), std::vector<double>(n - 1, -1.0)};
  PartitionedTridiagonal solver(a, true, 16);
  std::vector<double> x(n, 1.0);
  allocations = 0;
  counting = true;
  solver.solve(x);
  solver.eliminate(x);
  solver.add_end_force(x, 2.0);
  solver.substitute(x);
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_EQ(solver.partitions(), 16u);  // the chunks' sweeps ran, not one sequential sweep
}

}  // namespace
}  // namespace barimpact
