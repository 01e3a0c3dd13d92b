#include "results_h5_module.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <hdf5.h>
#include <unistd.h>
#if H5_VERSION_GE(1, 13, 2)
#include <H5FDdevelop.h>
#endif

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>

namespace barimpact {

namespace fs = std::filesystem;

namespace {

// Field chunks of about this many bytes: as many whole snapshots as fit,
// so that reading one is one chunk; a larger snapshot in pieces of it.
constexpr hsize_t chunk_bytes = 256 * 1024;

// The innermost message of the calling thread's HDF5 error stack (where the
// error was found), then the stack cleared.
std::string hdf5_error() {
  std::string message;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0 && e->desc != nullptr) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &message);
  H5Eclear2(H5E_DEFAULT);
  return message.empty() ? std::string("HDF5 error") : message;
}

// A stretch of HDF5 calls: one thread at a time (not every build of the
// library is thread-safe: a sweep's workers write runs together), with the
// library's printing of its error stack on stderr held back: failures are
// exceptions here. The caller's error handler (h5py's, say) is put back.
class Session {
 public:
  Session() : lock_(mutex()) {
    H5Eget_auto2(H5E_DEFAULT, &handler_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~Session() { H5Eset_auto2(H5E_DEFAULT, handler_, data_); }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  H5E_auto2_t handler_ = nullptr;
  void* data_ = nullptr;
};

// An HDF5 identifier, closed with the object; a negative one (a failed
// call) throws, naming `what` and the library's reason.
class Id {
 public:
  Id(hid_t id, herr_t (*closer)(hid_t), const std::string& what) : id_(id), close_(closer) {
    if (id_ < 0) throw Hdf5Error(fmt::format("{} ({})", what, hdf5_error()));
  }
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  Id(Id&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id& operator=(Id&&) = delete;
  operator hid_t() const { return id_; }  // NOLINT: used where HDF5 takes an hid_t
  /// Closes now, throwing when that fails (a file's close writes what it holds).
  void close(const std::string& what) {
    const herr_t status = close_(id_);
    id_ = -1;
    if (status < 0) throw Hdf5Error(fmt::format("{} ({})", what, hdf5_error()));
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw Hdf5Error(fmt::format("{} ({})", what, hdf5_error()));
}

// The file driver results.h5 is written through: POSIX calls on one
// descriptor, as HDF5's sec2 driver, except that a write the system refuses
// (a full disk) is not reported to HDF5. The first refusal is kept for the
// writer to report with the system's reason, and later writes are dropped:
// HDF5's close, which writes what it holds, then never fails, and never
// leaves the file half-closed (HDF5 kept a freed file then, and crashed at
// exit once the staging directory was gone).
struct DriverInfo {
  int* error;  // the first errno the system gave; 0 while none
};

struct DriverFile {
  H5FD_t base;  // first: what HDF5 sees
  int fd = -1;
  haddr_t eoa = 0, eof = 0;
  int* error = nullptr;
};

DriverFile& as_file(H5FD_t* file) {
  return *reinterpret_cast<DriverFile*>(file);
}
const DriverFile& as_file(const H5FD_t* file) {
  return *reinterpret_cast<const DriverFile*>(file);
}
void keep(int* error, int value) {
  if (*error == 0) *error = value;
}

H5FD_t* driver_open(const char* name, unsigned flags, hid_t fapl, haddr_t /*maxaddr*/) {
  const auto* info = static_cast<const DriverInfo*>(H5Pget_driver_info(fapl));
  if (info == nullptr) return nullptr;
  int mode = (flags & H5F_ACC_RDWR) != 0 ? O_RDWR : O_RDONLY;
  if ((flags & H5F_ACC_CREAT) != 0) mode |= O_CREAT;
  if ((flags & H5F_ACC_TRUNC) != 0) mode |= O_TRUNC;
  if ((flags & H5F_ACC_EXCL) != 0) mode |= O_EXCL;
  int fd = -1;
  do {
    fd = ::open(name, mode | O_CLOEXEC, 0666);
  } while (fd < 0 && errno == EINTR);
  if (fd < 0) {
    // HDF5 first tries the file without creating it, to see whether it is
    // open already: only the creation's failure is the file's.
    if ((flags & H5F_ACC_CREAT) != 0) keep(info->error, errno);
    return nullptr;
  }
  auto* file = new DriverFile{};
  file->fd = fd;
  file->error = info->error;
  file->eof = static_cast<haddr_t>(std::max<off_t>(::lseek(fd, 0, SEEK_END), 0));
  return &file->base;
}

herr_t driver_close(H5FD_t* base) {
  DriverFile& file = as_file(base);
  if (::close(file.fd) != 0 && errno != EINTR) keep(file.error, errno);
  delete &file;
  return 0;
}

int driver_compare(const H5FD_t* a, const H5FD_t* b) {
  return std::less<const H5FD_t*>()(a, b) ? -1 : a == b ? 0 : 1;
}

herr_t driver_query(const H5FD_t* /*file*/, unsigned long* flags) {
  if (flags != nullptr)
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA;
  return 0;
}

haddr_t driver_get_eoa(const H5FD_t* file, H5FD_mem_t /*type*/) {
  return as_file(file).eoa;
}
herr_t driver_set_eoa(H5FD_t* file, H5FD_mem_t /*type*/, haddr_t address) {
  as_file(file).eoa = address;
  return 0;
}
haddr_t driver_get_eof(const H5FD_t* file, H5FD_mem_t /*type*/) {
  return as_file(file).eof;
}
herr_t driver_get_handle(H5FD_t* file, hid_t /*fapl*/, void** handle) {
  *handle = &as_file(file).fd;
  return 0;
}

// Past the end of the file: zeros, as sec2 reads.
herr_t driver_read(H5FD_t* base, H5FD_mem_t /*type*/, hid_t /*dxpl*/, haddr_t address, size_t size, void* buffer) {
  DriverFile& file = as_file(base);
  auto* out = static_cast<char*>(buffer);
  while (size > 0) {
    const ssize_t n = ::pread(file.fd, out, size, static_cast<off_t>(address));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      keep(file.error, errno);
      return -1;
    }
    if (n == 0) {
      std::fill(out, out + size, char{0});
      break;
    }
    out += n, address += static_cast<haddr_t>(n), size -= static_cast<size_t>(n);
  }
  return 0;
}

herr_t driver_write(H5FD_t* base, H5FD_mem_t /*type*/, hid_t /*dxpl*/, haddr_t address, size_t size,
                    const void* buffer) {
  DriverFile& file = as_file(base);
  if (*file.error != 0) return 0;  // the file is refused already: dropped
  const auto* in = static_cast<const char*>(buffer);
  for (haddr_t at = address; size > 0;) {
    const ssize_t n = ::pwrite(file.fd, in, size, static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      keep(file.error, n < 0 ? errno : EIO);
      return 0;
    }
    in += n, at += static_cast<haddr_t>(n), size -= static_cast<size_t>(n);
    file.eof = std::max(file.eof, at);
  }
  return 0;
}

herr_t driver_truncate(H5FD_t* base, hid_t /*dxpl*/, hbool_t /*closing*/) {
  DriverFile& file = as_file(base);
  if (file.eoa == file.eof || *file.error != 0) return 0;
  if (::ftruncate(file.fd, static_cast<off_t>(file.eoa)) != 0)
    keep(file.error, errno);
  else
    file.eof = file.eoa;
  return 0;
}

H5FD_class_t checked_driver_class() {
  H5FD_class_t c{};
#if H5_VERSION_GE(1, 13, 2)
  c.version = H5FD_CLASS_VERSION;
  c.value = static_cast<H5FD_class_value_t>(620);  // a user driver's (above 255)
#endif
  c.name = "barimpact_checked";
  c.maxaddr = (haddr_t{1} << (8 * sizeof(off_t) - 1)) - 1;
  c.fc_degree = H5F_CLOSE_STRONG;
  c.fapl_size = sizeof(DriverInfo);
  c.open = driver_open;
  c.close = driver_close;
  c.cmp = driver_compare;
  c.query = driver_query;
  c.get_eoa = driver_get_eoa;
  c.set_eoa = driver_set_eoa;
  c.get_eof = driver_get_eof;
  c.get_handle = driver_get_handle;
  c.read = driver_read;
  c.write = driver_write;
  c.truncate = driver_truncate;
  const std::array<H5FD_mem_t, H5FD_MEM_NTYPES> map H5FD_FLMAP_DICHOTOMY;
  std::copy(map.begin(), map.end(), c.fl_map);
  return c;
}

// The driver, registered once (within a Session).
hid_t checked_driver() {
  static const H5FD_class_t driver = checked_driver_class();
  static const hid_t id = H5FDregister(&driver);
  if (id < 0) throw Hdf5Error(fmt::format("cannot register HDF5's file driver ({})", hdf5_error()));
  return id;
}

// A results.h5 written in the run directory through the checked driver.
// A failure is a std::system_error when the system refused a write (with
// its reason, naming the file), else Hdf5Error; either way the file is
// closed by the writer's end, every handle of it first.
class Writer {
 public:
  explicit Writer(const fs::path& path) : path_(path.string()) {
    guarded([&] {
      const Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, at(""));
      // The 1.8 file format (compact groups), which every HDF5 from 1.8 on
      // reads (h5py's included): nothing of the 1.10 format is used.
      check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18), at(""));
      check(H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), at(""));
      const DriverInfo info{&error_};
      check(H5Pset_driver(fapl, checked_driver(), &info), at(""));
      file_.emplace(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
                    fmt::format("{}: cannot create it", path_));
    });
  }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// Runs `work`; what the system refused in it is thrown as its reason.
  template <class Work>
  void guarded(Work&& work) {
    try {
      work();
    } catch (const Hdf5Error&) {
      throw_refusal();
      throw;
    }
    throw_refusal();
  }

  [[nodiscard]] hid_t file() const { return *file_; }

  Id group(const char* name) const {
    return {H5Gcreate2(*file_, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, at(name)};
  }

  // A UTF-8 text attribute (variable length: h5py reads it as str).
  void text(hid_t object, const char* name, const std::string& value) const {
    const Id type = text_type();
    const Id space(H5Screate(H5S_SCALAR), H5Sclose, at(name));
    const Id attribute(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, at(name));
    const char* p = value.c_str();
    check(H5Awrite(attribute, type, static_cast<const void*>(&p)), at(name));
  }

  // A 1-D attribute of UTF-8 texts.
  void texts(hid_t object, const char* name, const std::vector<std::string>& values) const {
    const Id type = text_type();
    const hsize_t n = values.size();
    const Id space(H5Screate_simple(1, &n, nullptr), H5Sclose, at(name));
    const Id attribute(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, at(name));
    std::vector<const char*> p;
    for (const auto& v : values) p.push_back(v.c_str());
    if (!p.empty()) check(H5Awrite(attribute, type, p.data()), at(name));
  }

  // A dataset of `dims` (1-D, or 2-D with no rows), written whole from
  // `data`: float64, or int32 with `integers`.
  Id dataset(hid_t group, const std::string& name, std::vector<hsize_t> dims, const void* data,
             bool integers = false) const {
    const Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, at(name));
    Id set = create(group, name, space, H5P_DEFAULT, integers);
    hsize_t size = 1;
    for (auto d : dims) size *= d;
    const hid_t memory_type = integers ? H5T_NATIVE_INT32 : H5T_NATIVE_DOUBLE;
    if (size > 0) check(H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), at(name));
    return set;
  }

  // A 2-D float64 dataset of no rows yet, of `columns` each, extended by
  // append_row: chunked by whole rows (as many of `planned` as fit in
  // chunk_bytes) and, at a gzip `level` above 0, shuffled (each double's
  // bytes grouped by place) and compressed.
  Id rows(hid_t group, const std::string& name, hsize_t columns, hsize_t planned, int level) const {
    const std::array<hsize_t, 2> dims{0, columns}, most{H5S_UNLIMITED, columns};
    const Id space(H5Screate_simple(2, dims.data(), most.data()), H5Sclose, at(name));
    const Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, at(name));
    const std::array<hsize_t, 2> chunk{std::clamp<hsize_t>(chunk_bytes / (columns * sizeof(double)), 1, planned),
                                       std::min<hsize_t>(columns, chunk_bytes / sizeof(double))};
    check(H5Pset_chunk(dcpl, 2, chunk.data()), at(name));
    if (level > 0) {
      check(H5Pset_shuffle(dcpl), at(name));
      check(H5Pset_deflate(dcpl, static_cast<unsigned>(level)), at(name));
    }
    return create(group, name, space, dcpl, false);
  }

  // Row `row` of a dataset made by rows(), from `values`.
  void append_row(hid_t set, hsize_t row, hsize_t columns, const double* values, const char* name) const {
    const std::array<hsize_t, 2> dims{row + 1, columns}, start{row, 0}, count{1, columns};
    check(H5Dset_extent(set, dims.data()), at(name));
    const Id file_space(H5Dget_space(set), H5Sclose, at(name));
    check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), at(name));
    const Id memory_space(H5Screate_simple(2, count.data(), nullptr), H5Sclose, at(name));
    check(H5Dwrite(set, H5T_NATIVE_DOUBLE, memory_space, file_space, H5P_DEFAULT, values), at(name));
  }

  /// Closes the file, writing what HDF5 holds of it: every handle of it
  /// must be closed by then.
  void close() {
    guarded([&] { file_->close(fmt::format("{}: cannot write it to the end", path_)); });
    file_.reset();
  }

 private:
  [[nodiscard]] std::string at(std::string_view name) const {
    return name.empty() ? fmt::format("{}: cannot write it", path_) : fmt::format("{}: cannot write {}", path_, name);
  }

  void throw_refusal() const {
    if (error_ != 0) throw std::system_error(error_, std::system_category(), path_);
  }

  Id create(hid_t group, const std::string& name, hid_t space, hid_t dcpl, bool integers) const {
    const Id fill(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, at(name));
    const hid_t properties = dcpl == H5P_DEFAULT ? hid_t{fill} : dcpl;
    check(H5Pset_fill_time(properties, H5D_FILL_TIME_NEVER), at(name));
    const hid_t file_type = integers ? H5T_STD_I32LE : H5T_IEEE_F64LE;
    return {H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, properties, H5P_DEFAULT), H5Dclose,
            at(name)};
  }

  [[nodiscard]] Id text_type() const {
    Id type(H5Tcopy(H5T_C_S1), H5Tclose, at("a text"));
    check(H5Tset_size(type, H5T_VARIABLE), at("a text"));
    check(H5Tset_cset(type, H5T_CSET_UTF8), at("a text"));
    return type;
  }

  std::string path_;
  int error_ = 0;  // the checked driver's: the system's first refusal
  std::optional<Id> file_;
};

void write_history(const Writer& w, const RunResult& result) {
  const Id history = w.group("history");
  std::vector<std::string> names;
  for (const auto& b : budget_columns) names.emplace_back(b.name);
  names.insert(names.end(), result.columns.begin(), result.columns.end());
  w.texts(history, "columns", names);
  const std::size_t rows = result.history.size(), n = result.columns.size();
  std::vector<double> column(rows);
  for (const auto& b : budget_columns) {
    for (std::size_t k = 0; k < rows; ++k) column[k] = result.history[k].*b.value;
    w.dataset(history, std::string(b.name), {rows}, column.data());
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < rows; ++k) column[k] = result.extra[k * n + i];
    w.dataset(history, result.columns[i], {rows}, column.data());
  }
}

constexpr std::array<const char*, 4> quantities{"u", "v", "sigma", "eps_p"};

// A results.h5 written as the run goes: the file made in the run's staging,
// /fields' u, v, sigma and eps_p extended by each snapshot the run takes,
// the rest written at the end. HDF5 holds a few chunks of each, not the file.
class Stream final : public detail::Hdf5Results {
 public:
  Stream(const fs::path& path, int compression, std::size_t snapshots)
      : compression_(compression), planned_(std::max<hsize_t>(snapshots, 1)) {
    const Session session;
    try {
      writer_ = std::make_unique<Writer>(path);
      writer_->guarded([&] { fields_.emplace(writer_->group("fields")); });
    } catch (...) {
      writer_.reset();  // closed within the session
      throw;
    }
  }
  ~Stream() override {
    const Session session;
    sets_.clear();  // every handle closed before the file
    fields_.reset();
    writer_.reset();
  }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;

  void append(const std::array<const double*, 4>& values, std::size_t nodes) override {
    const Session session;
    writer_->guarded([&] {
      if (sets_.empty())
        for (const char* q : quantities) sets_.push_back(writer_->rows(*fields_, q, nodes, planned_, compression_));
      for (std::size_t q = 0; q < quantities.size(); ++q)
        writer_->append_row(sets_[q], written_, nodes, values[q], quantities[q]);
      ++written_;
    });
  }

  void finish(const detail::Hdf5Case& c, const RunResult& result, const std::vector<double>& t) override {
    const Session session;
    writer_->guarded([&] {
      writer_->text(writer_->file(), "case", c.toml);
      writer_->text(writer_->file(), "units", c.units);
      write_history(*writer_, result);
      write_fields(result.fields, t);
      sets_.clear();
      fields_.reset();
    });
    writer_->close();
  }

 private:
  // /fields beside the snapshots' values: their times, the rows' positions
  // and bodies (and, when no snapshot came, empty values of every row).
  void write_fields(const Fields& f, const std::vector<double>& t) {
    const Writer& w = *writer_;
    w.texts(*fields_, "columns", {"t", "x", "u", "v", "sigma", "eps_p", "body"});
    w.dataset(*fields_, "t", {t.size()}, t.data());
    w.dataset(*fields_, "x", {f.nodes()}, f.x.data());
    if (sets_.empty())
      for (const char* q : quantities) w.dataset(*fields_, q, {0, f.nodes()}, nullptr);
    std::vector<std::int32_t> body(f.body.begin(), f.body.end());
    body.resize(f.nodes());
    const Id set = w.dataset(*fields_, "body", {f.nodes()}, body.data(), true);
    w.texts(set, "names", f.body_names);
  }

  int compression_;
  hsize_t planned_, written_ = 0;
  std::unique_ptr<Writer> writer_;
  std::optional<Id> fields_;
  std::vector<Id> sets_;  // u, v, sigma, eps_p once the first snapshot came
};

std::unique_ptr<detail::Hdf5Results> create(const fs::path& path, int compression, std::size_t snapshots) {
  return std::make_unique<Stream>(path, compression, snapshots);
}

HistoryColumns read_history(const fs::path& path) {
  const Session session;
  const std::string file_name = path.string();
  auto at = [&](std::string_view what) { return fmt::format("{}: {}", file_name, what); };
  const Id file(H5Fopen(file_name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, at("cannot open it"));
  const Id history(H5Gopen2(file, "history", H5P_DEFAULT), H5Gclose, at("no /history"));
  HistoryColumns out;
  {
    const Id attribute(H5Aopen(history, "columns", H5P_DEFAULT), H5Aclose, at("no /history attribute columns"));
    const Id space(H5Aget_space(attribute), H5Sclose, at("/history's columns"));
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    if (n < 0 || H5Sget_simple_extent_ndims(space) != 1)
      throw Hdf5Error(at("/history's columns are not a list of names"));
    Id type(H5Tcopy(H5T_C_S1), H5Tclose, at("/history's columns"));
    check(H5Tset_size(type, H5T_VARIABLE), at("/history's columns"));
    check(H5Tset_cset(type, H5T_CSET_UTF8), at("/history's columns"));
    std::vector<char*> names(static_cast<std::size_t>(n), nullptr);
    check(H5Aread(attribute, type, names.data()), at("/history's columns are not a list of names"));
    for (char* name : names) out.names.emplace_back(name != nullptr ? name : "");
#if H5_VERSION_GE(1, 12, 0)
    H5Treclaim(type, space, H5P_DEFAULT, names.data());
#else
    H5Dvlen_reclaim(type, space, H5P_DEFAULT, names.data());
#endif
  }
  for (const auto& name : out.names) {
    const Id set(H5Dopen2(history, name.c_str(), H5P_DEFAULT), H5Dclose, at(fmt::format("no /history/{}", name)));
    const Id space(H5Dget_space(set), H5Sclose, at(fmt::format("/history/{}", name)));
    const hssize_t rows = H5Sget_simple_extent_npoints(space);
    if (rows < 0 || H5Sget_simple_extent_ndims(space) != 1 ||
        (!out.values.empty() && static_cast<std::size_t>(rows) != out.values.front().size()))
      throw Hdf5Error(at(fmt::format("/history/{} is not a column as long as /history/t", name)));
    auto& values = out.values.emplace_back(static_cast<std::size_t>(rows));
    if (rows > 0)
      check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            at(fmt::format("cannot read /history/{}", name)));
  }
  return out;
}

}  // namespace

}  // namespace barimpact

extern "C" __attribute__((visibility("default"))) const barimpact::detail::Hdf5Module* barimpact_hdf5_module() {
  static const barimpact::detail::Hdf5Module module{barimpact::create, barimpact::read_history};
  return &module;
}
