#include "field_stream.hpp"

namespace barimpact::detail {

namespace fs = std::filesystem;

FieldStream::FieldStream(const fs::path& staging, const Case& c) {
  times_.reserve(c.output.fields_at.size());  // the run's loop does not allocate
  if (c.output.format == OutputFormat::hdf5) {
    h5_ = std::make_unique<ResultsH5File>(staging / results_h5_name, c, c.output.fields_at.size());
    return;
  }
  csv_ = std::make_unique<OutputFile>(staging / "fields.csv");
  csv_->print("t,x,u,v,sigma,eps_p,body\n");
}

bool FieldStream::write(const Fields& f) {
  if (failure_) return false;
  try {
    const std::size_t n = f.nodes();
    times_.push_back(f.t.front());
    if (h5_) {
      h5_->append({f.u.data(), f.v.data(), f.sigma.data(), f.eps_p.data()}, n);
      return true;
    }
    for (std::size_t j = 0; j < n; ++j)
      csv_->print("{},{},{},{},{},{},{}\n", f.t.front(), f.x[j], f.u[j], f.v[j], f.sigma[j], f.eps_p[j],
                  f.body_names[f.body[j]]);
    return true;
  } catch (...) {
    failure_ = std::current_exception();  // rethrown by finish(): the run stops here
    return false;
  }
}

void FieldStream::finish(const Case& c, const RunResult& result) {
  if (failure_) std::rethrow_exception(failure_);
  if (h5_)
    h5_->finish(c, result, times_);
  else
    csv_->close();
}

}  // namespace barimpact::detail
