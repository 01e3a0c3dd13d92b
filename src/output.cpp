#include "barimpact/output.hpp"

#include <fmt/format.h>
#include <fmt/os.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace barimpact {

namespace fs = std::filesystem;

RunDirectory::RunDirectory(fs::path target) : target_(std::move(target)) {
  std::error_code ec;
  if (target_.empty()) throw InputError("--out: the output directory is empty");
  if (!target_.has_filename()) target_ = target_.parent_path();
  const fs::path parent = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw InputError(
        fmt::format("--out {}: the parent directory {} does not exist", target_.string(), parent.string()));
  if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
    throw InputError(fmt::format("--out {}: exists and is not a directory", target_.string()));
  staging_ = parent / fmt::format(".{}.partial-{}", target_.filename().string(), ::getpid());
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec)
    throw InputError(fmt::format("--out {}: cannot write in {} ({})", target_.string(), parent.string(),
                                 ec ? ec.message() : "not created"));
}

RunDirectory::~RunDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

namespace {

// Shortest text that reads back to the same double.
void write_history(const fs::path& path, const std::vector<HistoryRow>& rows) {
  auto out = fmt::output_file(path.string());
  out.print("t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc\n");
  for (const auto& r : rows)
    out.print("{},{},{},{},{},{},{},{},{}\n", r.t, r.U, r.V, r.R, r.E_kin, r.E_strain, r.E_obstacle, r.W_ext, r.D_visc);
  out.close();
}

void write_fields(const fs::path& path, const RunResult& result) {
  auto out = fmt::output_file(path.string());
  out.print("t,x,u,v,sigma\n");
  const Fields& f = result.fields;
  for (std::size_t s = 0; s < f.count(); ++s)
    for (std::size_t j = 0, i = s * f.nodes(); j < f.nodes(); ++j, ++i)
      out.print("{},{},{},{},{}\n", f.t[s], f.x[j], f.u[i], f.v[i], f.sigma[i]);
  out.close();
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

void write_text(const fs::path& path, const std::string& text) {
  auto out = fmt::output_file(path.string());
  out.print("{}", text);
  out.close();
}

void RunDirectory::commit(const Case& c, const RunResult& result) {
  commit([&](const fs::path& dir) {
    write_history(dir / "history.csv", result.history);
    write_fields(dir / "fields.csv", result);
    write_text(dir / "case.toml", c.to_toml());
    write_text(dir / "summary.json", summary_json(c, result.summary));
  });
}

void RunDirectory::commit(const std::function<void(const fs::path& staging)>& write) {
  try {
    write(staging_);
  } catch (const std::system_error& e) {
    throw InputError(fmt::format("--out {}: cannot write the results: {}", target_.string(), e.what()));
  }
  std::error_code ec;
  fs::path old;
  if (fs::exists(target_, ec)) {
    old = staging_.parent_path() / fmt::format(".{}.old-{}", target_.filename().string(), ::getpid());
    fs::rename(target_, old, ec);
    if (ec)
      throw InputError(
          fmt::format("--out {}: cannot replace the existing directory: {}", target_.string(), ec.message()));
  }
  fs::rename(staging_, target_, ec);
  if (ec)
    throw InputError(fmt::format("--out {}: cannot move the results into place: {}", target_.string(), ec.message()));
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

std::string summary_json(const Case& c, const Summary& s) {
  nlohmann::json contacts = nlohmann::json::array();
  for (const auto& ci : s.contacts)
    contacts.push_back({{"start", ci.start},
                        {"end", ci.end},
                        {"closed", ci.closed},
                        {"exit_velocity", ci.closed ? number_or_null(ci.exit_velocity) : nlohmann::json(nullptr)},
                        {"rebound_velocity", ci.closed ? number_or_null(ci.rebound_velocity) : nlohmann::json(nullptr)},
                        {"max_reaction", ci.max_reaction}});
  const double rel = s.energy_initial != 0.0 ? s.energy_error_max / std::abs(s.energy_initial) : s.energy_error_max;
  const nlohmann::json j = {
      {"complete", s.complete},
      {"status", std::string(to_string(s.status))},
      {"message", s.message},
      {"scheme", s.method},
      {"steps", s.steps},
      {"steps_done", s.steps_done},
      {"step", c.time.step},
      {"elements", c.bar.elements},
      {"t_end", s.t_end},
      {"contacts", contacts},
      {"contact_count", s.contacts.size()},
      {"max_penetration", s.max_penetration},
      {"max_reaction", s.max_reaction},
      {"energy_initial", number_or_null(s.energy_initial)},
      {"energy_final", number_or_null(s.energy_final)},
      {"energy_error_max", number_or_null(s.energy_error_max)},
      {"energy_error_relative", number_or_null(rel)},
      {"run_seconds", s.run_seconds},
  };
  return j.dump(2) + "\n";
}

std::string summary_text(const Case& c, const Summary& s) {
  std::string out = fmt::format("{}: {} steps of dt = {} on {} elements, t = 0 .. {}{}\n", s.method, s.steps_done,
                                c.time.step, c.bar.elements, s.t_end, s.complete ? "" : " (INCOMPLETE)");
  if (s.contacts.empty()) out += "  no contact\n";
  constexpr std::size_t shown = 8;
  for (std::size_t i = 0; i < std::min(shown, s.contacts.size()); ++i) {
    const auto& ci = s.contacts[i];
    if (ci.closed)
      out += fmt::format(
          "  contact {}: t = {:.6g} .. {:.6g}, max R = {:.4g}, leaves with mean velocity {:+.4g} (end {:+.4g})\n",
          i + 1, ci.start, ci.end, ci.max_reaction, ci.rebound_velocity, ci.exit_velocity);
    else
      out += fmt::format("  contact {}: t = {:.6g} .. (still in contact at the end), max R = {:.4g}\n", i + 1, ci.start,
                         ci.max_reaction);
  }
  if (s.contacts.size() > shown)
    out += fmt::format("  ... {} more contact episodes in summary.json\n", s.contacts.size() - shown);
  out += fmt::format("  max penetration {:.4g}, max reaction {:.4g}\n", s.max_penetration, s.max_reaction);
  if (std::isfinite(s.energy_initial))
    out += fmt::format("  energy: initial {:.6g}, final {:.6g}, max balance error {:.3g} ({:.2g}% of initial)\n",
                       s.energy_initial, s.energy_final, s.energy_error_max,
                       s.energy_initial != 0.0 ? 100.0 * s.energy_error_max / std::abs(s.energy_initial) : 0.0);
  else
    out += "  energy: not known for this solution\n";
  out += fmt::format("  run time {:.3f} s\n", s.run_seconds);
  if (!s.complete) out += fmt::format("  {}\n", s.message);
  return out;
}

}  // namespace barimpact
