// results.h5: a run's history and fields in one HDF5 file, what a run
// directory holds instead of history.csv and fields.csv when the case says
// `[output] format = "hdf5"`. The same numbers, bit for bit (float64):
//
//   /                 attributes `case` (the resolved case, case.toml's text)
//                     and `units` ([units] system: "SI", "US" or "none")
//   /history          attribute `columns`: the column names in history.csv's
//                     order (HDF5 lists a group's members alphabetically)
//   /history/<name>   one 1-D float64 dataset per history.csv column, one
//                     value per row: /history/t, /history/U, ...,
//                     /history/gauge.mid.strain
//   /fields           attribute `columns`: fields.csv's (t, x, u, v, sigma,
//                     eps_p, body)
//   /fields/t         (snapshots,) the snapshots' times
//   /fields/x         (rows,) the rows' positions: each bar body's nodes in
//                     line order, a welded node once per body
//   /fields/u, v, sigma, eps_p
//                     (snapshots, rows) float64: [s, j] is fields.csv's row
//                     of snapshot s and row j (extendible along the
//                     snapshots, chunked by whole snapshots up to 256 KiB, a
//                     larger one in pieces; shuffled
//                     and compressed with gzip at level output.compression,
//                     1 by default, none at 0)
//   /fields/body      (rows,) int32, each row's body as an index into the
//                     attribute `names` (fields.csv's `body` column of one
//                     snapshot: names[body[j]])
//
// With h5py: f["history/U"][:], f["fields/u"][s, :], f.attrs["case"].
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact {

/// What the HDF5 library refused (a file it cannot create, read or close),
/// with its reason: the run directory turns it into a one-line refusal.
struct Hdf5Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The file's name in a run directory.
inline constexpr std::string_view results_h5_name = "results.h5";

/// Writes `result`'s history and fields, and `c` as attributes, into a new
/// file at `path` (replaced if it exists), a snapshot at a time. Throws
/// Hdf5Error (what HDF5 refused) or OutputError (what the file system
/// refused: a full disk), naming the path; HDF5 holds no file open
/// afterwards, and a file not written whole is removed. A run directory
/// writes its results.h5 as the run goes instead (RunDirectory::stream_fields).
void write_results_h5(const std::filesystem::path& path, const Case& c, const RunResult& result);

/// A history by column, as history.csv holds it.
struct HistoryColumns {
  std::vector<std::string> names;           ///< in history.csv's order
  std::vector<std::vector<double>> values;  ///< one per name, one value per row
};

/// Every history column of a results.h5, in history.csv's order. Throws
/// std::runtime_error naming the path and what is missing.
[[nodiscard]] HistoryColumns read_results_h5_history(const std::filesystem::path& path);

}  // namespace barimpact
