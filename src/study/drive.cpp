#include "barimpact/study/drive.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "../run/summary_units.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/schemes/registry.hpp"
#include "blow_read.hpp"
#include "csv_cells.hpp"

namespace barimpact {

namespace fs = std::filesystem;

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

double pile_area(const Case& c) {
  for (const auto& b : c.bodies)
    if (b.name == c.drive->pile) return b.area;
  return nan;
}

// The body of the sweep file over drive.depth: one axis, the depths as the case gives them.
std::string depth_sweep(const fs::path& case_file, const DriveData& d) {
  std::vector<std::string> values;
  for (double z : d.depths) values.push_back(toml_float(z));
  return fmt::format("case = {}\n[[axis]]\nkey = \"drive.depth\"\nvalues = [{}]\n",
                     nlohmann::json(fs::absolute(case_file).string()).dump(), fmt::join(values, ", "));
}

// The study's own figures in its directory (`stem`.png, .svg), gone before
// it writes its table: they would show another run's.
void remove_figures(const fs::path& dir, const std::string& stem) {
  std::error_code ec;
  for (const char* ext : {".png", ".svg"}) fs::remove(dir / (stem + ext), ec);
}

// Blows to reach each depth from the first: trapezoidal in blows per metre
// (infinite past a refusal, NaN past a depth with no blow).
void accumulate(std::vector<DriveRow>& rows) {
  for (std::size_t i = 0; i < rows.size(); ++i)
    rows[i].cumulative_blows =
        i == 0 ? 0.0
               : rows[i - 1].cumulative_blows +
                     0.5 * (rows[i - 1].blows_per_m + rows[i].blows_per_m) * (rows[i].depth - rows[i - 1].depth);
}

}  // namespace

DrivePlan::DrivePlan(const fs::path& case_file, const std::vector<Case::Override>& sets)
    : base_(fit_scheme(Case::from_file(case_file, sets)).c) {
  if (!base_.drive)
    throw InputError(fmt::format("drive: {} has no [drive] section (the soil profile and the depths to analyse)",
                                 case_file.string()));
  const DriveData& d = *base_.drive;
  for (double z : d.depths) soil_.push_back(soil_at(d, z, d.toe_area.value_or(pile_area(base_))));
  sweep_ = SweepPlan::from_string(depth_sweep(case_file, d), fmt::format("drive of {}", case_file.string()),
                                  fs::current_path());
  sweep_.set_base(sets);
}

double DrivePlan::stroke() const {
  return base_.hammer ? base_.hammer->stroke : nan;
}

std::vector<DriveRow> run_drive(const DrivePlan& plan, const fs::path& dir, const SweepOptions& options) {
  const auto& points = plan.sweep().points();
  SweepStart start = resume_sweep(plan.sweep(), dir);
  for (auto& r : run_sweep(plan.sweep(), dir, start.todo, options))
    start.rows[static_cast<std::size_t>(std::stoll(r.id))] = r;
  std::vector<DriveRow> rows(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    DriveRow& row = rows[i];
    row.run = std::move(start.rows[i]);
    row.depth = plan.drive().depths[i];
    const DriveSoil& soil = plan.soil(i);
    row.shaft = soil.shaft_capacity;
    row.toe = soil.toe_capacity;
    row.capacity = row.shaft + row.toe;
    row.long_term_capacity = soil.long_term_capacity;
    const detail::BlowRead blow = detail::read_blow(dir / "runs" / points[i].id);
    detail::take_blow(row, blow);
    row.finished = row.finished && row.run.status == "complete";
    row.first_set = std::isnan(blow.first_set) ? row.set : blow.first_set;
    row.blows_run = std::isnan(row.set) ? 0 : blow.blows_run;
    row.stroke = std::isnan(blow.stroke) ? plan.stroke() : blow.stroke;
  }
  accumulate(rows);
  return rows;
}

DriveTotals drive_totals(const DrivePlan& plan, const std::vector<DriveRow>& rows) {
  DriveTotals t;
  const DriveData& d = plan.drive();
  for (const auto& r : rows) {
    if (t.refusal_depth) break;  // the pile is not driven past refusal
    if (r.blows_per_250mm >= d.refusal) t.refusal_depth = r.depth;
    if (r.max_compression > t.max_compression) {
      t.max_compression = r.max_compression;
      t.max_compression_depth = r.depth;
    }
    if (r.max_tension > t.max_tension) {
      t.max_tension = r.max_tension;
      t.max_tension_depth = r.depth;
    }
  }
  std::size_t last = rows.empty() ? 0 : rows.size() - 1;  // the deepest depth driven to
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].blows_per_250mm >= d.refusal) {
      last = std::isfinite(rows[i].cumulative_blows) || i == 0 ? i : i - 1;
      break;
    }
  t.total_blows = rows.empty() ? 0.0 : rows[last].cumulative_blows;
  t.driving_time = t.total_blows / d.blow_rate;
  return t;
}

namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string summary_json(const DrivePlan& plan, const std::vector<DriveRow>& rows) {
  const DriveTotals t = drive_totals(plan, rows);
  const DriveData& d = plan.drive();
  nlohmann::json j;
  j["depths"] = rows.size();
  j["total_blows"] = number_or_null(t.total_blows);
  j["driving_time"] = number_or_null(t.driving_time);
  j["refusal_depth"] = t.refusal_depth ? nlohmann::json(*t.refusal_depth) : nlohmann::json(nullptr);
  j["refusal"] = d.refusal;
  j["blow_rate"] = d.blow_rate;
  j["max_compression"] = {{"value", t.max_compression}, {"depth", t.max_compression_depth}};
  j["max_tension"] = {{"value", t.max_tension}, {"depth", t.max_tension_depth}};
  std::size_t complete = 0;
  for (const auto& r : rows) complete += r.run.status == "complete" ? 1 : 0;
  j["complete"] = complete;
  if (const auto& h = plan.base().hammer)
    j["hammer"] = {{"model", h->model.empty() ? nlohmann::json(nullptr) : nlohmann::json(h->model)},
                   {"kind", std::string(to_string(h->kind))},
                   {"stroke", h->stroke},
                   {"efficiency", h->efficiency}};
  for (const auto& b : plan.base().bodies)
    if (b.name == d.pile)
      j["pile"] = {{"name", b.name},
                   {"length", b.length},
                   {"area", b.area},
                   {"yield_stress", b.material.kind == MaterialKind::plastic ? nlohmann::json(b.material.yield_stress)
                                                                             : nlohmann::json(nullptr)}};
  j["units"] = units_json(plan.base().units);
  return j.dump(2) + "\n";
}

}  // namespace

std::vector<DriveRow> write_drive(const DrivePlan& plan, const fs::path& dir, const SweepOptions& options, bool force) {
  prepare_sweep(dir, options, force, plan.sweep().inputs(), "drive",
                {"runs", "drive.csv", "summary.json", "drive.png", "drive.svg"});
  remove_figures(dir, "drive");  // a run with --no-plot leaves no figure of another
  auto rows = run_drive(plan, dir, options);
  replace_text(dir / "drive.csv", drive_csv(rows));
  replace_text(dir / "summary.json", summary_json(plan, rows));
  return rows;
}

std::string drive_csv(const std::vector<DriveRow>& rows) {
  using detail::csv_number;
  std::string out =
      "depth,shaft,toe,capacity,long_term_capacity,set,blows_per_250mm,blows_per_m,max_compression,max_tension,"
      "enthru,stroke,cumulative_blows,finished,first_set,blows_run,transfer_ratio,id,status,message,warnings\n";
  for (const auto& r : rows) {
    std::string warnings;
    for (const auto& w : r.run.warnings) warnings += (warnings.empty() ? "" : "; ") + w;
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_number(r.depth),
                       csv_number(r.shaft), csv_number(r.toe), csv_number(r.capacity), csv_number(r.long_term_capacity),
                       csv_number(r.set), csv_number(r.blows_per_250mm), csv_number(r.blows_per_m),
                       csv_number(r.max_compression), csv_number(r.max_tension), csv_number(r.enthru),
                       csv_number(r.stroke), csv_number(r.cumulative_blows), r.finished ? "true" : "false",
                       csv_number(r.first_set), r.blows_run, csv_number(r.transfer_ratio), r.run.id, r.run.status,
                       detail::csv_text(r.run.message), detail::csv_text(warnings));
  }
  return out;
}

namespace {

// The strokes of --stroke FROM:TO:COUNT (m, > 0).
std::vector<double> parse_strokes(const std::string& text) {
  double from = 0, to = 0;
  long long count = 0;
  int used = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf:%lld%n", &from, &to, &count, &used) != 3 ||
      used != static_cast<int>(text.size()) || count < 1 || count > 10'000 || (count == 1 && from != to) ||
      !(from > 0 && to > 0 && std::isfinite(from) && std::isfinite(to)))
    throw InputError(fmt::format(
        "--stroke {}: expected FROM:TO:COUNT, strokes > 0 in m and COUNT in [1, 10000] (1 needs FROM = TO)", text));
  return linear_range(from, to, count);
}

}  // namespace

InspectorPlan::InspectorPlan(const fs::path& case_file, const std::string& strokes, std::optional<double> depth,
                             std::vector<Case::Override> sets)
    : strokes_(parse_strokes(strokes)) {
  const Case probe = Case::from_file(case_file, sets);
  if (probe.drive && !depth)
    throw InputError(
        fmt::format("--depth is required: {} has a [drive] profile (the penetration to chart at)", case_file.string()));
  if (!probe.drive && depth)
    throw InputError(
        fmt::format("--depth {}: {} has no [drive] profile (its soil is the case's own)", *depth, case_file.string()));
  if (depth) sets.push_back({fmt::format("drive.depth={}", toml_float(*depth))});
  const Case c = fit_scheme(Case::from_file(case_file, sets)).c;  // --depth's rules, named
  if (!c.hammer)
    throw InputError(fmt::format("inspector: {} has no [hammer] (the stroke it varies)", case_file.string()));
  if (c.hammer->kind == HammerKind::diesel)
    throw InputError(fmt::format(
        "inspector: {}'s hammer is a diesel hammer, whose stroke follows the soil (barimpact drive's stroke column)",
        case_file.string()));
  for (const auto& b : c.bodies)
    if (b.name == c.hammer->ram)
      ram_weight_ = (b.kind == BodyKind::mass ? b.mass : b.density * b.area * b.length) * drive_gravity(c.load.gravity);
  std::vector<std::string> values;
  for (double v : strokes_) values.push_back(toml_float(v));
  sweep_ = SweepPlan::from_string(
      fmt::format("case = {}\n[[axis]]\nkey = \"hammer.stroke\"\nvalues = [{}]\n",
                  nlohmann::json(fs::absolute(case_file).string()).dump(), fmt::join(values, ", ")),
      fmt::format("inspector of {}", case_file.string()), fs::current_path());
  sweep_.set_base(sets);
}

std::string inspector_csv(const std::vector<InspectorRow>& rows) {
  using detail::csv_number;
  std::string out =
      "stroke,energy,set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru,finished,transfer_ratio,id,"
      "status,message,warnings\n";
  for (const auto& r : rows) {
    std::string warnings;
    for (const auto& w : r.run.warnings) warnings += (warnings.empty() ? "" : "; ") + w;
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_number(r.stroke), csv_number(r.energy),
                       csv_number(r.set), csv_number(r.blows_per_250mm), csv_number(r.blows_per_m),
                       csv_number(r.max_compression), csv_number(r.max_tension), csv_number(r.enthru),
                       r.finished ? "true" : "false", csv_number(r.transfer_ratio), r.run.id, r.run.status,
                       detail::csv_text(r.run.message), detail::csv_text(warnings));
  }
  return out;
}

std::vector<InspectorRow> write_inspector(const InspectorPlan& plan, const fs::path& dir, const SweepOptions& options,
                                          bool force) {
  prepare_sweep(dir, options, force, plan.sweep().inputs(), "inspector",
                {"runs", "inspector.csv", "inspector.png", "inspector.svg"});
  remove_figures(dir, "inspector");
  const auto& points = plan.sweep().points();
  SweepStart start = resume_sweep(plan.sweep(), dir);
  for (auto& r : run_sweep(plan.sweep(), dir, start.todo, options))
    start.rows[static_cast<std::size_t>(std::stoll(r.id))] = r;
  std::vector<InspectorRow> rows(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    InspectorRow& row = rows[i];
    row.run = std::move(start.rows[i]);
    row.stroke = plan.stroke(i);
    row.energy = plan.ram_weight() * row.stroke;
    detail::take_blow(row, detail::read_blow(dir / "runs" / points[i].id));
    row.finished = row.finished && row.run.status == "complete";
  }
  replace_text(dir / "inspector.csv", inspector_csv(rows));
  return rows;
}

}  // namespace barimpact
