// Field snapshots written as a run takes them, into its run directory's
// staging: fields.csv row by row, or, for results.h5 (made whole at the
// end), a spool of raw doubles the HDF5 writer reads back a few snapshots
// at a time. Either way the run holds one snapshot, never all of them, and
// the files are the bytes the held snapshots would have made.
#pragma once

#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/observer.hpp"
#include "output_file.hpp"

namespace barimpact::detail {

class FieldStream final : public FieldSink {
 public:
  /// Writes into `staging`: fields.csv, or (hdf5) the spool `spool_name`.
  FieldStream(const std::filesystem::path& staging, const Case& c);
  bool write(const Fields& snapshot) override;
  /// After the run: a write's error rethrown, else the file closed whole.
  void finish();

  [[nodiscard]] bool spooled() const { return spooled_; }
  /// The snapshots' times (the spool's).
  [[nodiscard]] const std::vector<double>& times() const { return times_; }
  /// Quantity q's (0 u, 1 v, 2 sigma, 3 eps_p) values of snapshots
  /// first .. first + count - 1, snapshot-major, into `out` (the spool's).
  void read(int q, std::size_t first, std::size_t count, double* out);
  /// The spool removed (once results.h5 holds it).
  void remove_spool();

  static constexpr const char* spool_name = ".fields.spool";

 private:
  std::filesystem::path path_;
  bool spooled_;
  std::unique_ptr<OutputFile> out_;
  std::exception_ptr failure_;
  std::vector<double> times_;
  std::size_t nodes_ = 0;
  std::ifstream in_;
};

}  // namespace barimpact::detail
