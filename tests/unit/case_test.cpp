#include "barimpact/case/case.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "../support/pile.hpp"
#include "../support/run_case.hpp"
#include "../support/scratch_directory.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {
namespace {

using testing::case_from;
using testing::pile_toml;
using testing::refusal;

TEST(Case, EmptyFileGivesTheDocumentedDefaults) {
  const Case c = case_from("");
  EXPECT_EQ(c.one_bar()->bar.length, 1.0);
  EXPECT_EQ(c.one_bar()->bar.density, 1.0);
  EXPECT_EQ(c.one_bar()->bar.stiffness, 1.0);
  EXPECT_EQ(c.one_bar()->bar.viscosity, 0.0);
  EXPECT_EQ(c.one_bar()->bar.elements, 100);
  EXPECT_EQ(c.load.body_force, "0");
  EXPECT_EQ(c.one_bar()->initial.displacement, "0");
  EXPECT_EQ(c.one_bar()->initial.velocity, "0");
  EXPECT_EQ(c.one_bar()->obstacle.kind, ObstacleKind::elastic);
  EXPECT_EQ(c.one_bar()->obstacle.stiffness, 100.0);
  EXPECT_EQ(c.one_bar()->obstacle.gap, 0.0);
  EXPECT_EQ(c.time.end, 1.0);
  EXPECT_EQ(c.time.step, 0.01);
  EXPECT_EQ(c.time.scheme, "paper");
  EXPECT_EQ(c.time.alpha, 0.25);
  EXPECT_EQ(c.time.lambda, 0.0);
  EXPECT_EQ(c.output.every, 1);
  EXPECT_TRUE(c.output.fields_at.empty());
  EXPECT_EQ(c.step_count(), 100);
  EXPECT_EQ(c.one_bar()->bar.far_end, FarEnd::free);
  EXPECT_EQ(c.one_bar()->obstacle.viscosity, 0.0);
  EXPECT_EQ(c.time.beta, 0.25);
  EXPECT_EQ(c.time.gamma, 0.5);
  EXPECT_EQ(c.time.theta, 0.5);
  EXPECT_EQ(c.time.restitution, 0.0);
}

TEST(Case, RefusesACaseFileThatIsNotARegularFileWithoutOpeningIt) {
  // Opening a FIFO blocks until a writer comes: refused before.
  const testing::ScratchDirectory dir("case-fifo");
  const auto fifo = dir.path() / "case.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    (void)Case::from_file(fifo);
    ADD_FAILURE() << "accepted a FIFO";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("case.fifo: the case file is a named pipe"), std::string::npos) << e.what();
  }
}

TEST(Case, ReadsAShellsPipeWhichHasItsWriter) {
  // `barimpact run <(generate-case)`: /dev/fd/N, an anonymous pipe.
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  const std::string text = "[bar]\nelements = 7\n";
  ASSERT_EQ(::write(ends[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
  ::close(ends[1]);
  const Case c = Case::from_file(fmt::format("/dev/fd/{}", ends[0]));
  ::close(ends[0]);
  EXPECT_EQ(c.bodies.front().elements, 7);
}

TEST(Case, UnitsSystemIsSIUSOrNoneAndIsWrittenBack) {
  EXPECT_EQ(case_from("").units, "none");
  const Case si = case_from("[units]\nsystem = \"SI\"\n");
  EXPECT_EQ(si.units, "SI");
  EXPECT_NE(si.to_toml().find("[units]\nsystem = \"SI\""), std::string::npos);
  EXPECT_EQ(Case::from_string(si.to_toml(), {}, "again").units, "SI");
  EXPECT_EQ(case_from("[units]\nsystem = \"US\"\n").units, "US");
  EXPECT_REFUSED("[units]\nsystem = \"imperial\"", "units.system", "\"SI\", \"US\" or \"none\"");
  EXPECT_REFUSED("[units]\nlength = \"m\"", "unknown key units.length");
}

TEST(Case, OutputFormatIsCsvOrHdf5AndIsWrittenBack) {
  const Case plain = case_from("");
  EXPECT_EQ(plain.output.format, OutputFormat::csv);
  EXPECT_EQ(plain.output.compression, 1);
  EXPECT_NE(plain.to_toml().find("[output]\nevery = 1\nfields_at = []\nformat = \"csv\"\ncompression = 1\n"),
            std::string::npos);
  const Case h5 = case_from("[output]\nformat = \"hdf5\"\ncompression = 0\n");
  EXPECT_EQ(h5.output.format, OutputFormat::hdf5);
  EXPECT_EQ(h5.output.compression, 0);
  const Case again = Case::from_string(h5.to_toml(), {}, "again");
  EXPECT_EQ(again.output.format, OutputFormat::hdf5);
  EXPECT_EQ(again.output.compression, 0);
  EXPECT_REFUSED("[output]\nformat = \"netcdf\"", "output.format", "must be \"csv\" or \"hdf5\" (got \"netcdf\")");
  EXPECT_REFUSED("[output]\nformat = 5", "output.format", "must be a string");
  EXPECT_REFUSED("[output]\ncompression = 10", "output.compression", "from 0 (none) to 9 (got 10)");
  EXPECT_REFUSED("[output]\ncompression = -1", "output.compression", "(got -1)");
  EXPECT_REFUSED("[output]\ncompression = 1.5", "output.compression", "must be an integer");
}

TEST(Case, RefusesSchemesThatDoNotFitAndNamesThoseThatDo) {
  EXPECT_REFUSED("[obstacle]\nkind = \"rigid\"", "time.scheme", "cannot run the rigid link \"near_end\"",
                 "central-difference, mass-redistribution, paoli-schatzman, moreau-jean, characteristic");
  EXPECT_REFUSED("[time]\nscheme = \"moreau-jean\"", "time.scheme", "paper, newmark, central-difference");
  EXPECT_REFUSED("[bar]\nviscosity = 0.1\n[obstacle]\nkind = \"rigid\"\n[time]\nscheme = \"mass-redistribution\"",
                 "time.scheme", "elastic bodies", "viscosity 0");
  EXPECT_REFUSED("[time]\nscheme = \"central-difference\"\nstep = 0.01", "time.step", "stable limit");
  EXPECT_REFUSED("[obstacle]\nkind = \"rigid\"\n[time]\nscheme = \"characteristic\"\nstep = 0.02", "time.step",
                 "h/c = 0.01");
}

// Reading a case checks the scheme's name (and its keys' ranges) only; what
// the scheme makes of the step and the line is decided where the scheme is
// made (fit_scheme), with the same message naming where the key was set.
TEST(Case, ReadingChecksTheSchemesNameOnlyAndFittingTheRest) {
  const std::string above = "[time]\nscheme = \"central-difference\"\nstep = 0.05";
  const Case read = Case::from_string(above, {}, "test.toml");  // reads: the limit is the scheme's to check
  EXPECT_TRUE(read.time.step_given);
  try {
    (void)fit_scheme(read);
    ADD_FAILURE() << "fitted";
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("test.toml:3: time.step = 0.05 is above central-difference's stable limit", 0), 0u)
        << e.what();
  }
  // "auto" is left to the scheme: 0.9 of h/c = 0.01 on the default bar, free.
  const Case automatic = Case::from_string(
      "[obstacle]\nkind = \"none\"\n[time]\nscheme = \"central-difference\"\nstep = \"auto\"", {}, "t");
  EXPECT_TRUE(automatic.time.step_auto);
  EXPECT_FALSE(automatic.time.step_given);
  EXPECT_DOUBLE_EQ(fit_scheme(automatic).c.time.step, auto_step_fraction * 0.01);
  // An unknown name is the reading's refusal.
  EXPECT_THROW((void)Case::from_string("[time]\nscheme = \"leapfrog\"", {}, "t"), InputError);
  // The rules that follow from the step wait for it when the scheme sets it
  // (h/c = 0.01 here, not the default step), and are checked then.
  const std::string rigid = "[obstacle]\nkind = \"rigid\"\n[time]\nscheme = \"characteristic\"\nend = 0.004";
  const Case early = Case::from_string(rigid, {}, "test.toml");
  EXPECT_THROW((void)fit_scheme(early), InputError);  // time.end < h/c
  EXPECT_EQ(fit_scheme(Case::from_string(rigid, {{"time.end=0.02"}}, "test.toml")).c.step_count(), 2);
}

TEST(Case, CharacteristicSetsTheStep) {
  const Case c = case_from("[bar]\nstiffness = 4\n[obstacle]\nkind = \"rigid\"\n[time]\nscheme = \"characteristic\"");
  EXPECT_DOUBLE_EQ(c.time.step, 0.005);  // h / c = 0.01 / 2
  EXPECT_EQ(c.step_count(), 200);
}

TEST(Case, StepCountIsTheFirstStepTimeAtOrAfterTheEnd) {
  EXPECT_EQ(case_from("[time]\nend = 4\nstep = 0.01").step_count(), 400);
  EXPECT_EQ(case_from("[time]\nend = 6.0\nstep = 0.01").step_count(), 600);
  EXPECT_EQ(case_from("[time]\nend = 1.05\nstep = 0.1").step_count(), 11);
}

TEST(Case, IntegersAreAcceptedWhereNumbersAreExpected) {
  const Case c = case_from("[bar]\nlength = 2\n[load]\nbody_force = -1\n");
  EXPECT_EQ(c.one_bar()->bar.length, 2.0);
  EXPECT_EQ(c.load.body_force, "-1");
}

TEST(Case, ResolvedTomlRunsTheSameCase) {
  const Case c = case_from(R"toml([bar]
length = 0.30000000000000004
elements = 7
viscosity = 0.125
[load]
body_force = "sin(x) * t"
[initial]
velocity = "-1 + x/2"
[obstacle]
kind = "none"
gap = 1e-5
[time]
end = 2
step = 0.1
lambda = 0.25
alpha = 0.5
[output]
every = 3
fields_at = [0.5, 1]
)toml",
                           {});
  const Case again = case_from(c.to_toml());
  EXPECT_EQ(again.to_toml(), c.to_toml());
  EXPECT_EQ(again.one_bar()->bar.length, 0.30000000000000004);
  EXPECT_EQ(again.one_bar()->initial.velocity, "-1 + x/2");
  EXPECT_EQ(again.one_bar()->obstacle.kind, ObstacleKind::none);
  EXPECT_EQ(again.output.fields_at, (std::vector<double>{0.5, 1.0}));
}

TEST(Case, OverridesReadTomlValuesAndBareWords) {
  const Case c = case_from("", {"bar.elements=7", "obstacle.kind=none", "load.body_force=-x*t",
                                "output.fields_at=[0.25, 0.5]", "time.scheme=\"paper\""});
  EXPECT_EQ(c.one_bar()->bar.elements, 7);
  EXPECT_EQ(c.one_bar()->obstacle.kind, ObstacleKind::none);
  EXPECT_EQ(c.load.body_force, "-x*t");
  EXPECT_EQ(c.output.fields_at, (std::vector<double>{0.25, 0.5}));
}

TEST(Case, RefusesUnknownSectionsAndKeys) {
  EXPECT_REFUSED("[bars]\nlength = 1", "test.toml:1", "unknown section [bars]");
  EXPECT_REFUSED("[bar]\nlenght = 1", "test.toml:2", "unknown key bar.lenght", "length");
  EXPECT_REFUSED("length = 1", "length", "section");
}

TEST(Case, RefusesWrongTypes) {
  EXPECT_REFUSED("[bar]\nlength = \"one\"", "test.toml:2", "bar.length", "must be a number");
  EXPECT_REFUSED("[bar]\nelements = 10.5", "bar.elements", "must be an integer");
  EXPECT_REFUSED("[time]\nscheme = 3", "time.scheme", "must be a string");
  EXPECT_REFUSED("[output]\nfields_at = [\"a\"]", "output.fields_at", "numbers");
  EXPECT_REFUSED("[initial]\nvelocity = true", "initial.velocity", "expression");
}

TEST(Case, RefusesValuesOutsideTheirRange) {
  EXPECT_REFUSED("[bar]\nstiffness = 0", "test.toml:2", "bar.stiffness", "> 0");
  EXPECT_REFUSED("[bar]\ndensity = -1", "bar.density", "> 0");
  EXPECT_REFUSED("[bar]\nviscosity = -0.1", "bar.viscosity", ">= 0");
  EXPECT_REFUSED("[bar]\nlength = 0", "bar.length", "> 0");
  EXPECT_REFUSED("[bar]\nelements = 0", "bar.elements", ">= 1");
  EXPECT_REFUSED("[obstacle]\nstiffness = -5", "obstacle.stiffness", ">= 0");
  EXPECT_REFUSED("[time]\nstep = 0", "time.step", "> 0");
  EXPECT_REFUSED("[time]\nstep = -0.1", "time.step", "> 0");
  EXPECT_REFUSED("[time]\nend = 0.001", "time.end", ">= time.step");
  EXPECT_REFUSED("[time]\nalpha = 0.51", "time.alpha", "[0, 1/2]");
  EXPECT_REFUSED("[time]\nalpha = -0.01", "time.alpha", "[0, 1/2]");
  EXPECT_REFUSED("[time]\nlambda = -1", "time.lambda", ">= 0");
  EXPECT_REFUSED("[output]\nevery = 0", "output.every", ">= 1");
  EXPECT_REFUSED("[output]\nfields_at = [2.0]", "output.fields_at", "[0, 1]");
  EXPECT_REFUSED("[obstacle]\nkind = \"glass\"", "obstacle.kind", "none, elastic, viscoelastic, rigid");
  EXPECT_REFUSED("[time]\nscheme = \"euler\"", "time.scheme", "paper");
  EXPECT_REFUSED("[bar]\nlength = nan", "bar.length", "finite");
  EXPECT_REFUSED("[bar]\nfar_end = \"pinned\"", "bar.far_end", "free, clamped");
  EXPECT_REFUSED("[obstacle]\nviscosity = -1", "obstacle.viscosity", ">= 0");
  EXPECT_REFUSED("[time]\nbeta = 0.6", "time.beta", "[0, 1/2]");
  EXPECT_REFUSED("[time]\ngamma = 0.4", "time.gamma", "[1/2, 1]");
  EXPECT_REFUSED("[time]\ntheta = 0.3", "time.theta", "[1/2, 1]");
  EXPECT_REFUSED("[time]\nrestitution = 1.5", "time.restitution", "[0, 1]");
  EXPECT_REFUSED("[time]\npartitions = 0", "time.partitions", "[1, 4096]");
  EXPECT_REFUSED("[time]\npartitions = 5000", "time.partitions", "[1, 4096]");
  EXPECT_REFUSED("[time]\npartitions = \"many\"", "time.partitions", "\"auto\"");
  EXPECT_REFUSED("[time]\npartitions = 2.5", "time.partitions", "integer");
  EXPECT_REFUSED("[bar]\nfar_end = \"clamped\"\n[initial]\nvelocity = \"-1\"", "initial.velocity", "clamped end");
}

TEST(Case, RefusesExpressionsThatDoNotParseOrAreNotFinite) {
  EXPECT_REFUSED("[initial]\nvelocity = \"-1 +\"", "test.toml:2", "initial.velocity", "not a valid expression");
  EXPECT_REFUSED("[initial]\ndisplacement = \"y * 2\"", "initial.displacement", "unknown name \"y\"");
  EXPECT_REFUSED("[load]\nbody_force = \"sqrt(-1)\"", "load.body_force", "finite");
  EXPECT_REFUSED("[load]\nbody_force = \"1 / x\"", "load.body_force", "finite", "x = 0");
  EXPECT_REFUSED("[initial]\nvelocity = \"\"", "initial.velocity", "empty");
}

TEST(Case, RefusesBadTomlWithItsLine) {
  EXPECT_REFUSED("[bar]\nlength = 1\nlength = 2", "test.toml:3", "not valid TOML");
  EXPECT_REFUSED("[bar\n", "test.toml:1", "not valid TOML");
}

TEST(Case, RefusesBadOverridesNamingTheOption) {
  const auto bad = [](const std::string& set, const char* part) {
    const std::string msg = refusal("", {set});
    EXPECT_NE(msg.find("--set " + set), std::string::npos) << msg;
    EXPECT_NE(msg.find(part), std::string::npos) << msg;
  };
  bad("bar.stiffness=-1", "> 0");
  bad("bar.elements", "section.key=value");
  bad("elements=3", "section.key=value");
  bad("bar.lenght=2", "unknown key");
  bad("nosuch.key=2", "unknown section");
  bad("bar.elements=many", "integer");
  bad("bar.length=", "empty");
}

TEST(Case, RefusesMissingAndUnreadableFiles) {
  EXPECT_THROW((void)Case::from_file("/nonexistent/case.toml"), InputError);
  EXPECT_THROW((void)Case::from_file(std::filesystem::temp_directory_path()), InputError);
  try {
    (void)Case::from_file("/nonexistent/case.toml");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/case.toml"), std::string::npos);
  }
}

TEST(Case, EmptyCaseFileGivesTheDefaults) {
  const auto path = std::filesystem::temp_directory_path() / "barimpact-empty-case.toml";
  std::ofstream(path).close();
  const Case c = fit_scheme(Case::from_file(path)).c;
  std::filesystem::remove(path);
  EXPECT_EQ(c.to_toml(), case_from("").to_toml());
}

TEST(Case, ReadsNonAsciiTextInCommentsAndStringValues) {
  const Case c = case_from(
      "# \xCF\x81 = 7800 kg/m\xC2\xB3\n[bar] # \xC3\xA9\nlength = 2.0 # \xC2\xA7\n[output]\nfields_at = [ # \xC3\xBC\n "
      " 0.5,\n]\n");
  EXPECT_EQ(c.one_bar()->bar.length, 2.0);
  // A word with a non-ASCII letter is read, then refused as a word.
  EXPECT_REFUSED("[time]\nscheme = \"p\xC3\xA4per\"", "time.scheme", "must be one of");
}

TEST(Case, RefusesNonAsciiTextWhereTomlDoesNotAllowIt) {
  // toml++ 3.3 would reach undefined behaviour classifying these characters.
  EXPECT_REFUSED("[bar]\nlength = 1\xC3\xA9", "test.toml:2:11", "non-ASCII character outside a string");
  EXPECT_REFUSED("[bar]\n\"l\xC3\xA9ngth\" = 1", "test.toml:2:3", "non-ASCII character in a key");
  EXPECT_REFUSED("[\xC3\xA9]", "test.toml:1:2", "non-ASCII");
  EXPECT_REFUSED("[load]\nbody_force = \"\"\"\\\n  \xC2\xA7\"\"\"", "test.toml:3:3", "line-ending backslash");
  EXPECT_REFUSED("[load]\nbody_force = \"\"\"\\\xC2\xA7\"\"\"", "after a backslash");
  EXPECT_REFUSED("[bar]\nlength = 715\"\xCC\x9A\"", "outside a string");
  const std::string msg = refusal("", {"bar.length=1\xC3\xA9"});  // not TOML: read as a word
  EXPECT_NE(msg.find("must be a number (got a string)"), std::string::npos) << msg;
}

TEST(Case, ErrorsStayOneLineWhateverTheInputHolds) {
  EXPECT_REFUSED("[bar]\n\"a\\nb\" = 1", "unknown key bar.a\\nb");
  EXPECT_REFUSED("d. 6=t\n0(sep = 0.01\n", "not valid TOML");  // toml++ quotes the text it saw
  EXPECT_REFUSED("[load]\nbody_force = \"1 +\\n\"", "load.body_force");
}

TEST(Case, RefusesAnExpressionThatMuparserWouldReadOnlyInPart) {
  // muparser stops at a NUL: "-1\0 + 2" would run as -1.
  EXPECT_REFUSED("[initial]\nvelocity = \"-1\\u0000 + 2\"", "initial.velocity", "NUL");
  const std::string msg = refusal("", {std::string("initial.velocity=t\0junk", 23)});
  EXPECT_NE(msg.find("NUL"), std::string::npos) << msg;
}

TEST(Case, ResolvedTomlKeepsEveryFieldTimeExactly) {
  // Times below 1 are written by hand: toml++ 3.3 sizes float arrays with
  // size_t(log10(x)) (undefined for x < 1).
  const std::vector<double> times{0.0, 1e-5, 0.0004, 0.1 + 0.2, 1.0, 3.75};
  std::string list;
  for (double t : times) list += fmt::format("{}{}", list.empty() ? "" : ", ", t);
  const Case c = case_from("[time]\nend = 4\n[output]\nfields_at = [" + list + "]\n");
  const Case again = case_from(c.to_toml());
  EXPECT_EQ(again.output.fields_at, times);
  EXPECT_EQ(again.to_toml(), c.to_toml());
}

TEST(Case, ChecksAConstantExpressionOnceNotAtEveryNode) {
  // 10^8 nodes: a pass over them per expression would take seconds.
  const Case c =
      case_from("[bar]\nelements = 100000000\n[obstacle]\nkind = \"none\"\n[time]\nend = 1e-9\nstep = 1e-9\n");
  EXPECT_EQ(c.one_bar()->bar.elements, 100'000'000);
  EXPECT_REFUSED("[bar]\nelements = 100000000\n[initial]\nvelocity = \"0/0\"", "initial.velocity", "finite");
}

// A pile's modulus in MPa or GPa, its density in t/m^3: no pile has such a
// material in SI (before, the run went on with a wave of 5 m/s).
TEST(SmithCase, RefusesAPileMaterialInAnotherUnitNamingIt) {
  auto with = [](const std::string& from, const std::string& to) {
    std::string s = pile_toml;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  EXPECT_REFUSED(with("modulus = 210e9", "modulus = 210000"), "body.pile.modulus = 210000: MPa? outside");
  EXPECT_REFUSED(with("modulus = 210e9", "modulus = 210"), "body.pile.modulus = 210: GPa?");
  EXPECT_REFUSED(with("density = 7850.0", "density = 7.85"), "body.pile.density = 7.85: t/m^3?");
  // The same numbers in a case without soil or a blow are not a pile's.
  EXPECT_NO_THROW(case_from("[[body]]\nname = \"rod\"\nmodulus = 210000\ndensity = 7.85\n"));
}

TEST(SmithCase, RefusesWhatItCannotRun) {
  EXPECT_REFUSED(std::string(pile_toml) + "[far_end]\nlaw = \"smith\"\nultimate = 1.0\n", "far_end.law",
                 "near-end law only");
  EXPECT_REFUSED(std::string(pile_toml) + "[far_end]\nlaw = \"free\"\nquake = 1.0\n", "far_end.quake",
                 "not used by law \"free\"");
  auto with = [](const std::string& from, const std::string& to) {
    std::string s = pile_toml;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  EXPECT_REFUSED(with("ultimate = 200e3\n", ""), "near_end.ultimate", "is required");
  EXPECT_REFUSED(with("ultimate = 300e3\n", ""), "body.pile.shaft.ultimate", "is required");
  EXPECT_REFUSED(with("damping = 0.0\n[near_end]", "skin = 1.0\n[near_end]"), "body.pile.shaft.skin",
                 "not a shaft key");
  EXPECT_REFUSED(with("ultimate = 300e3\n", "ultimate = 300e3\nembedded = 11.0\n"), "body.pile.shaft.embedded",
                 "(0, 10]");
  EXPECT_REFUSED(with("quake = 0.0025\ndamping = 0.0\n[time]", "quake = 0.0\ndamping = 0.0\n[time]"), "near_end.quake",
                 "> 0");
  EXPECT_REFUSED(with("damping = 0.0\n[time]", "damping = 0.0\ndamping_law = \"case\"\n[time]"), "near_end.damping_law",
                 "smith or viscous");
  EXPECT_REFUSED(with("scheme = \"central-difference\"", "scheme = \"paper\""), "time.step", "\"auto\"",
                 "explicit schemes");
  EXPECT_REFUSED(with("step = \"auto\"\nscheme = \"central-difference\"", "step = 1e-5\nscheme = \"moreau-jean\""),
                 "time.scheme", "Smith", "paper, newmark, central-difference");
  const std::string plastic =
      testing::refusal(with("step = \"auto\"\nscheme = \"central-difference\"", "step = 1e-5\nscheme = \"newmark\""),
                       {"body.pile.material=plastic", "body.pile.yield_stress=250e6"});
  EXPECT_NE(plastic.find("elastic-plastic body \"pile\""), std::string::npos) << plastic;
  const std::string plastic_paper =
      testing::refusal(with("step = \"auto\"\nscheme = \"central-difference\"", "step = 1e-5\nscheme = \"paper\""),
                       {"body.pile.material=plastic", "body.pile.yield_stress=250e6"});
  EXPECT_NE(plastic_paper.find("\"paper\" cannot run Smith's soil beside the elastic-plastic body \"pile\""),
            std::string::npos)
      << plastic_paper;
  const std::string explicit_newmark = testing::refusal(
      with("step = \"auto\"\nscheme = \"central-difference\"", "step = 1e-5\nscheme = \"newmark\""), {"time.beta=0"});
  EXPECT_NE(explicit_newmark.find("time.beta = 0"), std::string::npos) << explicit_newmark;
  EXPECT_REFUSED(with("step = \"auto\"", "step = \"fast\""), "time.step", "a number or \"auto\"");
}

TEST(PlasticCase, RefusesBadMaterialKeysNamingThem) {
  const std::string head = "[[body]]\nname = \"b\"\nmodulus = 2.0\n";
  EXPECT_EQ(refusal(head + "material = \"plastic\"\n"),
            "test.toml:1: body.b.yield_stress is required when material = \"plastic\"");
  EXPECT_NE(refusal(head + "material = \"plastic\"\nyield_stress = 0.0\n").find("body.b.yield_stress must be > 0"),
            std::string::npos);
  EXPECT_NE(refusal(head + "material = \"plastic\"\nyield_stress = 1.0\nhardening_modulus = -0.1\n")
                .find("body.b.hardening_modulus must be >= 0"),
            std::string::npos);
  EXPECT_NE(refusal(head + "material = \"plastic\"\nyield_stress = 1.0\nhardening_modulus = 2.0\n")
                .find("body.b.hardening_modulus must be below modulus = 2"),
            std::string::npos);
  EXPECT_NE(refusal(head + "material = \"plastic\"\nyield_stress = 1.0\nhardening = \"mixed\"\n")
                .find("body.b.hardening must be kinematic or isotropic"),
            std::string::npos);
  EXPECT_NE(refusal(head + "material = \"steel\"\n").find("body.b.material must be elastic or plastic"),
            std::string::npos);
  for (const char* key : {"yield_stress = 1.0", "hardening_modulus = 0.1", "hardening = \"isotropic\""})
    EXPECT_NE(refusal(head + key + "\n").find("is used by material = \"plastic\" only"), std::string::npos) << key;
  EXPECT_NE(refusal("[[body]]\nname = \"m\"\nkind = \"mass\"\nyield_stress = 1.0\n")
                .find("body.m.yield_stress is not used by a mass"),
            std::string::npos);
  EXPECT_NE(refusal("[bar]\nstiffness = 3.0\nmaterial = \"plastic\"\nyield_stress = 1.0\nhardening_modulus = 3.0\n")
                .find("bar.hardening_modulus must be below stiffness = 3"),
            std::string::npos);
  // characteristic refuses the body before it would discuss the step.
  EXPECT_NE(refusal(head + "material = \"plastic\"\nyield_stress = 1.0\n[time]\nscheme = \"characteristic\"\n"
                           "step = 0.001\n")
                .find("time.scheme = \"characteristic\" cannot run the elastic-plastic body \"b\""),
            std::string::npos);
}

// Both spellings hold the material; case.toml writes it and reads back to
// the same run; a plastic bar is run by the line's schemes.
TEST(PlasticCase, BothSpellingsReadBackExactly) {
  for (const char* text : {R"toml([bar]
stiffness = 2.0
elements = 20
material = "plastic"
yield_stress = 0.3
hardening_modulus = 0.5
hardening = "isotropic"
[initial]
velocity = "-1"
[obstacle]
kind = "rigid"
gap = -0.001
[time]
scheme = "central-difference"
step = 0.01
end = 1
)toml",
                           R"toml([[body]]
name = "p"
area = 3.0
modulus = 0.1
elements = 20
material = "plastic"
yield_stress = 0.03
velocity = "-1"
[near_end]
law = "rigid"
[time]
scheme = "central-difference"
step = 0.01
end = 1
)toml"}) {
    const Case c = case_from(text);
    EXPECT_FALSE(c.one_bar().has_value());
    const Case back = case_from(c.to_toml());
    EXPECT_EQ(back.to_toml(), c.to_toml());
    const RunResult a = run(c), b = run(back);
    ASSERT_EQ(a.history.size(), b.history.size());
    for (std::size_t n = 0; n < a.history.size(); ++n) {
      EXPECT_EQ(a.history[n].U, b.history[n].U);
      EXPECT_EQ(a.history[n].D_plastic, b.history[n].D_plastic);
    }
  }
}

}  // namespace
}  // namespace barimpact
