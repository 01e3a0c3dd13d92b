#include "barimpact/run/output.hpp"

#include "barimpact/run/output_directory.hpp"
#include "barimpact/run/results_h5.hpp"
#include "barimpact/schemes/registry.hpp"
#include "field_stream.hpp"
#include "output_file.hpp"
#include "summary_units.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

namespace barimpact {

namespace fs = std::filesystem;
using detail::OutputFile;

RunDirectory::RunDirectory(fs::path target, bool force, std::string command, bool remove_stale, CommandInputs inputs)
    : target_(std::move(target)), inputs_(std::move(inputs)), command_(std::move(command)) {
  shown_ = target_;
  beside_ = check_output_directory(target_, force, "--out", inputs_) == OutputMode::beside;
  // Work on the resolved path: a link given as --out is written through, not replaced.
  std::error_code ec;
  target_ = fs::weakly_canonical(fs::absolute(target_), ec);
  if (ec) target_ = fs::absolute(shown_).lexically_normal();
  if (!target_.has_filename()) target_ = target_.parent_path();
  // Beside someone else's files, the staging goes inside the target: nothing is made outside it.
  const fs::path parent = beside_ ? target_ : target_.parent_path();
  const std::string name = beside_ ? std::string("barimpact") : target_.filename().string();
  if (!beside_) parents_ = std::make_unique<MadeParents>(target_);
  if (remove_stale) remove_stale_staging(parent, name);
  staging_ = parent / fmt::format(".{}.partial-{}", name, ::getpid());
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec) {
    const std::string reason = ec ? ec.message() : "not created";
    throw OutputError(fmt::format("--out {}: cannot write in {} ({})", shown_.string(), parent.string(), reason),
                      parent, reason);
  }
  try {
    write_text(staging_ / staging_flag, "a barimpact run's results while they are written\n");
  } catch (const OutputError& e) {
    fs::remove_all(staging_, ec);  // a constructor that throws has no destructor run
    throw refused(e);
  }
}

RunDirectory::~RunDirectory() {
  fields_.reset();  // its file closed before the staging goes
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

OutputError RunDirectory::refused(const OutputError& e) const {
  // The file by its name in the results (the staging directory is gone by the time this is read).
  const auto inside = [&](const fs::path& dir) {
    const fs::path name = e.path().lexically_relative(dir);
    return name.empty() || *name.begin() == ".." ? fs::path() : name;
  };
  fs::path name = inside(staging_);
  if (name.empty()) name = inside(target_);
  if (name.empty()) name = e.path();
  return {fmt::format("--out {}: cannot write {}: {}", shown_.string(), name.string(), e.reason()), shown_ / name,
          e.reason()};
}

OutputError RunDirectory::cannot_write(const std::exception& e, const std::string& reason) const {
  return {fmt::format("--out {}: cannot write the results: {}", shown_.string(), e.what()), shown_, reason};
}

namespace {

// Shortest text that reads back to the same double.
constexpr std::string_view budget_header = "t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc,D_contact,D_plastic";

void write_history(const fs::path& path, const RunResult& result) {
  OutputFile out(path);
  const std::size_t n = result.columns.size();
  out.print("{}", budget_header);
  for (const auto& name : result.columns) out.print(",{}", name);
  out.print("\n");
  for (std::size_t k = 0; k < result.history.size(); ++k) {
    const HistoryRow& r = result.history[k];
    out.print("{},{},{},{},{},{},{},{},{},{},{}", r.t, r.U, r.V, r.R, r.E_kin, r.E_strain, r.E_obstacle, r.W_ext,
              r.D_visc, r.D_contact, r.D_plastic);
    for (std::size_t i = 0; i < n; ++i) out.print(",{}", result.extra[k * n + i]);
    out.print("\n");
  }
  out.close();
}

void write_fields(const fs::path& path, const RunResult& result) {
  OutputFile out(path);
  out.print("t,x,u,v,sigma,eps_p,body\n");
  const Fields& f = result.fields;
  for (std::size_t s = 0; s < f.count(); ++s)
    for (std::size_t j = 0, i = s * f.nodes(); j < f.nodes(); ++j, ++i)
      out.print("{},{},{},{},{},{},{}\n", f.t[s], f.x[j], f.u[i], f.v[i], f.sigma[i], f.eps_p[i],
                f.body_names[f.body[j]]);
  out.close();
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

void write_text(const fs::path& path, const std::string& text) {
  OutputFile out(path);
  out.write(text);
  out.close();
}

void replace_text(const fs::path& path, const std::string& text) {
  detail::replace_file(path.parent_path() / fmt::format(".{}.partial-{}", path.filename().string(), ::getpid()), path,
                       text);
}

std::string_view history_file(OutputFormat format) {
  return format == OutputFormat::hdf5 ? results_h5_name : std::string_view("history.csv");
}

std::vector<std::string> run_outputs(const Case& c) {
  std::vector<std::string> names{std::string(history_file(c.output.format)), "summary.json",
                                 std::string(case_file_name)};
  if (c.output.format != OutputFormat::hdf5) names.emplace_back("fields.csv");
  return names;
}

void RunDirectory::expect(const std::vector<std::string>& names) const {
  refuse_entries_of_another_kind(shown_, names);
}

FieldSink& RunDirectory::stream_fields(const Case& c) {
  try {
    fields_ = std::make_unique<detail::FieldStream>(staging_, c);
  } catch (const OutputError& e) {
    throw refused(e);
  } catch (const Hdf5Error& e) {
    throw cannot_write(e, e.what());
  }
  return *fields_;
}

void RunDirectory::commit(const Case& c, const RunResult& result) {
  commit([&](const fs::path& dir) {
    if (fields_) fields_->finish(c, result);  // what the disk refused during the run, first
    if (c.output.format == OutputFormat::hdf5) {
      if (!fields_) write_results_h5(dir / results_h5_name, c, result);  // else streamed there
    } else {
      write_history(dir / "history.csv", result);
      if (!fields_) write_fields(dir / "fields.csv", result);  // else streamed there
    }
    write_text(dir / case_file_name, c.to_toml());
    write_text(dir / "summary.json", summary_json(c, result.summary));
  });
}

void RunDirectory::commit(const std::function<void(const fs::path& staging)>& write) {
  try {
    write(staging_);
    spare_inputs();
    // The marker first, then the flag away: a process killed in between
    // leaves a staging directory that is still provably barimpact's (its
    // flag, or a marker listing all of it), which a rerun removes.
    auto entries = directory_entries(staging_);
    entries.erase(std::remove(entries.begin(), entries.end(), std::string(staging_flag)), entries.end());
    write_output_marker(staging_, command_, entries);
    fs::remove(staging_ / staging_flag);
  } catch (const OutputError& e) {
    throw refused(e);
  } catch (const std::system_error& e) {
    throw cannot_write(e, e.code().message());
  } catch (const Hdf5Error& e) {
    throw cannot_write(e, e.what());
  }
  // The target is judged again now: it may have changed during the run.
  std::error_code ec;
  if (fs::is_directory(target_, ec) && fs::is_empty(target_, ec)) fs::remove(target_, ec);
  if (beside_ || (fs::exists(target_, ec) && !written_by_barimpact(target_)))
    move_beside();
  else
    move_into_place();
  committed_ = true;
  if (parents_) parents_->keep();
}

// The staging directory renamed to the target; a directory barimpact wrote
// there before is set aside first, put back if the rename fails, and
// removed once the new results are in place.
void RunDirectory::move_into_place() {
  std::error_code ec;
  fs::path old;
  const auto cannot = [&](std::string_view what) {
    return OutputError(fmt::format("--out {}: cannot {}: {}", shown_.string(), what, ec.message()), shown_,
                       ec.message());
  };
  if (fs::exists(target_, ec)) {
    old = target_.parent_path() / fmt::format(".{}.old-{}", target_.filename().string(), ::getpid());
    fs::rename(target_, old, ec);
    if (ec) throw cannot("replace the existing directory");
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    const OutputError failure = cannot("move the results into place");
    std::error_code ignored;
    if (!old.empty()) fs::rename(old, target_, ignored);
    throw failure;
  }
  if (!old.empty()) fs::remove_all(old, ec);  // barimpact's own files only (written_by_barimpact)
}

// Where a staged file would replace an input of the command (--force beside
// the user's files): the resolved case goes to case.resolved.toml; any
// other name is refused, before anything is moved.
void RunDirectory::spare_inputs() {
  if (fs::exists(staging_ / case_file_name) && inputs_.reads_file(target_ / case_file_name))
    fs::rename(staging_ / case_file_name, staging_ / resolved_case_name);
  refuse_names_over_inputs(shown_, directory_entries(staging_), inputs_);
}

// --force on a directory that holds someone else's files: each of
// barimpact's files replaces only the file of its own name. The marker is
// written first: when the disk refuses it, nothing has moved yet.
void RunDirectory::move_beside() {
  const auto names = directory_entries(staging_);
  std::vector<std::string> moved = names;
  moved.erase(std::remove(moved.begin(), moved.end(), std::string(output_marker)), moved.end());
  refuse_entries_of_another_kind(shown_, moved);
  // A run's results in the other format, left here by an earlier run, would
  // pass for this one's: removed when barimpact's marker lists them (as a
  // replaced directory would lose them). So would a resolved case of an
  // earlier run beside a case.toml written now.
  const auto writes = [&](std::string_view n) { return std::find(names.begin(), names.end(), n) != names.end(); };
  std::vector<std::string> stale;
  if (writes("history.csv") || writes(results_h5_name))
    for (const std::string_view n : {std::string_view("history.csv"), std::string_view("fields.csv"), results_h5_name})
      if (!writes(n)) stale.emplace_back(n);
  if (writes(case_file_name)) stale.emplace_back(resolved_case_name);
  try {
    write_output_marker(target_, command_, names);
  } catch (const OutputError& e) {
    throw refused(e);
  }
  for (const auto& name : names) {
    std::error_code ec;
    if (name == output_marker) continue;
    fs::rename(staging_ / name, target_ / name, ec);
    if (ec)
      throw OutputError(fmt::format("--out {}: cannot move {} into place: {}", shown_.string(), name, ec.message()),
                        shown_ / name, ec.message());
  }
  try {
    remove_listed_files(target_, command_, stale);
  } catch (const OutputError& e) {
    throw refused(e);
  }
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string();
}

void read_history(const fs::path& path, RunResult& result) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line.rfind(budget_header, 0) != 0) throw std::runtime_error("not a history.csv");
  result.columns.clear();
  for (std::size_t at = budget_header.size(); at < line.size();) {
    const std::size_t end = std::min(line.find(',', at + 1), line.size());
    result.columns.push_back(line.substr(at + 1, end - at - 1));
    at = end;
  }
  while (std::getline(in, line)) {
    HistoryRow r{};
    std::size_t at = 0;
    auto next = [&] {
      const std::size_t end = std::min(line.find(',', at), line.size());
      const double v = std::stod(line.substr(at, end - at));  // "nan" and "inf" read back too
      at = end + 1;
      return v;
    };
    for (const auto& b : budget_columns) r.*b.value = next();
    for (std::size_t i = 0; i < result.columns.size(); ++i) result.extra.push_back(next());
    result.history.push_back(r);
  }
}

// The history as results.h5 holds it, by column: into rows as read_history gives them.
void read_results_history(const fs::path& path, RunResult& result) {
  const HistoryColumns h = read_results_h5_history(path);
  const std::size_t budget = budget_columns.size();
  if (h.names.size() < budget || !std::equal(budget_columns.begin(), budget_columns.end(), h.names.begin(),
                                             [](const BudgetColumn& b, const std::string& n) { return b.name == n; }))
    throw std::runtime_error("not a results.h5 history");
  result.columns.assign(h.names.begin() + static_cast<std::ptrdiff_t>(budget), h.names.end());
  const std::size_t rows = h.values.front().size(), n = result.columns.size();
  result.history.assign(rows, HistoryRow{});
  result.extra.assign(rows * n, 0.0);
  for (std::size_t k = 0; k < rows; ++k) {
    for (std::size_t i = 0; i < budget; ++i) result.history[k].*budget_columns[i].value = h.values[i][k];
    for (std::size_t i = 0; i < n; ++i) result.extra[k * n + i] = h.values[budget + i][k];
  }
}

double number_or_nan(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::numeric_limits<double>::quiet_NaN();
}

RunStatus status_from(const std::string& text) {
  for (auto s : {RunStatus::complete, RunStatus::non_finite, RunStatus::stopped, RunStatus::interrupted})
    if (to_string(s) == text) return s;
  throw std::runtime_error("unknown status " + text);
}

}  // namespace

fs::path run_case_file(const fs::path& dir) {
  const auto listed = marked_entries(dir);
  const bool resolved = std::find(listed.begin(), listed.end(), resolved_case_name) != listed.end() &&
                        fs::is_regular_file(dir / resolved_case_name);
  return dir / (resolved ? resolved_case_name : case_file_name);
}

namespace {

// summary.json's blow, the numbers a study's table reads back (not the envelopes).
BlowSummary read_blow(const nlohmann::json& j) {
  BlowSummary b;
  b.set = number_or_nan(j, "set");
  b.enthru = number_or_nan(j, "enthru");
  b.hammer_energy = number_or_nan(j, "hammer_energy");
  b.impact = j.value("impact", true);
  b.finished = j.value("finished", false);
  b.rest_time = number_or_nan(j, "rest_time");
  b.restrike_time = number_or_nan(j, "restrike_time");
  b.last_slip_time = number_or_nan(j, "last_slip_time");
  b.strikes = j.value("strikes", 1);
  b.diesel = j.contains("next_stroke");
  b.next_stroke = number_or_nan(j, "next_stroke");
  b.compression_work = number_or_nan(j, "compression_work");
  b.expansion_work = number_or_nan(j, "expansion_work");
  b.stroke = number_or_nan(j, "stroke");
  b.first_set = number_or_nan(j, "first_set");
  b.blows_run = j.value("blows_run", 1);
  for (auto [key, peak] : {std::pair{"max_compression", &b.max_compression}, std::pair{"max_tension", &b.max_tension}})
    if (j.contains(key) && j.at(key).is_object()) peak->value = number_or_nan(j.at(key), "value");
  return b;
}

}  // namespace

std::optional<RunResult> read_run_directory(const fs::path& dir, const std::string& case_toml) {
  const fs::path case_file = run_case_file(dir);
  if (!case_toml.empty() && read_text(case_file) != case_toml) return std::nullopt;
  try {
    std::ifstream in(dir / "summary.json");
    const auto j = nlohmann::json::parse(in);
    RunResult r;
    Summary& s = r.summary;
    s.method = j.at("scheme").get<std::string>();
    s.status = status_from(j.at("status").get<std::string>());
    s.complete = s.status == RunStatus::complete;
    s.message = j.value("message", "");
    s.steps = j.at("steps").get<long long>();
    s.steps_done = j.at("steps_done").get<long long>();
    s.t_end = number_or_nan(j, "t_end");
    for (const auto& e : j.at("contacts")) {
      ContactInterval ci;
      ci.start = e.at("start").get<double>();
      ci.end = e.at("end").get<double>();
      ci.closed = e.at("closed").get<bool>();
      ci.exit_velocity = number_or_nan(e, "exit_velocity");
      ci.rebound_velocity = number_or_nan(e, "rebound_velocity");
      ci.max_reaction = e.at("max_reaction").get<double>();
      ci.impact_impulse = e.value("impact_impulse", 0.0);
      s.contacts.push_back(ci);
    }
    s.max_penetration = number_or_nan(j, "max_penetration");
    s.max_reaction = number_or_nan(j, "max_reaction");
    s.max_impact_impulse = j.value("max_impact_impulse", 0.0);
    s.energy_initial = number_or_nan(j, "energy_initial");
    s.energy_final = number_or_nan(j, "energy_final");
    s.energy_error_max = number_or_nan(j, "energy_error_max");
    s.run_seconds = number_or_nan(j, "run_seconds");
    s.warnings = j.value("warnings", std::vector<std::string>{});
    if (j.contains("blow") && j.at("blow").is_object()) s.blow = read_blow(j.at("blow"));
    // The file the case says the run wrote (a user's file of the other name may lie beside it under --force).
    if (Case::from_file(case_file).output.format == OutputFormat::hdf5)
      read_results_history(dir / results_h5_name, r);
    else
      read_history(dir / "history.csv", r);
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // not a run directory barimpact wrote whole: run it again
  }
}

namespace {

// Each contact episode of the near end; the velocities it leaves with only
// when it closed (an open one has none yet).
nlohmann::json contacts_json(const Summary& s) {
  nlohmann::json contacts = nlohmann::json::array();
  for (const auto& ci : s.contacts)
    contacts.push_back({{"start", ci.start},
                        {"end", ci.end},
                        {"closed", ci.closed},
                        {"exit_velocity", ci.closed ? number_or_null(ci.exit_velocity) : nlohmann::json(nullptr)},
                        {"rebound_velocity", ci.closed ? number_or_null(ci.rebound_velocity) : nlohmann::json(nullptr)},
                        {"max_reaction", ci.max_reaction},
                        {"impact_impulse", ci.impact_impulse}});
  return contacts;
}

// Each link's contact episodes, under the link's name.
nlohmann::json links_json(const Summary& s) {
  nlohmann::json links = nlohmann::json::object();
  for (std::size_t i = 0; i < s.link_names.size(); ++i) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& e : s.link_episodes[i])
      list.push_back({{"start", e.start},
                      {"end", e.end},
                      {"closed", e.closed},
                      {"max_force", e.max_force},
                      {"velocity_lower", e.closed ? number_or_null(e.velocity_lower) : nlohmann::json(nullptr)},
                      {"velocity_upper", e.closed ? number_or_null(e.velocity_upper) : nlohmann::json(nullptr)}});
    links[s.link_names[i]] = list;
  }
  return links;
}

// The largest plastic strain and each body's plastic work; null when no body yields.
nlohmann::json plastic_json(const Summary& s) {
  if (!s.plastic) return nullptr;
  nlohmann::json work = nlohmann::json::object();
  for (const auto& [body, w] : s.plastic->work) work[body] = w;
  return {{"largest_strain", s.plastic->largest_strain},
          {"body", s.plastic->body},
          {"x", s.plastic->x},
          {"t", s.plastic->t},
          {"work", work}};
}

nlohmann::json stress_peak_json(const StressPeak& p) {
  return nlohmann::json{{"value", p.value}, {"body", p.body}, {"x", p.x}, {"t", p.t}};
}

// The pile-driving blow's measures; null when the case has no [blow].
nlohmann::json blow_json(const Summary& s) {
  const auto& b = s.blow;
  if (!b) return nullptr;
  nlohmann::json out = {
      {"set", b->set},
      {"blows_per_m", number_or_null(b->blows_per_m())},
      {"blows_per_250mm", number_or_null(b->blows_per_250mm())},
      {"max_compression", stress_peak_json(b->max_compression)},
      {"max_tension", stress_peak_json(b->max_tension)},
      {"enthru", number_or_null(b->enthru)},
      {"gauge", b->gauge.empty() ? nlohmann::json(nullptr) : nlohmann::json(b->gauge)},
      {"hammer_energy", b->hammer_energy},
      {"transfer_ratio", number_or_null(b->transfer_ratio())},
      {"ram", b->ram},
      {"pile", b->pile},
      {"impact_time", b->impact_time},
      {"impact_velocity", b->impact_velocity},
      {"toe_penetration", b->toe_penetration},
      {"finished", b->finished},
      {"rest_time", number_or_null(b->rest_time)},
      {"rest_window", number_or_null(b->rest_window)},
      {"restrike_time", number_or_null(b->restrike_time)},
      {"last_slip_time", number_or_null(b->last_slip_time)},
      {"strikes", b->strikes},
      {"precursor", stress_peak_json(b->precursor)},
      {"impact", b->impact},
      {"impedance", number_or_null(b->impedance)},
      {"envelope", {{"x", b->envelope.x}, {"compression", b->envelope.compression}, {"tension", b->envelope.tension}}}};
  if (b->diesel) {  // a diesel hammer's rebound and gas works
    out["next_stroke"] = number_or_null(b->next_stroke);
    out["compression_work"] = b->compression_work;
    out["expansion_work"] = b->expansion_work;
    out["stroke"] = number_or_null(b->stroke);
  }
  if (b->diesel || b->blows_run > 1) {  // blows repeated at one soil: the first's set, how many
    out["first_set"] = number_or_null(b->first_set);
    out["blows_run"] = b->blows_run;
  }
  if (!std::isnan(b->residual_toe_force)) out["residual_toe_force"] = b->residual_toe_force;
  return out;
}

}  // namespace

std::string summary_json(const Case& c, const Summary& s) {
  const double rel = s.energy_initial != 0.0 ? s.energy_error_max / std::abs(s.energy_initial) : s.energy_error_max;
  const nlohmann::json j = {
      {"complete", s.complete},
      {"status", std::string(to_string(s.status))},
      {"message", s.message},
      {"scheme", s.method},
      {"steps", s.steps},
      {"steps_done", s.steps_done},
      {"step", c.time.step},
      {"step_rule", c.time.step_auto
                        ? fmt::format("auto: {} of {}'s stable step for this line", auto_step_fraction, c.time.scheme)
                        : std::string("given")},
      {"elements", c.bar_elements()},
      {"t_end", s.t_end},
      {"contacts", contacts_json(s)},
      {"contact_count", s.contacts.size()},
      {"max_penetration", s.max_penetration},
      {"max_reaction", s.max_reaction},
      {"max_impact_impulse", s.max_impact_impulse},
      {"links", links_json(s)},
      {"plastic", plastic_json(s)},
      {"blow", blow_json(s)},
      {"energy_initial", number_or_null(s.energy_initial)},
      {"energy_final", number_or_null(s.energy_final)},
      {"energy_error_max", number_or_null(s.energy_error_max)},
      {"energy_error_relative", number_or_null(rel)},
      {"run_seconds", s.run_seconds},
      {"warnings", s.warnings},
      // What the numbers are in (SI, or the case's own under "none") and
      // what the console prints them in.
      {"units", units_json(c.units)},
  };
  return j.dump(2) + "\n";
}

namespace {

// A signed number to 4 digits, or what it is when it is not one (a velocity
// not measured is nan: it reads "not measured", never "+nan").
std::string signed_number(double v) {
  return std::isfinite(v) ? fmt::format("{:+.4g}", v) : std::string(std::isnan(v) ? "not measured" : "infinite");
}

}  // namespace

namespace {

// The blow's console lines: "no impact" when the ram never struck; a set of
// How the blow ended: at rest, settled before the ram struck again, or not.
std::string blow_end_text(const BlowSummary& b) {
  std::string out = !std::isnan(b.rest_time) ? fmt::format("pile at rest from t = {:.4g}", b.rest_time)
                    : b.finished             ? fmt::format("the soil's last slip at t = {:.4g}", b.last_slip_time)
                                             : std::string("the pile had not come to rest");
  if (b.strikes > 1)
    out += fmt::format(" after {} strikes (the ram fell back on the pile before it came to rest)", b.strikes);
  if (!std::isnan(b.restrike_time))
    out += fmt::format("; the ram fell back and struck again at t = {:.4g}: the blow ends there", b.restrike_time);
  return out;
}

// The blow's counts: per 250 mm or per ft under a display system, per unit
// length without one; 0 is a refusal only when the pile came to rest.
std::string count_text(const BlowSummary& b, const units::Display* d) {
  if (b.set > 0)
    return d ? fmt::format("{:.3g} {}", d->count(b.blows_per_m()), d->count_name)
             : fmt::format("{:.3g} blows per unit length", b.blows_per_m());
  return b.finished ? std::string("refusal") : std::string("no set yet: the blow is not finished");
}

// A number with its display unit, or bare under "none".
std::string shown(double si, const units::Shown* unit, int digits = 4) {
  return unit ? fmt::format("{:.{}g} {}", (*unit)(si), digits, unit->name) : fmt::format("{:.{}g}", si, digits);
}

// The diesel's line: its blows, its next stroke, its gas works.
std::string diesel_text(const BlowSummary& b, const units::Display* d) {
  const auto* depth = d ? &d->depth : nullptr;
  const auto* energy = d ? &d->energy : nullptr;
  return fmt::format("  diesel: {}next stroke {}; gas works W_c {}, W_e {}\n",
                     b.blows_run > 1 ? fmt::format("blow {} from a stroke of {} (the first set {}); ", b.blows_run,
                                                   shown(b.stroke, depth), shown(b.first_set, d ? &d->set : nullptr))
                                     : std::string(),
                     std::isnan(b.next_stroke) ? std::string("not reached (the ram has not risen past the ports)")
                                               : shown(b.next_stroke, depth),
                     shown(b.compression_work, energy), shown(b.expansion_work, energy));
}

// The blow's console lines: "no impact" when the ram never struck; no inf or
// nan printed. Engineering units (mm, MPa, J; in, ksi, kip-ft) under a
// display system, the case's own numbers without a unit under "none".
std::string blow_text(const BlowSummary& b, const units::Display* d) {
  if (!b.impact)
    return fmt::format(
        "  blow: no impact: the ram \"{}\" never struck the pile (check its velocity's sign, towards "
        "the pile, and [blow] ram)\n",
        b.ram);
  const auto* stress = d ? &d->stress : nullptr;
  const auto* energy = d ? &d->energy : nullptr;
  std::string out =
      fmt::format("  blow: set {} ({}), max compression {}, max tension {}{}\n", shown(b.set, d ? &d->set : nullptr),
                  count_text(b, d), shown(b.max_compression.value, stress), shown(b.max_tension.value, stress),
                  d ? "" : " (the case's units)");
  const std::string ratio = std::isnan(b.transfer_ratio())
                                ? std::string(" (no transfer ratio: the ram brought no energy)")
                                : fmt::format(" (transfer ratio {:.3g})", b.transfer_ratio());
  out +=
      fmt::format("  hammer energy {} at t = {:.4g}; ENTHRU {}{}; {}\n", shown(b.hammer_energy, energy), b.impact_time,
                  std::isnan(b.enthru) ? std::string("not measured (no gauge on the pile)")
                                       : fmt::format("{} at {}", shown(b.enthru, energy), b.gauge),
                  std::isnan(b.enthru) ? "" : ratio, blow_end_text(b));
  if (b.diesel) out += diesel_text(b, d);
  return out;
}

}  // namespace

namespace {

// The console's other numbers: under "US" in kip, in, ft/s and kip-ft
// (a US reader has no use for bare newtons); under "SI" and "none" bare,
// the case's own numbers.
struct LineUnits {
  const units::Shown *force = nullptr, *length = nullptr, *velocity = nullptr, *energy = nullptr;
};

LineUnits line_units(const Case& c) {
  if (c.units != "US") return {};
  const auto& us = units::us_display;
  return {&us.force, &us.set, &us.velocity, &us.energy};
}

// A velocity with its sign, or what it is when it is not one.
std::string signed_velocity(double v, const units::Shown* unit) {
  if (unit == nullptr || !std::isfinite(v)) return signed_number(v);
  return fmt::format("{:+.4g} {}", (*unit)(v), unit->name);
}

// The near end's contacts and their largest values.
std::string contacts_text(const Summary& s, bool obstacle, const LineUnits& u) {
  std::string out;
  if (s.contacts.empty() && (obstacle || s.link_names.empty())) out += "  no contact\n";
  constexpr std::size_t listed = 8;
  for (std::size_t i = 0; i < std::min(listed, s.contacts.size()); ++i) {
    const auto& ci = s.contacts[i];
    if (ci.closed)
      out +=
          fmt::format("  contact {}: t = {:.6g} .. {:.6g}, max R = {}, leaves with mean velocity {} (end {})\n", i + 1,
                      ci.start, ci.end, shown(ci.max_reaction, u.force),
                      signed_velocity(ci.rebound_velocity, u.velocity), signed_velocity(ci.exit_velocity, u.velocity));
    else
      out += fmt::format("  contact {}: t = {:.6g} .. (still in contact at the end), max R = {}\n", i + 1, ci.start,
                         shown(ci.max_reaction, u.force));
  }
  if (s.contacts.size() > listed)
    out += fmt::format("  ... {} more contact episodes in summary.json\n", s.contacts.size() - listed);
  if (obstacle || s.link_names.empty())
    out += fmt::format(
        "  max penetration {}, max reaction {}{}\n", shown(s.max_penetration, u.length), shown(s.max_reaction, u.force),
        s.max_impact_impulse > 0.0
            ? fmt::format(" after the impact steps (largest impact impulse {:.4g} over one step)", s.max_impact_impulse)
            : std::string());
  return out;
}

// The joints' and far end's episodes, and the plastic bodies.
std::string links_text(const Summary& s, const LineUnits& u) {
  std::string out;
  for (std::size_t i = 0; i < s.link_names.size(); ++i) {
    if (s.link_names[i] == "near_end") continue;  // the contacts above
    double largest = 0.0;
    for (const auto& e : s.link_episodes[i]) largest = std::max(largest, e.max_force);
    out += fmt::format("  {}: {} contact episode(s), largest force {}\n", s.link_names[i], s.link_episodes[i].size(),
                       shown(largest, u.force));
  }
  if (s.plastic) {
    out += fmt::format("  plastic: largest eps_p {:.4g} in {} at x = {:.4g}, t = {:.4g}; plastic work",
                       s.plastic->largest_strain, s.plastic->body, s.plastic->x, s.plastic->t);
    for (const auto& [body, w] : s.plastic->work) out += fmt::format(" {} {:.4g}", body, w);
    out += "\n";
  }
  return out;
}

std::string energy_text(const Summary& s, const LineUnits& u) {
  if (!std::isfinite(s.energy_initial)) return "  energy: not known for this solution\n";
  return fmt::format("  energy: initial {}, final {}, max balance error {}{}\n", shown(s.energy_initial, u.energy, 6),
                     shown(s.energy_final, u.energy, 6), shown(s.energy_error_max, u.energy, 3),
                     s.energy_initial != 0.0
                         ? fmt::format(" ({:.2g}% of initial)", 100.0 * s.energy_error_max / std::abs(s.energy_initial))
                         : std::string());
}

}  // namespace

std::string summary_text(const Case& c, const Summary& s) {
  std::string out =
      fmt::format("{}: {} steps of dt = {:.6g} on {} elements, t = 0 .. {:.6g}{}\n", s.method, s.steps_done,
                  c.time.step, c.bar_elements(), s.t_end, s.complete ? "" : " (INCOMPLETE)");
  // The near end's obstacle, when it has one (a line's ends may be free, held or loaded).
  const bool obstacle = std::find(s.link_names.begin(), s.link_names.end(), "near_end") != s.link_names.end() ||
                        (c.one_bar() && c.one_bar()->obstacle.kind != ObstacleKind::none);
  const LineUnits u = line_units(c);
  out += contacts_text(s, obstacle, u);
  out += links_text(s, u);
  if (const auto& b = s.blow) out += blow_text(*b, units::display(c.units));
  out += energy_text(s, u);
  out += fmt::format("  run time {:.3f} s\n", s.run_seconds);
  if (!s.complete) out += fmt::format("  {}\n", s.message);
  return out;
}

}  // namespace barimpact
