// A PaperBatch lane gives PaperScheme's numbers to the last bit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

#include "../support/run_case.hpp"
#include "barimpact/schemes/simd.hpp"
#include "barimpact/study/paper_batch.hpp"

namespace barimpact {
namespace {

bool same_bits(const std::vector<HistoryRow>& a, const std::vector<HistoryRow>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(HistoryRow)) == 0;
}

std::vector<Case> four_cases(const std::string& load, int elements = 60) {
  // Everything a lane may have of its own: k, gap, alpha, lambda, viscosity,
  // density, stiffness, initial data, far end, with a shared mesh and step count.
  const std::string base = "[bar]\nelements = " + std::to_string(elements) +
                           "\n[time]\nend = 3\n[output]\nfields_at = [0.5, 1.0]\n[load]\nbody_force = \"" + load +
                           "\"\n";
  return {testing::case_from(base, {"initial.velocity=\"-1\""}),
          testing::case_from(base, {"initial.velocity=\"-0.5 + x/4\"", "obstacle.stiffness=400", "obstacle.gap=0.01",
                                    "time.alpha=0.4"}),
          testing::case_from(base, {"initial.velocity=\"-1\"", "time.lambda=0.25", "bar.viscosity=0.02",
                                    "bar.density=2", "bar.stiffness=3"}),
          testing::case_from(base, {"initial.displacement=\"0.01*(1-x)\"", "bar.far_end=\"clamped\"", "time.step=0.005",
                                    "time.end=1.5", "obstacle.kind=none"})};
}

// Every SIMD path this processor runs (scalar, sse2, avx2: simd.hpp), forced
// in turn, gives every lane the single run's bits.
TEST(PaperBatch, LanesMatchSingleRunsToTheLastBitOnEverySimdPath) {
  const auto paths = supported_simd_paths();
  ASSERT_GE(paths.size(), 1u);
  for (SimdPath path : paths) {
    force_simd_path(path);
    // An even and an odd M: the two-ended solve's halves are equal, or not.
    for (auto [load, elements] : {std::pair{"0", 60}, std::pair{"-1 + x", 60}, std::pair{"-1 + x", 61}}) {
      const auto cases = four_cases(load, elements);
      std::vector<const Case*> ptrs;
      for (const auto& c : cases) ptrs.push_back(&c);
      const auto batch = run_batch(ptrs);
      ASSERT_EQ(batch.size(), 4u);
      for (std::size_t l = 0; l < 4; ++l) {
        const auto single = run(cases[l]);
        EXPECT_TRUE(same_bits(batch[l].history, single.history))
            << to_string(path) << " lane " << l << " load " << load;
        EXPECT_EQ(batch[l].fields.u, single.fields.u) << to_string(path) << " lane " << l;
        EXPECT_EQ(batch[l].summary.contacts.size(), single.summary.contacts.size()) << l;
      }
    }
  }
  force_simd_path(std::nullopt);
}

TEST(PaperBatch, TheWidestSupportedPathIsTheDefault) {
  force_simd_path(std::nullopt);
  const auto paths = supported_simd_paths();
  EXPECT_EQ(paths.front(), SimdPath::scalar);
#if defined(__x86_64__)
  EXPECT_EQ(paths.at(1), SimdPath::sse2);  // every x86-64 processor
#endif
  if (std::getenv("BARIMPACT_SIMD") == nullptr) {
    EXPECT_EQ(simd_path(), paths.back());
  }
}

TEST(PaperBatch, APartialBatchAndAFailingLane) {
  // Three lanes (the fourth pads); lane 1 blows up (alpha = 0, dt far above
  // its limit), the others complete unchanged.
  const std::string base =
      "[bar]\nelements = 100\n[initial]\nvelocity = \"-1\"\n[time]\nstep = 0.1\nend = 40\n[output]\nevery = 10\n";
  const std::vector<Case> cases{testing::case_from(base), testing::case_from(base, {"time.alpha=0"}),
                                testing::case_from(base, {"time.alpha=0.5"})};
  const auto batch = run_batch({&cases[0], &cases[1], &cases[2]});
  EXPECT_EQ(batch[1].summary.status, RunStatus::non_finite);
  for (std::size_t l : {0u, 2u}) {
    EXPECT_TRUE(batch[l].summary.complete);
    EXPECT_TRUE(same_bits(batch[l].history, run(cases[l]).history)) << l;
  }
  const auto single = run(cases[1]);
  EXPECT_EQ(batch[1].summary.steps_done, single.summary.steps_done);
  EXPECT_TRUE(same_bits(batch[1].history, single.history));
}

TEST(PaperBatch, RefusesCasesThatCannotShareIt) {
  const Case a = testing::case_from("");
  const Case b = testing::case_from("[bar]\nelements = 50");
  const Case v = testing::case_from("[obstacle]\nkind = \"viscoelastic\"\nviscosity = 0.1");
  const Case t = testing::case_from("[load]\nbody_force = \"t\"");
  EXPECT_FALSE(batchable(a, b));
  EXPECT_FALSE(batchable(a, v));
  EXPECT_FALSE(batchable(a, t));
  EXPECT_THROW((void)run_batch({&a, &b}), InputError);
}

}  // namespace
}  // namespace barimpact
