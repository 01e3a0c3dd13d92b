#include "results_h5_module.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace barimpact {

namespace fs = std::filesystem;

namespace {

// Field chunks of about this many bytes: as many whole snapshots as fit,
// so that reading one is one chunk; a larger snapshot in pieces of it.
constexpr hsize_t chunk_bytes = 256 * 1024;
// The in-memory file grows by this much at a time.
constexpr std::size_t memory_increment = 1024 * 1024;

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

// Bob Jenkins' lookup3 hash (hashlittle), which HDF5 checksums its metadata with.
std::uint32_t lookup3(const unsigned char* k, std::size_t length) {
  const auto rot = [](std::uint32_t x, int r) { return (x << r) | (x >> (32 - r)); };
  const auto word = [](const unsigned char* p) {
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24;
  };
  std::uint32_t a = 0xdeadbeef + static_cast<std::uint32_t>(length), b = a, c = a;
  for (; length > 12; length -= 12, k += 12) {
    a += word(k), b += word(k + 4), c += word(k + 8);
    a -= c, a ^= rot(c, 4), c += b, b -= a, b ^= rot(a, 6), a += c, c -= b, c ^= rot(b, 8), b += a;
    a -= c, a ^= rot(c, 16), c += b, b -= a, b ^= rot(a, 19), a += c, c -= b, c ^= rot(b, 4), b += a;
  }
  if (length == 0) return c;
  std::array<unsigned char, 12> tail{};  // the last bytes, zero-padded: as lookup3's switch adds them
  std::copy(k, k + length, tail.begin());
  a += word(tail.data()), b += word(tail.data() + 4), c += word(tail.data() + 8);
  c ^= b, c -= rot(b, 14), a ^= c, a -= rot(c, 11), b ^= a, b -= rot(a, 25), c ^= b, c -= rot(b, 16);
  a ^= c, a -= rot(c, 4), b ^= a, b -= rot(a, 14), c ^= b, c -= rot(b, 24);
  return c;
}

// H5Fget_file_image clears the superblock's status flags in the image it
// returns without updating the superblock's checksum (HDF5 1.10: version 2
// and 3 superblocks, which the 1.8 format writes), so that no library would
// open the file: the checksum is computed again over the fields before it
// (file format specification, "Superblock"; the same value where HDF5 is fixed).
void seal_superblock(std::vector<char>& image) {
  constexpr std::size_t fixed = 12;  // signature, version, sizes of offsets and lengths, flags
  if (image.size() < fixed || (image[8] != 2 && image[8] != 3)) return;
  const std::size_t at = fixed + 4 * static_cast<std::size_t>(static_cast<unsigned char>(image[9]));
  if (image.size() < at + 4) return;
  const std::uint32_t sum = lookup3(reinterpret_cast<const unsigned char*>(image.data()), at);
  for (std::size_t i = 0; i < 4; ++i) image[at + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
}

// The file is made in memory (HDF5's core driver, nothing on disk) and
// written out by the caller as one image through the checked writer: HDF5
// never holds a file of the run directory open, so a full disk is one
// refusal with the system's reason, and no handle outlives the staging
// directory. It costs the compressed file's size in memory, twice at the end.
class Writer {
 public:
  explicit Writer(const fs::path& path) : path_(path.string()), fapl_(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, at("")) {
    // The 1.8 file format (compact groups), which every HDF5 from 1.8 on
    // reads (h5py's included): nothing of the 1.10 format is used.
    check(H5Pset_libver_bounds(fapl_, H5F_LIBVER_V18, H5F_LIBVER_V18), at(""));
    check(H5Pset_fapl_core(fapl_, memory_increment, false), at(""));
    file_ = std::make_unique<Id>(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl_), H5Fclose,
                                 fmt::format("{}: cannot create it", path_));
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

  // A dataset of `dims` (1-D or 2-D, row-major `data`): float64, or int32
  // with `integers`. 2-D ones are chunked by whole rows and, at a gzip
  // `level` above 0, shuffled (each double's bytes grouped by place) and
  // compressed.
  Id dataset(hid_t group, const std::string& name, std::vector<hsize_t> dims, const void* data, int level = 0,
             bool integers = false) const {
    Id set = create(group, name, dims, level, integers);
    hsize_t size = 1;
    for (auto d : dims) size *= d;
    const hid_t memory_type = integers ? H5T_NATIVE_INT32 : H5T_NATIVE_DOUBLE;
    if (size > 0) check(H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), at(name));
    return set;
  }

  // The same 2-D float64 dataset written a chunk's rows at a time, each
  // filled by `rows(first, count, out)`: whole chunks, in order, as one
  // write of all of it lays them out.
  void dataset_by_rows(hid_t group, const std::string& name, std::array<hsize_t, 2> dims, int level,
                       const std::function<void(std::size_t, std::size_t, double*)>& rows) const {
    const Id set = create(group, name, {dims[0], dims[1]}, level, false);
    if (dims[0] == 0 || dims[1] == 0) return;
    const hsize_t block = chunk_rows(dims[1], dims[0]);
    std::vector<double> buffer(block * dims[1]);
    const Id file_space(H5Dget_space(set), H5Sclose, at(name));
    for (hsize_t first = 0; first < dims[0]; first += block) {
      const std::array<hsize_t, 2> start{first, 0}, count{std::min(block, dims[0] - first), dims[1]};
      rows(first, count[0], buffer.data());
      check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), at(name));
      const Id memory_space(H5Screate_simple(2, count.data(), nullptr), H5Sclose, at(name));
      check(H5Dwrite(set, H5T_NATIVE_DOUBLE, memory_space, file_space, H5P_DEFAULT, buffer.data()), at(name));
    }
  }

  /// The whole file's bytes, then the file closed (in memory: nothing to refuse but memory).
  std::vector<char> image() {
    const std::string what = fmt::format("{}: cannot write it to the end", path_);
    check(H5Fflush(*file_, H5F_SCOPE_GLOBAL), what);
    const ssize_t size = H5Fget_file_image(*file_, nullptr, 0);
    if (size < 0) check(-1, what);
    std::vector<char> bytes(static_cast<std::size_t>(size));
    if (H5Fget_file_image(*file_, bytes.data(), bytes.size()) != size) check(-1, what);
    file_->close(what);
    seal_superblock(bytes);
    return bytes;
  }

 private:
  [[nodiscard]] std::string at(std::string_view name) const {
    return name.empty() ? fmt::format("{}: cannot write it", path_) : fmt::format("{}: cannot write {}", path_, name);
  }
  // Whole rows of `columns` doubles in a chunk of about chunk_bytes (at least one, at most `rows`).
  static hsize_t chunk_rows(hsize_t columns, hsize_t rows) {
    return std::clamp<hsize_t>(chunk_bytes / (columns * sizeof(double)), 1, rows);
  }

  Id create(hid_t group, const std::string& name, std::vector<hsize_t> dims, int level, bool integers) const {
    const Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, at(name));
    const Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, at(name));
    check(H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER), at(name));
    if (dims.size() == 2 && dims[0] > 0 && dims[1] > 0) {
      const std::array<hsize_t, 2> chunk{chunk_rows(dims[1], dims[0]),
                                         std::min<hsize_t>(dims[1], chunk_bytes / sizeof(double))};
      check(H5Pset_chunk(dcpl, 2, chunk.data()), at(name));
      if (level > 0) {
        check(H5Pset_shuffle(dcpl), at(name));
        check(H5Pset_deflate(dcpl, static_cast<unsigned>(level)), at(name));
      }
    }
    const hid_t file_type = integers ? H5T_STD_I32LE : H5T_IEEE_F64LE;
    return {H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose, at(name)};
  }

  [[nodiscard]] Id text_type() const {
    Id type(H5Tcopy(H5T_C_S1), H5Tclose, at("a text"));
    check(H5Tset_size(type, H5T_VARIABLE), at("a text"));
    check(H5Tset_cset(type, H5T_CSET_UTF8), at("a text"));
    return type;
  }

  std::string path_;
  Id fapl_;
  std::unique_ptr<Id> file_;
};

}  // namespace

namespace {

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

void write_fields(const Writer& w, int compression, const Fields& f, const StreamedSnapshots* streamed) {
  const Id fields = w.group("fields");
  w.texts(fields, "columns", {"t", "x", "u", "v", "sigma", "eps_p", "body"});
  const std::vector<double>& t = streamed != nullptr ? *streamed->t : f.t;
  w.dataset(fields, "t", {t.size()}, t.data());
  w.dataset(fields, "x", {f.nodes()}, f.x.data());
  const std::array<const char*, 4> names{"u", "v", "sigma", "eps_p"};
  const std::array<const std::vector<double>*, 4> held{&f.u, &f.v, &f.sigma, &f.eps_p};
  for (int q = 0; q < 4; ++q)
    if (streamed == nullptr)
      w.dataset(fields, names[q], {f.count(), f.nodes()}, held[q]->data(), compression);
    else
      w.dataset_by_rows(fields, names[q], {t.size(), f.nodes()}, compression,
                        [&](std::size_t first, std::size_t count, double* out) { streamed->read(q, first, count, out); });
  std::vector<std::int32_t> body(f.body.begin(), f.body.end());
  body.resize(f.nodes());
  const Id set = w.dataset(fields, "body", {f.nodes()}, body.data(), 0, true);
  w.texts(set, "names", f.body_names);
}

std::vector<char> image(const fs::path& path, const detail::Hdf5Case& c, const RunResult& result,
                        const StreamedSnapshots* streamed) {
  const Session session;
  Writer w(path);
  w.text(w.file(), "case", c.toml);
  w.text(w.file(), "units", c.units);
  write_history(w, result);
  write_fields(w, c.compression, result.fields, streamed);
  return w.image();
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
  static const barimpact::detail::Hdf5Module module{barimpact::image, barimpact::read_history};
  return &module;
}
