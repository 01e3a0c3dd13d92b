// Field snapshots written as a run takes them, into its run directory's
// staging: fields.csv row by row, or results.h5's /fields extended by each
// (its history and the rest written at the end). Either way the run holds
// one snapshot, never all of them, and the files are those the held
// snapshots would have made.
#pragma once

#include <exception>
#include <filesystem>
#include <memory>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/observer.hpp"
#include "output_file.hpp"
#include "results_h5_module.hpp"

namespace barimpact::detail {

class FieldStream final : public FieldSink {
 public:
  /// Writes into `staging`: fields.csv, or results.h5.
  FieldStream(const std::filesystem::path& staging, const Case& c);
  bool write(const Fields& snapshot) override;
  /// After the run: a write's error rethrown, else the file closed whole
  /// (results.h5 with the rest of `result`).
  void finish(const Case& c, const RunResult& result);

 private:
  std::unique_ptr<OutputFile> csv_;
  std::unique_ptr<ResultsH5File> h5_;
  std::exception_ptr failure_;
  std::vector<double> times_;
};

}  // namespace barimpact::detail
