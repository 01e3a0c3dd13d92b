#include "field_stream.hpp"

#include "barimpact/model/input_error.hpp"

namespace barimpact::detail {

namespace fs = std::filesystem;

FieldStream::FieldStream(const fs::path& staging, const Case& c)
    : path_(staging / (c.output.format == OutputFormat::hdf5 ? spool_name : "fields.csv")),
      spooled_(c.output.format == OutputFormat::hdf5),
      out_(std::make_unique<OutputFile>(path_)) {
  times_.reserve(c.output.fields_at.size());  // the run's loop does not allocate
  if (!spooled_) out_->print("t,x,u,v,sigma,eps_p,body\n");
}

bool FieldStream::write(const Fields& f) {
  if (failure_) return false;
  try {
    const std::size_t n = f.nodes();
    nodes_ = n;
    times_.push_back(f.t.front());
    if (spooled_) {
      for (const auto* values : {&f.u, &f.v, &f.sigma, &f.eps_p})
        out_->write({reinterpret_cast<const char*>(values->data()), n * sizeof(double)});
      return true;
    }
    for (std::size_t j = 0; j < n; ++j)
      out_->print("{},{},{},{},{},{},{}\n", f.t.front(), f.x[j], f.u[j], f.v[j], f.sigma[j], f.eps_p[j],
                  f.body_names[f.body[j]]);
    return true;
  } catch (...) {
    failure_ = std::current_exception();  // rethrown by finish(): the run stops here
    return false;
  }
}

void FieldStream::finish() {
  if (failure_) std::rethrow_exception(failure_);
  out_->close();
  if (spooled_) in_.open(path_, std::ios::binary);
}

void FieldStream::read(int q, std::size_t first, std::size_t count, double* out) {
  const std::size_t bytes = nodes_ * sizeof(double);
  for (std::size_t s = 0; s < count; ++s) {
    in_.seekg(static_cast<std::streamoff>(((first + s) * 4 + static_cast<std::size_t>(q)) * bytes));
    in_.read(reinterpret_cast<char*>(out + s * nodes_), static_cast<std::streamsize>(bytes));
    if (!in_) throw OutputError(fmt::format("{}: cannot read it back", path_.string()), path_, "short read");
  }
}

void FieldStream::remove_spool() {
  in_.close();
  std::error_code ec;
  fs::remove(path_, ec);
}

}  // namespace barimpact::detail
