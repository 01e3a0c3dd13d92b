#include "barimpact/run/output_directory.hpp"

#include <fmt/format.h>
#include <pwd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "barimpact/case/case.hpp"
#include "output_file.hpp"

namespace barimpact {

namespace fs = std::filesystem;

namespace {

// The home directory: $HOME, or the password database's when it is unset.
fs::path home_directory();

// The absolute, symlink-resolved form of `p`, with no trailing separator.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path full = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) full = fs::absolute(p).lexically_normal();
  if (!full.has_filename() && full != full.root_path()) full = full.parent_path();
  return full;
}

fs::path home_directory() {
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') return resolved(home);
  if (const passwd* entry = ::getpwuid(::getuid()); entry != nullptr && entry->pw_dir != nullptr)
    return resolved(entry->pw_dir);
  return {};
}

// True when `a` is a proper ancestor of `b` (both resolved).
bool is_parent_of(const fs::path& a, const fs::path& b) {
  if (a == b) return false;
  auto ai = a.begin(), bi = b.begin();
  for (; ai != a.end(); ++ai, ++bi)
    if (bi == b.end() || *ai != *bi) return false;
  return true;
}

// The marker of `dir`, if barimpact wrote it: its JSON, else null.
nlohmann::json read_marker(const fs::path& dir) {
  std::ifstream in(dir / output_marker);
  if (!in) return nullptr;
  try {
    auto j = nlohmann::json::parse(in);
    if (j.value("written_by", "") == "barimpact" && j.contains("entries")) return j;
  } catch (const std::exception&) {
  }
  return nullptr;  // unreadable: not a marker barimpact wrote
}

std::vector<std::string> marker_entries(const fs::path& dir) {
  const auto j = read_marker(dir);
  try {
    return j.is_null() ? std::vector<std::string>{} : j.at("entries").get<std::vector<std::string>>();
  } catch (const std::exception&) {
    return {};
  }
}

std::string some_names(const std::vector<std::string>& names) {
  constexpr std::size_t shown = 3;
  std::string out;
  for (std::size_t i = 0; i < std::min(shown, names.size()); ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > shown) out += fmt::format(" and {} more", names.size() - shown);
  return out;
}

}  // namespace

std::vector<std::string> directory_entries(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    names.push_back(it->path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

// The entries of `dir` that are not barimpact's, recursively: a directory
// with a marker owns what it lists (a listed directory must be owned in
// turn); a directory without one (a study's runs/) owns only directories
// that are owned. Links are entries, never followed.
// A file barimpact stages before renaming it onto a listed entry of its
// directory (replace_text's ".sweep.csv.partial-<pid>"): ours while it is
// written, and left behind only when that process was killed.
bool staged_entry(const std::string& name, const std::set<std::string>& ours) {
  const auto at = name.rfind(".partial-");
  if (name.size() < 2 || name[0] != '.' || at == std::string::npos || at < 2) return false;
  const std::string digits = name.substr(at + 9);
  return !digits.empty() && digits.size() <= 9 && digits.find_first_not_of("0123456789") == std::string::npos &&
         ours.count(name.substr(1, at - 1)) > 0;
}

std::vector<std::string> foreign_entries(const fs::path& dir) {
  const auto listed = marker_entries(dir);
  const std::set<std::string> ours(listed.begin(), listed.end());
  std::vector<std::string> foreign;
  for (const auto& name : directory_entries(dir)) {
    std::error_code ec;
    const bool is_dir = fs::symlink_status(dir / name, ec).type() == fs::file_type::directory;
    if (!listed.empty() && name == output_marker) continue;
    if (is_dir && fs::exists(dir / name / staging_flag, ec)) continue;  // a run of barimpact's being written
    if (!is_dir && staged_entry(name, ours)) continue;                  // a listed file being replaced
    if (!listed.empty() && !ours.count(name)) {
      foreign.push_back(name);
    } else if (is_dir && listed.empty() && marker_entries(dir / name).empty()) {
      foreign.push_back(name);  // in a directory without a marker, only barimpact's own directories are ours
    } else if (is_dir) {
      for (const auto& inner : foreign_entries(dir / name)) foreign.push_back(name + "/" + inner);
    } else if (listed.empty()) {
      foreign.push_back(name);
    }
  }
  return foreign;
}

}  // namespace

bool written_by_barimpact(const fs::path& dir) {
  return !marker_entries(dir).empty() && foreign_entries(dir).empty();
}

std::vector<std::string> marked_entries(const fs::path& dir) {
  return marker_entries(dir);
}

bool CommandInputs::reads_file(const fs::path& path) const {
  const fs::path p = resolved(path);
  return std::any_of(files.begin(), files.end(), [&](const fs::path& f) { return !f.empty() && resolved(f) == p; });
}

fs::path CommandInputs::file_under(const fs::path& dir, const std::string& entry) const {
  const fs::path at = resolved(dir) / entry;  // a link named `entry` is replaced, not written through
  for (const auto& f : files)
    if (!f.empty() && (resolved(f) == at || is_parent_of(at, resolved(f)))) return f;
  return {};
}

void refuse_names_over_inputs(const fs::path& dir, const std::vector<std::string>& names, const CommandInputs& inputs,
                              std::string_view option) {
  for (const auto& name : names)
    if (const auto f = inputs.file_under(dir, name); !f.empty())
      throw InputError(
          fmt::format("{} {}: barimpact would write {} over {}, which this command reads; it never "
                      "writes over its input, --force or not (choose another directory)",
                      option, dir.string(), name, f.string()));
}

namespace {

constexpr std::string_view never_over_input =
    "barimpact never writes its results over what it reads, --force or not (choose another directory)";

// --out may not be an input file, nor a directory the command reads or a parent of one.
void refuse_inputs(const fs::path& full, const CommandInputs& inputs, const std::function<void(std::string)>& refuse) {
  for (const auto& d : inputs.directories) {
    if (d.empty()) continue;
    if (resolved(d) == full) refuse(fmt::format("is the directory this command reads; {}", never_over_input));
    if (is_parent_of(full, resolved(d)))
      refuse(fmt::format("is a parent of {}, a directory this command reads; {}", d.string(), never_over_input));
  }
  if (inputs.reads_file(full)) refuse(fmt::format("is the file this command reads; {}", never_over_input));
}

// The first input file inside `full` (resolved), or empty.
fs::path input_inside(const fs::path& full, const CommandInputs& inputs) {
  for (const auto& f : inputs.files)
    if (!f.empty() && is_parent_of(full, resolved(f))) return f;
  return {};
}

}  // namespace

std::string output_command(const fs::path& dir) {
  const auto j = read_marker(dir);
  return j.is_null() ? std::string() : j.value("command", "");
}

OutputMode check_output_directory(const fs::path& target, bool force, std::string_view option,
                                  const CommandInputs& inputs) {
  if (target.empty()) throw InputError(fmt::format("{}: the output directory is empty", option));
  auto refuse = [&](std::string_view why) { throw InputError(fmt::format("{} {}: {}", option, target.string(), why)); };
  const fs::path full = resolved(target);
  std::error_code ec;
  const fs::path cwd = resolved(fs::current_path(ec));
  if (full == full.root_path()) refuse("is the root directory; barimpact never writes its results there");
  if (full == home_directory())
    refuse("is your home directory; barimpact never writes its results there (choose a new directory inside it)");
  if (is_parent_of(full, cwd)) refuse("is a parent of the working directory; barimpact never writes its results there");
  refuse_inputs(full, inputs, refuse);
  if (!fs::exists(full, ec)) {
    // Missing parents are made when the results are written (MadeParents);
    // the nearest existing one must be a directory barimpact may write in.
    fs::path above = full.parent_path();
    while (!fs::exists(above, ec) && above != above.root_path()) above = above.parent_path();
    if (!fs::is_directory(above, ec)) refuse(fmt::format("{} is not a directory", above.string()));
    if (::access(above.c_str(), W_OK | X_OK) != 0) refuse(fmt::format("{} is not writable", above.string()));
    return OutputMode::create;
  }
  if (!fs::is_directory(full, ec)) refuse("exists and is not a directory");
  if (::access(full.c_str(), W_OK | X_OK) != 0) refuse("is not writable");
  if (fs::exists(fs::symlink_status(full / output_marker, ec)) && marker_entries(full).empty())
    refuse(fmt::format("holds a {} that barimpact did not write; choose a new or empty directory", output_marker));
  if (full == cwd) {
    if (!force)
      refuse(
          "is the working directory; choose a new directory, or add --force to write barimpact's files beside yours "
          "(nothing of yours is deleted)");
    return OutputMode::beside;
  }
  if (directory_entries(full).empty()) return OutputMode::create;
  const auto foreign = foreign_entries(full);
  if (foreign.empty()) {
    if (const auto f = input_inside(full, inputs); !f.empty())
      refuse(
          fmt::format("holds {}, which this command reads; barimpact never replaces or resumes in a directory "
                      "it reads from, --force or not (choose another directory)",
                      f.string()));
    return OutputMode::replace;
  }
  if (!force)
    refuse(fmt::format(
        "holds files barimpact did not write ({}); choose a new or empty directory, or add --force to write "
        "barimpact's files beside them (nothing of yours is deleted)",
        some_names(foreign)));
  return OutputMode::beside;
}

namespace {

void write_marker(const fs::path& dir, std::string_view command, const std::set<std::string>& all) {
  const nlohmann::json j = {{"written_by", "barimpact"},
                            {"version", BARIMPACT_VERSION},
                            {"command", std::string(command)},
                            {"note",
                             "barimpact replaces or resumes this directory; it never touches what is not "
                             "listed in entries"},
                            {"entries", std::vector<std::string>(all.begin(), all.end())}};
  detail::replace_file(dir / fmt::format("{}.{}", output_marker, ::getpid()), dir / output_marker, j.dump(2) + "\n");
}

}  // namespace

void write_output_marker(const fs::path& dir, std::string_view command, const std::vector<std::string>& entries) {
  std::set<std::string> all(entries.begin(), entries.end());
  for (const auto& e : marker_entries(dir)) all.insert(e);
  all.erase(std::string(output_marker));
  write_marker(dir, command, all);
}

void remove_listed_files(const fs::path& dir, std::string_view command, const std::vector<std::string>& names) {
  const auto listed = marker_entries(dir);
  std::set<std::string> kept(listed.begin(), listed.end());
  bool removed = false;
  for (const auto& name : names) {
    std::error_code ec;
    if (kept.count(name) == 0 || !fs::is_regular_file(fs::symlink_status(dir / name, ec))) continue;
    if (fs::remove(dir / name, ec)) {
      kept.erase(name);
      removed = true;
    }
  }
  if (removed) write_marker(dir, command, kept);
}

void remove_stale_staging(const fs::path& parent, const std::string& name) {
  for (const auto& entry : directory_entries(parent)) {
    if (entry.size() < 2 || entry[0] != '.') continue;
    for (const std::string_view kind : {".partial-", ".old-"}) {
      const auto at = name.empty() ? entry.rfind(kind) : name.size() + 1;
      if (at == std::string::npos || at == 0 || at + kind.size() >= entry.size()) continue;
      if (entry.compare(at, kind.size(), kind) != 0) continue;
      if (!name.empty() && entry.compare(1, name.size(), name) != 0) continue;
      const std::string digits = entry.substr(at + kind.size());
      if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
      const auto pid = static_cast<pid_t>(std::stol(digits));
      if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
      // Only what barimpact made: a staging directory carries its flag, an
      // old results directory is barimpact's whole.
      std::error_code ec;
      const fs::path path = parent / entry;
      const auto type = fs::symlink_status(path, ec).type();
      if (type == fs::file_type::regular) {  // a listed file's staged copy its killed writer left
        const auto listed = marker_entries(parent);
        if (staged_entry(entry, std::set<std::string>(listed.begin(), listed.end()))) fs::remove(path, ec);
        continue;
      }
      if (type != fs::file_type::directory) continue;
      if (fs::exists(path / staging_flag, ec) || written_by_barimpact(path)) fs::remove_all(path, ec);
    }
  }
}

MadeParents::MadeParents(const fs::path& target) {
  std::error_code ec;
  for (fs::path p = resolved(target).parent_path(); !fs::exists(p, ec) && p != p.root_path(); p = p.parent_path())
    made_.push_back(p);
  std::reverse(made_.begin(), made_.end());
  for (std::size_t i = 0; i < made_.size(); ++i)
    if (!fs::create_directory(made_[i], ec) && ec) {
      const std::string why =
          fmt::format("--out {}: cannot create {} ({})", target.string(), made_[i].string(), ec.message());
      made_.resize(i);
      remove_made();  // a constructor that throws has no destructor run
      throw InputError(why);
    }
}

MadeParents::~MadeParents() {
  remove_made();
}

void MadeParents::remove_made() {
  std::error_code ec;
  for (auto p = made_.rbegin(); p != made_.rend(); ++p) fs::remove(*p, ec);  // empty ones only
  made_.clear();
}

void refuse_entries_of_another_kind(const fs::path& dir, const std::vector<std::string>& names,
                                    std::string_view option) {
  for (const auto& name : names) {
    std::error_code ec;
    const bool directory = written_as_directory(name);
    // A file replaces a link of its name; a directory is written through one.
    const auto type = (directory ? fs::status(dir / name, ec) : fs::symlink_status(dir / name, ec)).type();
    if (type == fs::file_type::not_found || type == fs::file_type::none) continue;
    if ((type == fs::file_type::directory) != directory)
      throw InputError(fmt::format(
          "{} {}: holds {} {} where barimpact writes {} of that name; nothing was written (rename or move it, "
          "or choose another directory)",
          option, dir.string(), type == fs::file_type::directory ? "a directory" : "a file", name,
          directory ? "a directory" : "a file"));
  }
}

void prepare_output_directory(const fs::path& target, std::string_view command, const std::vector<std::string>& entries,
                              bool force, std::string_view option, const CommandInputs& inputs) {
  (void)check_output_directory(target, force, option, inputs);
  refuse_names_over_inputs(target, entries, inputs, option);
  refuse_entries_of_another_kind(target, entries, option);
  std::error_code ec;
  fs::create_directories(target, ec);
  if (ec)
    throw OutputError(fmt::format("{} {}: cannot create it ({})", option, target.string(), ec.message()), target,
                      ec.message());
  try {
    write_output_marker(target, command, entries);
  } catch (const OutputError& e) {
    throw OutputError(fmt::format("{} {}: cannot write in it ({})", option, target.string(), e.what()), e.path(),
                      e.reason());
  }
}

}  // namespace barimpact
