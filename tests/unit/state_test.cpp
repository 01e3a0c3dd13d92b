// A scheme's state kept between steps (state.hpp): what is kept, of every
// kind a scheme keeps, comes back as kept after any change, as often as
// asked; a new keep replaces the old; once primed, neither allocates.
#include "barimpact/schemes/state.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <initializer_list>
#include <tuple>
#include <vector>

// GCC 12 sees the copies of these small vectors of known size through
// vector's operator= and warns of an overflow that cannot happen (a known
// false positive of -Wstringop-overflow on inlined std::copy).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif

namespace barimpact {
namespace {

// A link's branch, kept as it is.
struct Branch {
  double force;
  int status;
  bool operator==(const Branch&) const = default;
};

// Writes `values` into `v` in place (a kept vector keeps its size).
void put(std::vector<double>& v, std::initializer_list<double> values) {
  std::copy(values.begin(), values.end(), v.begin());
}

// A scheme's members of every kind a scheme keeps: levels, a scalar, the
// links' branches, a level pointer, a small array.
struct Members {
  std::vector<double> u{1.0, 2.0, 3.0}, v{-1.0, 0.5};
  double t = 0.25;
  std::vector<Branch> branches{{1.5, 1}, {0.0, 0}};
  const double* level = u.data();
  std::array<double, 3> ends{0.5, 0.0, -0.5};
  auto state() { return std::tie(u, v, t, branches, level, ends); }
};
using Kept = KeptState<std::vector<double>, std::vector<double>, double, std::vector<Branch>, const double*,
                       std::array<double, 3>>;

TEST(KeptState, RestoreGivesBackWhatKeepCopiedOfEveryKind) {
  Members m;
  Kept kept;
  kept.keep(m.state());
  EXPECT_EQ(kept.get<0>(), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(kept.get<1>(), (std::vector<double>{-1.0, 0.5}));

  put(m.u, {7.0, 8.0, 9.0});
  m.v[1] = 4.0;
  m.t = 3.0;
  m.branches[0] = {9.0, 2};
  m.level = m.v.data();
  m.ends[2] = 7.0;
  for (int twice = 0; twice < 2; ++twice) {
    kept.restore(m.state());
    EXPECT_EQ(m.u, (std::vector<double>{1.0, 2.0, 3.0}));
    EXPECT_EQ(m.v, (std::vector<double>{-1.0, 0.5}));
    EXPECT_EQ(m.t, 0.25);
    EXPECT_EQ(m.branches, (std::vector<Branch>{{1.5, 1}, {0.0, 0}}));
    EXPECT_EQ(m.level, m.u.data());
    EXPECT_EQ(m.ends[2], -0.5);
    m.u[0] = -5.0;  // changed again after the first restore
  }

  // A new keep replaces the old copies.
  put(m.u, {4.0, 5.0, 6.0});
  kept.keep(m.state());
  put(m.u, {0.0, 0.0, 0.0});
  kept.restore(m.state());
  EXPECT_EQ(m.u, (std::vector<double>{4.0, 5.0, 6.0}));
  EXPECT_EQ(kept.get<0>(), m.u);
}

TEST(KeptState, OncePrimedKeepAndRestoreReuseTheStorage) {
  Members m;
  Kept kept;
  kept.keep(m.state());  // primes the copies
  const double* copy = kept.get<0>().data();
  const double* live = m.u.data();
  m.u[1] = 42.0;
  kept.keep(m.state());
  kept.restore(m.state());
  EXPECT_EQ(kept.get<0>().data(), copy) << "the kept copy moved: keep allocated";
  EXPECT_EQ(m.u.data(), live) << "the live vector moved: restore allocated";
}

}  // namespace
}  // namespace barimpact
