#include "barimpact/hopkinson/signal.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "barimpact/model/input_error.hpp"
#include "barimpact/run/results_h5.hpp"

namespace barimpact {

namespace {

using FileColumns = CsvColumns;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string_view unquote(std::string_view s) {
  s = trim(s);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return s;
}

std::vector<std::string_view> split(std::string_view line, char delimiter) {
  std::vector<std::string_view> cells;
  std::size_t from = 0;
  while (true) {
    const auto at = line.find(delimiter, from);
    cells.push_back(line.substr(from, at == std::string_view::npos ? std::string_view::npos : at - from));
    if (at == std::string_view::npos) return cells;
    from = at + 1;
  }
}

bool blank(std::string_view line) {
  return trim(line).empty();
}

class ColumnReader {
 public:
  ColumnReader(const CsvLayout& ch, std::filesystem::path file, std::vector<std::string> names,
               std::vector<std::string> keys)
      : ch_(ch), file_(std::move(file)), names_(std::move(names)), keys_(std::move(keys)) {}

  FileColumns read() {
    std::ifstream in(file_);
    if (!in) fail_file("cannot be read (no such file, or no permission)");
    FileColumns out;
    out.data.resize(names_.size());
    std::string line;
    long number = 0;
    bool have_layout = false;
    while (std::getline(in, line)) {
      ++number;
      // A UTF-8 byte order mark (spreadsheets write one) is not text of the first line.
      if (number == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
      if (number <= ch_.skip_rows) continue;
      if (!have_layout) {
        if (blank(line)) continue;
        layout(line, number);
        have_layout = true;
        if (ch_.header) continue;
      }
      if (blank(line)) continue;
      row(line, number, out);
    }
    if (in.bad()) fail_file("could not be read to the end");
    if (out.lines.empty()) fail_file("holds no samples");
    return out;
  }

 private:
  [[noreturn]] void fail_file(std::string_view rule) const {
    throw InputError(fmt::format("{}: {} {}", ch_.section, file_.string(), rule));
  }
  [[noreturn]] void fail_line(long line, std::string_view rule) const {
    throw InputError(fmt::format("{}:{}: {}: {}", file_.string(), line, ch_.section, rule));
  }

  // The header row (or, without one, the first row's width): where each named column is.
  void layout(const std::string& line, long number) {
    const auto cells = split(line, ch_.delimiter);
    std::vector<std::string> header;
    for (std::size_t i = 0; i < cells.size(); ++i)
      header.emplace_back(ch_.header ? std::string(unquote(cells[i])) : std::to_string(i + 1));
    auto index = [&](const std::string& name, std::string_view key) {
      const auto it = std::find(header.begin(), header.end(), name);
      if (it == header.end()) {
        const std::size_t shown = std::min<std::size_t>(header.size(), 12);
        fail_line(number, fmt::format("{}: no column \"{}\" (columns: {}{}{})", key, name,
                                      fmt::join(header.begin(), header.begin() + static_cast<long>(shown), ", "),
                                      header.size() > shown ? ", ..." : "",
                                      ch_.header ? "" : "; a file without a header names them \"1\", \"2\", ..."));
      }
      return static_cast<std::size_t>(it - header.begin());
    };
    if (!ch_.time_column.empty()) time_index_ = index(ch_.time_column, "time");
    for (std::size_t i = 0; i < names_.size(); ++i) data_index_.push_back(index(names_[i], keys_[i]));
  }

  double cell(const std::vector<std::string_view>& cells, std::size_t i, long line, const std::string& name) const {
    if (i >= cells.size()) fail_line(line, fmt::format("column \"{}\" is missing on this line", name));
    auto text = unquote(cells[i]);
    if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);  // from_chars takes no '+'
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty() || !std::isfinite(v))
      fail_line(line, fmt::format("column \"{}\" holds \"{}\", not a finite number", name, text));
    return v;
  }

  void row(const std::string& line, long number, FileColumns& out) const {
    const auto cells = split(line, ch_.delimiter);
    double t = 0.0;
    if (ch_.time_column.empty()) {
      t = static_cast<double>(out.lines.size()) * ch_.sample_interval;
    } else {
      t = cell(cells, time_index_, number, ch_.time_column);
      if (!out.t.empty() && !(t > out.t.back()))
        fail_line(number, fmt::format("time column \"{}\" is not increasing (t = {} after {})", ch_.time_column, t,
                                      out.t.back()));
    }
    out.t.push_back(t);
    for (std::size_t c = 0; c < names_.size(); ++c)
      out.data[c].push_back(cell(cells, data_index_[c], number, names_[c]));
    out.lines.push_back(number);
  }

  const CsvLayout& ch_;
  std::filesystem::path file_;
  std::vector<std::string> names_, keys_;
  std::size_t time_index_ = 0;
  std::vector<std::size_t> data_index_;
};

// A run's columns from the results.h5 it wrote (history.csv goes through
// ColumnReader), held to the same rules: finite samples, time increasing.
FileColumns read_run_results(const ChannelSetup& ch, const std::filesystem::path& file,
                             const std::vector<std::string>& names) {
  HistoryColumns h;
  try {
    h = read_results_h5_history(file);
  } catch (const std::runtime_error& e) {
    throw InputError(fmt::format("{}: {}", ch.section, e.what()));
  }
  auto column = [&](const std::string& name, std::string_view key) {
    const auto it = std::find(h.names.begin(), h.names.end(), name);
    if (it == h.names.end())
      throw InputError(fmt::format("{}: {}: {}: no column \"{}\" in /history", file.string(), ch.section, key, name));
    std::vector<double> values = std::move(h.values[static_cast<std::size_t>(it - h.names.begin())]);
    for (std::size_t k = 0; k < values.size(); ++k)
      if (!std::isfinite(values[k]))
        throw InputError(fmt::format("{}: {}: /history/{} holds {} at row {}, not a finite number", file.string(),
                                     ch.section, name, values[k], k + 1));
    return values;
  };
  FileColumns out;
  out.t = column(ch.time_column, "time");
  for (const auto& n : names) out.data.push_back(column(n, "strain"));
  for (std::size_t k = 1; k < out.t.size(); ++k)
    if (!(out.t[k] > out.t[k - 1]))
      throw InputError(fmt::format("{}: {}: /history/{} is not increasing (t = {} after {})", file.string(), ch.section,
                                   ch.time_column, out.t[k], out.t[k - 1]));
  if (out.t.empty()) throw InputError(fmt::format("{}: {} holds no samples", ch.section, file.string()));
  for (std::size_t k = 0; k < out.t.size(); ++k) out.lines.push_back(static_cast<long>(k + 1));
  return out;
}

// A measured channel clips when 3 or more consecutive samples reach its range.
void check_clipping(const ChannelSetup& ch, const std::filesystem::path& file, const std::string& name,
                    const FileColumns& f, const std::vector<double>& v) {
  constexpr int run_that_clips = 3;
  int run = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    run = std::abs(v[k]) >= *ch.full_scale ? run + 1 : 0;
    if (run == run_that_clips)
      throw InputError(fmt::format(
          "{}:{}: {}: column \"{}\" clips: {} consecutive samples at or beyond full_scale = {} from t = {} (a clipped "
          "pulse cannot be analysed: record with a larger range)",
          file.string(), f.lines[k + 1 - run_that_clips], ch.section, name, run_that_clips, *ch.full_scale,
          f.t[k + 1 - run_that_clips]));
  }
}

// The channels of several files must be one clock's samples.
void check_same_clock(const ChannelSetup& ch, const std::vector<double>& first, const FileColumns& other,
                      const std::filesystem::path& file) {
  if (other.t.size() != first.size())
    throw InputError(fmt::format("{}: {} has {} samples and {} has {}: the files of a channel must share one clock",
                                 ch.section, file.string(), other.t.size(), ch.files.front().string(), first.size()));
  const double spacing = first.size() > 1 ? (first.back() - first.front()) / double(first.size() - 1) : 0.0;
  for (std::size_t k = 0; k < first.size(); ++k)
    if (std::abs(other.t[k] - first[k]) > 0.01 * spacing)
      throw InputError(fmt::format("{}:{}: {}: t = {} where {} has t = {}: the files of a channel must share one clock",
                                   file.string(), other.lines[k], ch.section, other.t[k], ch.files.front().string(),
                                   first[k]));
}

}  // namespace

CsvColumns read_csv_columns(const CsvLayout& layout, const std::filesystem::path& file,
                            const std::vector<std::string>& names, const std::vector<std::string>& keys) {
  return ColumnReader(layout, file, names, keys).read();
}

GaugeSignal read_gauge_signal(const ChannelSetup& ch) {
  GaugeSignal s;
  s.simulated = !ch.run.empty();
  s.label = fmt::format("[{}] {}", ch.section, ch.files.front().string());
  std::vector<std::vector<double>> channels;
  for (std::size_t i = 0; i < ch.files.size(); ++i) {
    std::vector<std::string> names = ch.strain_columns;
    if (ch.files.size() > 1 && names.size() == ch.files.size()) names = {ch.strain_columns[i]};
    const CsvLayout layout{ch.section, ch.time_column, ch.header, ch.sample_interval, ch.delimiter, ch.skip_rows};
    const std::vector<std::string> keys(names.size(), ch.volts ? "volts" : "strain");
    auto f = !ch.run.empty() && ch.files[i].filename() == results_h5_name
                 ? read_run_results(ch, ch.files[i], names)
                 : read_csv_columns(layout, ch.files[i], names, keys);
    if (ch.full_scale)
      for (std::size_t c = 0; c < names.size(); ++c) check_clipping(ch, ch.files[i], names[c], f, f.data[c]);
    if (i == 0)
      s.t = std::move(f.t);  // the channel's clock
    else
      check_same_clock(ch, s.t, f, ch.files[i]);
    for (auto& d : f.data) channels.push_back(std::move(d));
  }
  // Volts through the bridge (linearised): eps = n V / (gain excitation gauge_factor).
  const double scale =
      ch.polarity *
      (ch.volts ? static_cast<double>(static_cast<int>(ch.bridge)) / (ch.gain * ch.excitation * ch.gauge_factor) : 1.0);
  s.strain.assign(s.t.size(), 0.0);
  for (const auto& c : channels)
    for (std::size_t k = 0; k < c.size(); ++k) s.strain[k] += c[k];
  for (auto& v : s.strain) v *= scale / static_cast<double>(channels.size());
  return s;
}

}  // namespace barimpact
