// [units] system = "US": a display system over SI numbers.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../support/run_case.hpp"
#include "barimpact/case/case.hpp"
#include "barimpact/case/units.hpp"
#include "barimpact/run/output.hpp"

namespace barimpact {
namespace {

using testing::example;

// "US" is a display: the case's numbers stay SI, the console converts them.
TEST(Units, TheConsoleUnderUSPrintsKipInchKsiAndBlowsPerFoot) {
  const Case si = example("pile/steel-pipe-sand.toml", {"time.end=0.1", "output.fields_at=[]"});
  const Case us = example("pile/steel-pipe-sand.toml", {"time.end=0.1", "output.fields_at=[]", "units.system=US"});
  EXPECT_EQ(us.units, "US");
  const RunResult r = run(si);
  const std::string text = summary_text(us, r.summary);
  for (const char* unit : {" in (", " blows/ft)", " ksi", " kip-ft", " kip\n"})
    EXPECT_NE(text.find(unit), std::string::npos) << unit << text;
  for (const char* unit : {" mm", " MPa", " J ", "250 mm"})
    EXPECT_EQ(text.find(unit), std::string::npos) << unit << text;
  const BlowSummary& b = *r.summary.blow;
  EXPECT_NE(text.find(fmt::format("set {:.4g} in ({:.3g} blows/ft)", b.set / 0.0254, b.blows_per_m() * 0.3048)),
            std::string::npos)
      << text;
  const std::string json = summary_json(us, r.summary);
  for (const char* part : {"\"system\": \"US\"", "\"numbers\": \"SI\"", "\"stress\": \"Pa\"", "\"stress\": \"ksi\"",
                           "\"blow_count\": \"blows/ft\""})
    EXPECT_NE(json.find(part), std::string::npos) << part << json;
}

}  // namespace
}  // namespace barimpact
