// A scheme's state kept between steps (step_snapshot.hpp): what is kept,
// of every kind it keeps, comes back as saved after any change, as often
// as asked, and a new save replaces the old.
#include "barimpact/schemes/step_snapshot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>
#include <vector>

namespace barimpact {
namespace {

// A trivially copyable branch of a link, kept by bytes.
struct Branch {
  double force;
  int status;
  bool operator==(const Branch&) const = default;
};

// Writes `values` into `v` in place (a kept vector must not move).
void put(std::vector<double>& v, std::initializer_list<double> values) {
  std::copy(values.begin(), values.end(), v.begin());
}

TEST(StepSnapshot, RestoreGivesBackWhatSaveKeptOfEveryKind) {
  std::vector<double> u{1.0, 2.0, 3.0}, v{-1.0, 0.5};
  double t = 0.25;
  std::vector<Branch> branches{{1.5, 1}, {0.0, 0}};
  const double* level = u.data();  // a scheme's level pointer
  StepSnapshot snapshot;
  snapshot.keep(u);
  snapshot.keep(v);
  snapshot.keep(t);
  snapshot.keep(branches);
  snapshot.keep_object(level);
  snapshot.save();
  EXPECT_EQ(snapshot.saved(0), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(snapshot.saved(1), (std::vector<double>{-1.0, 0.5}));

  put(u, {7.0, 8.0, 9.0});
  v[1] = 4.0;
  t = 3.0;
  branches[0] = {9.0, 2};
  level = v.data();
  for (int twice = 0; twice < 2; ++twice) {
    snapshot.restore();
    EXPECT_EQ(u, (std::vector<double>{1.0, 2.0, 3.0}));
    EXPECT_EQ(v, (std::vector<double>{-1.0, 0.5}));
    EXPECT_EQ(t, 0.25);
    EXPECT_EQ(branches, (std::vector<Branch>{{1.5, 1}, {0.0, 0}}));
    EXPECT_EQ(level, u.data());
    u[0] = -5.0;  // changed again after the first restore
  }

  // A new save replaces the old copies.
  put(u, {4.0, 5.0, 6.0});
  snapshot.save();
  put(u, {0.0, 0.0, 0.0});
  snapshot.restore();
  EXPECT_EQ(u, (std::vector<double>{4.0, 5.0, 6.0}));
  EXPECT_EQ(snapshot.saved(0), u);
}

}  // namespace
}  // namespace barimpact
