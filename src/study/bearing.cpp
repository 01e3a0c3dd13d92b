#include "barimpact/study/bearing.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "barimpact/run/output.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/schemes/registry.hpp"
#include "blow_read.hpp"
#include "csv_cells.hpp"

namespace barimpact {

namespace fs = std::filesystem;

void parse_capacity(const std::string& text, BearingOptions& o) {
  const auto fail = [&](const std::string& rule) { throw InputError(fmt::format("--capacity {}: {}", text, rule)); };
  const auto a = text.find(':'), b = text.find(':', a == std::string::npos ? a : a + 1);
  if (a == std::string::npos || b == std::string::npos) fail("expected FROM:TO:COUNT (capacities in N)");
  try {
    std::size_t used = 0;
    o.from = std::stod(text.substr(0, a), &used);
    if (used != a) fail("FROM is not a number");
    o.to = std::stod(text.substr(a + 1, b - a - 1), &used);
    if (used != b - a - 1) fail("TO is not a number");
    const long long count = std::stoll(text.substr(b + 1), &used);
    if (used != text.size() - b - 1) fail("COUNT is not an integer");
    if (count < 1 || count > 100'000) fail("COUNT must be in [1, 100000]");
    o.count = static_cast<int>(count);
  } catch (const std::logic_error&) {
    fail("expected FROM:TO:COUNT, numbers (capacities in N) and an integer");
  }
  if (!(std::isfinite(o.from) && std::isfinite(o.to) && o.from >= 0 && o.to >= 0))
    fail("capacities must be finite and >= 0");
  if (o.count == 1 && o.from != o.to) fail("one capacity needs FROM = TO (or COUNT >= 2)");
}

BearingPlan::BearingPlan(const fs::path& case_file, const BearingOptions& o) {
  const Case c = fit_scheme(Case::from_file(case_file, o.sets)).c;  // an override refused is refused here, named
  const bool toe = c.near_end.law == JointLaw::smith;
  std::vector<std::string> shafts;
  double shaft = 0.0;
  for (const auto& b : c.bodies)
    if (b.shaft) {
      shafts.push_back(b.name);
      shaft += b.shaft->soil.ultimate;
    }
  if (!toe && shafts.empty())
    throw InputError(
        fmt::format("bearing: {} has no Smith soil to scale ([near_end] law = \"smith\" and/or a [body.shaft])",
                    case_file.string()));
  const double total = (toe ? c.near_end.soil.ultimate : 0.0) + shaft;
  share_ = o.toe_share   ? *o.toe_share
           : total > 0.0 ? (toe ? c.near_end.soil.ultimate : 0.0) / total
                         : (toe ? 1.0 : 0.0);
  if (!(share_ >= 0.0 && share_ <= 1.0))
    throw InputError(fmt::format("--toe-share must be in [0, 1] (got {})", share_));
  if (share_ > 0.0 && !toe)
    throw InputError(fmt::format("--toe-share {} needs a toe to carry it: [near_end] law = \"smith\"", share_));
  if (share_ < 1.0 && shafts.empty())
    throw InputError(
        fmt::format("--toe-share {} leaves {} to a shaft the case does not have ([body.shaft])", share_, 1.0 - share_));
  // Each shaft keeps its part of the case's shaft capacity (equal parts if it has none).
  std::vector<double> part;
  for (const auto& b : c.bodies)
    if (b.shaft)
      part.push_back(shaft > 0.0 ? b.shaft->soil.ultimate / shaft : 1.0 / static_cast<double>(shafts.size()));
  std::vector<std::vector<std::string>> axes(shafts.size() + (toe ? 1 : 0));
  for (int i = 0; i < o.count; ++i) {
    const double cap = o.count == 1 ? o.from : o.from + (o.to - o.from) * i / (o.count - 1);
    capacity_.push_back(cap);
    std::size_t k = 0;
    if (toe) axes[k++].push_back(toml_float(share_ * cap));
    for (double p : part) axes[k++].push_back(toml_float((1.0 - share_) * cap * p));
  }
  std::string text = fmt::format("case = {}\n", nlohmann::json(fs::absolute(case_file).string()).dump());
  std::vector<std::string> keys;
  if (toe) keys.push_back("near_end.ultimate");
  for (const auto& name : shafts) keys.push_back(fmt::format("body.{}.shaft.ultimate", name));
  for (std::size_t k = 0; k < keys.size(); ++k)
    text += fmt::format("[[axis]]\nkey = \"{}\"\nvalues = [{}]\n", keys[k], fmt::join(axes[k], ", "));
  if (keys.size() > 1) {
    std::vector<std::string> quoted_keys;
    for (const auto& k : keys) quoted_keys.push_back("\"" + k + "\"");
    text = fmt::format("zip = [[{}]]\n", fmt::join(quoted_keys, ", ")) + text;
  }
  sweep_ = SweepPlan::from_string(text, fmt::format("bearing of {}", case_file.string()), fs::current_path());
  sweep_.set_base(o.sets);
}

std::vector<BearingRow> run_bearing(const BearingPlan& plan, const fs::path& dir, const SweepOptions& options) {
  const auto& points = plan.sweep().points();
  SweepStart start = resume_sweep(plan.sweep(), dir);
  for (auto& r : run_sweep(plan.sweep(), dir, start.todo, options))
    start.rows[static_cast<std::size_t>(std::stoll(r.id))] = r;
  std::vector<BearingRow> rows(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    BearingRow& row = rows[i];
    row.run = std::move(start.rows[i]);
    row.capacity = plan.capacity(i);
    row.toe = plan.toe_share() * row.capacity;
    row.shaft = row.capacity - row.toe;
    detail::take_blow(row, detail::read_blow(dir / "runs" / points[i].id));
    if (row.run.status != "complete") row.finished = false;
  }
  return rows;
}

std::vector<BearingRow> write_bearing(const BearingPlan& plan, const fs::path& dir, const SweepOptions& options,
                                      bool force) {
  prepare_sweep(dir, options, force, plan.sweep().inputs(), "bearing",
                {"runs", "bearing.csv", "bearing.png", "bearing.svg"});
  auto rows = run_bearing(plan, dir, options);
  replace_text(dir / "bearing.csv", bearing_csv(rows));
  return rows;
}

std::string bearing_csv(const std::vector<BearingRow>& rows) {
  std::string out =
      "capacity,set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru,finished,toe,shaft,"
      "transfer_ratio,id,status,message,warnings\n";
  for (const auto& r : rows) {
    std::string warnings;
    for (const auto& w : r.run.warnings) warnings += (warnings.empty() ? "" : "; ") + w;
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", detail::csv_number(r.capacity),
                       detail::csv_number(r.set), detail::csv_number(r.blows_per_250mm),
                       detail::csv_number(r.blows_per_m), detail::csv_number(r.max_compression),
                       detail::csv_number(r.max_tension), detail::csv_number(r.enthru), r.finished ? "true" : "false",
                       detail::csv_number(r.toe), detail::csv_number(r.shaft), detail::csv_number(r.transfer_ratio),
                       r.run.id, r.run.status, detail::csv_text(r.run.message), detail::csv_text(warnings));
  }
  return out;
}

}  // namespace barimpact
