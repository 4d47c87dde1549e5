// SPDX-License-Identifier: MIT
#include "base/h5.h"

#include <H5Cpp.h>
#include <fmt/format.h>

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <optional>

#include "base/error.h"
#include "base/staged_output.h"

namespace pastemix {

namespace {

std::vector<std::string> split_path(std::string_view path) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : path) {
    if (c == '/') {
      if (!cur.empty()) parts.push_back(cur);
      cur.clear();
    } else {
      cur.push_back(c);
    }
  }
  if (!cur.empty()) parts.push_back(cur);
  return parts;
}

// Creates every missing group along `parts[0..count)` and returns the last one.
H5::Group ensure_groups(const H5::Group& root, const std::vector<std::string>& parts, std::size_t count) {
  H5::Group g = root;
  std::string at;
  for (std::size_t k = 0; k < count; ++k) {
    at += "/" + parts[k];
    if (g.nameExists(parts[k])) g = g.openGroup(parts[k]);
    else g = g.createGroup(parts[k]);
  }
  return g;
}

template <class T>
void write_numeric(const H5::Group& file, std::string_view path, std::span<const T> data,
                   std::vector<std::uint64_t> dims, const H5::PredType& type) {
  auto parts = split_path(path);
  if (parts.empty()) throw std::invalid_argument("empty HDF5 dataset path");
  H5::Group parent = ensure_groups(file, parts, parts.size() - 1);
  if (dims.empty()) dims.push_back(data.size());
  std::uint64_t count = 1;
  for (auto d : dims) count *= d;
  if (count != data.size())
    throw std::invalid_argument(fmt::format("HDF5 dataset {}: dims hold {} values, data has {}", path, count,
                                            data.size()));
  std::vector<hsize_t> hdims(dims.begin(), dims.end());
  H5::DataSpace space(static_cast<int>(hdims.size()), hdims.data());
  H5::DataSet ds = parent.createDataSet(parts.back(), type, space);
  if (!data.empty()) ds.write(data.data(), type);
}

// Attributes go through the C API: it addresses any object by path, group or dataset alike.
template <class Fn>
void with_new_attribute(hid_t file, std::string_view object, std::string_view name, hid_t type, Fn&& write) {
  std::string obj = object.empty() ? "/" : std::string(object);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate_by_name(file, obj.c_str(), std::string(name).c_str(), type, space, H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT);
  H5Sclose(space);
  if (attr < 0) throw std::runtime_error(fmt::format("HDF5: cannot create attribute '{}' on '{}'", name, obj));
  herr_t status = write(attr);
  H5Aclose(attr);
  if (status < 0) throw std::runtime_error(fmt::format("HDF5: cannot write attribute '{}' on '{}'", name, obj));
}

}  // namespace

// The file is built in memory (HDF5's core driver, no backing store) and written to disk by close() in one
// checked write + fsync. HDF5 itself never meets a full disk: a failed H5Fclose leaves the file in HDF5's
// registry, and the library then crashes when it closes it again at exit (HDF5 1.10). The file id is held
// through the C API and closed exactly once.
constexpr std::size_t kCoreIncrement = 4u << 20;  // bytes the in-memory file grows by

struct H5Writer::Impl {
  hid_t file = H5I_INVALID_HID;
  std::optional<H5::Group> root;  // "/", the parent of every path
  std::string path;
  bool open = false;
  int uncaught_at_open = 0;  // std::uncaught_exceptions() when the writer was made
  ~Impl() { close_once(); }
  // Closes the root group and the file once; true if HDF5 reported no error.
  bool close_once() {
    root.reset();
    if (file == H5I_INVALID_HID) return true;
    const herr_t rc = H5Fclose(file);
    file = H5I_INVALID_HID;
    return rc >= 0;
  }
};

// Every HDF5 call of the writer goes through here: the C++ API throws H5::Exception, which is not a
// std::exception, so an uncaught one (a full disk, a quota, a file-size limit) used to abort the command
// (exit 134). It becomes an InputError naming the file and the system's cause (exit 2: the environment).
template <class Fn>
void H5Writer::guard(std::string_view what, Fn&& fn) {
  if (!impl_->open) throw std::logic_error(fmt::format("HDF5 writer of {} used after close()", impl_->path));
  errno = 0;
  try {
    fn();
  } catch (const H5::Exception& e) {
    const int err = errno;
    throw InputError(impl_->path, 0, "",
                     fmt::format("cannot write ({}: {}{})", what, e.getDetailMsg(),
                                 err ? fmt::format("; {}", std::strerror(err)) : std::string()));
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    const int err = errno;
    throw InputError(impl_->path, 0, "",
                     fmt::format("cannot write ({}: {}{})", what, e.what(),
                                 err ? fmt::format("; {}", std::strerror(err)) : std::string()));
  }
}

H5Writer::H5Writer(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  H5::Exception::dontPrint();
  impl_->path = path.string();
  impl_->open = true;
  impl_->uncaught_at_open = std::uncaught_exceptions();
  guard("create", [&] {
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_core(fapl, kCoreIncrement, /*backing_store=*/0);
    impl_->file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    if (impl_->file < 0) throw std::runtime_error("H5Fcreate failed");
    const hid_t g = H5Gopen2(impl_->file, "/", H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("cannot open the root group");
    impl_->root.emplace(g);  // the Group takes its own reference
    H5Gclose(g);
  });
}
H5Writer::H5Writer(const std::filesystem::path& path, const std::string& image) : impl_(std::make_unique<Impl>()) {
  H5::Exception::dontPrint();
  impl_->path = path.string();
  impl_->open = true;
  impl_->uncaught_at_open = std::uncaught_exceptions();
  guard("open an image", [&] {
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_core(fapl, kCoreIncrement, /*backing_store=*/0);
    // The library copies the image (no callbacks set): the caller's string may go.
    H5Pset_file_image(fapl, const_cast<char*>(image.data()), image.size());
    // HDF5 names the in-memory file: under `path` it would refuse to open when a file of that name is on
    // disk, and share the file of another writer open under the same name. A name that cannot exist on
    // disk, one per image; `path` is where close() writes it.
    static std::atomic<long> images{0};
    const std::string name = fmt::format("/dev/null/pastemix-image-{}-{}", static_cast<long>(::getpid()), images++);
    impl_->file = H5Fopen(name.c_str(), H5F_ACC_RDWR, fapl);
    H5Pclose(fapl);
    if (impl_->file < 0) throw std::runtime_error("not an HDF5 file image");
    const hid_t g = H5Gopen2(impl_->file, "/", H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("cannot open the root group");
    impl_->root.emplace(g);
    H5Gclose(g);
  });
}

// Destroyed on the way out of an error (stack unwinding): nothing is written, the StagedOutput removes the
// name. Destroyed normally without close(): written as close() would, but a failure can only be printed
// (callers that publish the file call close() so that a failure stops the command).
H5Writer::~H5Writer() {
  if (impl_->open && std::uncaught_exceptions() <= impl_->uncaught_at_open) {
    try {
      close();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
    }
  }
  try {
    impl_->close_once();
  } catch (...) {
  }
}

std::string H5Writer::image() {
  std::string out;
  guard("image", [&] {
    if (H5Fflush(impl_->file, H5F_SCOPE_GLOBAL) < 0) throw std::runtime_error("H5Fflush failed");
    const ssize_t size = H5Fget_file_image(impl_->file, nullptr, 0);
    if (size < 0) throw std::runtime_error("H5Fget_file_image failed");
    out.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(impl_->file, out.data(), out.size()) != size)
      throw std::runtime_error("H5Fget_file_image failed");
  });
  return out;
}

void H5Writer::close() {
  std::string image = this->image();
  guard("close", [&] {
    impl_->open = false;
    if (!impl_->close_once()) throw std::runtime_error("H5Fclose failed");
  });
  write_file_synced(impl_->path, image);  // InputError (path, the system's cause) on a full disk
}

void H5Writer::discard() {
  impl_->open = false;
  impl_->close_once();
}

void H5Writer::create_group(std::string_view path) {
  auto parts = split_path(path);
  guard(path, [&] { ensure_groups(*impl_->root, parts, parts.size()); });
}
void H5Writer::write(std::string_view path, std::span<const double> data, std::vector<std::uint64_t> dims) {
  guard(path, [&] { write_numeric(*impl_->root, path, data, std::move(dims), H5::PredType::NATIVE_DOUBLE); });
}
void H5Writer::write(std::string_view path, std::span<const float> data, std::vector<std::uint64_t> dims) {
  guard(path, [&] { write_numeric(*impl_->root, path, data, std::move(dims), H5::PredType::NATIVE_FLOAT); });
}
void H5Writer::write(std::string_view path, std::span<const std::int64_t> data, std::vector<std::uint64_t> dims) {
  guard(path, [&] { write_numeric(*impl_->root, path, data, std::move(dims), H5::PredType::NATIVE_INT64); });
}
void H5Writer::write(std::string_view path, std::span<const std::int32_t> data, std::vector<std::uint64_t> dims) {
  guard(path, [&] { write_numeric(*impl_->root, path, data, std::move(dims), H5::PredType::NATIVE_INT32); });
}

void H5Writer::write_bytes(std::string_view path, std::span<const std::uint8_t> data) {
  guard(path, [&] { write_numeric(*impl_->root, path, data, {}, H5::PredType::NATIVE_UINT8); });
}
void H5Writer::remove(std::string_view path) {
  guard(path, [&] {
    if (H5Ldelete(impl_->file, std::string(path).c_str(), H5P_DEFAULT) < 0)
      throw std::runtime_error(fmt::format("cannot unlink '{}'", path));
  });
}

void H5Writer::write_strings(std::string_view path, const std::vector<std::string>& data) {
  guard(path, [&] { write_strings_unguarded(path, data); });
}

void H5Writer::write_strings_unguarded(std::string_view path, const std::vector<std::string>& data) {
  auto parts = split_path(path);
  H5::Group parent = ensure_groups(*impl_->root, parts, parts.size() - 1);
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  hsize_t n = data.size();
  H5::DataSpace space(1, &n);
  H5::DataSet ds = parent.createDataSet(parts.back(), type, space);
  std::vector<const char*> ptrs;
  for (const auto& s : data) ptrs.push_back(s.c_str());
  if (!ptrs.empty()) ds.write(ptrs.data(), type);
}

void H5Writer::attribute(std::string_view object, std::string_view name, double value) {
  guard(name, [&] {
    with_new_attribute(impl_->file, object, name, H5T_NATIVE_DOUBLE,
                       [&](hid_t a) { return H5Awrite(a, H5T_NATIVE_DOUBLE, &value); });
  });
}
void H5Writer::attribute(std::string_view object, std::string_view name, std::int64_t value) {
  guard(name, [&] {
    with_new_attribute(impl_->file, object, name, H5T_NATIVE_INT64,
                       [&](hid_t a) { return H5Awrite(a, H5T_NATIVE_INT64, &value); });
  });
}
void H5Writer::attribute(std::string_view object, std::string_view name, std::string_view value) {
  guard(name, [&] { string_attribute(object, name, value); });
}
void H5Writer::string_attribute(std::string_view object, std::string_view name, std::string_view value) {
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  std::string s(value);
  const char* p = s.c_str();
  with_new_attribute(impl_->file, object, name, type, [&](hid_t a) { return H5Awrite(a, type, &p); });
  H5Tclose(type);
}
void H5Writer::flush() {
  // In memory until close(); kept so callers can mark a consistent point.
  guard("flush", [&] {
    if (H5Fflush(impl_->file, H5F_SCOPE_GLOBAL) < 0) throw std::runtime_error("H5Fflush failed");
  });
}

struct H5Reader::Impl {
  H5::H5File file;
  std::string path;
};

H5Reader::H5Reader(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  H5::Exception::dontPrint();
  impl_->path = path.string();
  try {
    impl_->file = H5::H5File(path.string(), H5F_ACC_RDONLY);
  } catch (const H5::Exception&) {
    throw InputError(path.string(), 0, "", "cannot open as an HDF5 file");
  }
}
H5Reader::~H5Reader() = default;

bool H5Reader::exists(std::string_view path) const {
  auto parts = split_path(path);
  std::string at;
  for (const auto& p : parts) {
    at += "/" + p;
    if (H5Lexists(impl_->file.getId(), at.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

static H5::DataSet open_dataset(const H5::H5File& file, const std::string& file_path, std::string_view path) {
  try {
    return file.openDataSet(std::string(path));
  } catch (const H5::Exception&) {
    throw InputError(file_path, 0, fmt::format("dataset '{}'", path), "missing from the file");
  }
}

static std::vector<std::uint64_t> dims_raw(const H5::H5File& file_, const std::string& path_, std::string_view path) {
  H5::DataSet ds = open_dataset(file_, path_, path);
  H5::DataSpace space = ds.getSpace();
  int rank = space.getSimpleExtentNdims();
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  space.getSimpleExtentDims(d.data());
  return {d.begin(), d.end()};
}

std::vector<std::uint64_t> H5Reader::dims(std::string_view path) const {
  try {
    return dims_raw(impl_->file, impl_->path, path);
  } catch (const H5::Exception& e) {
    // A dataset of another type or shape than expected (a file from another tool): an input error, not an abort.
    throw InputError(impl_->path, 0, fmt::format("dataset '{}'", path), fmt::format("cannot read: {}", e.getDetailMsg()));
  }
}

static std::vector<double> read_doubles_raw(const H5::H5File& file_, const std::string& path_, std::string_view path) {
  H5::DataSet ds = open_dataset(file_, path_, path);
  std::vector<double> out(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
  if (!out.empty()) ds.read(out.data(), H5::PredType::NATIVE_DOUBLE);
  return out;
}

std::vector<double> H5Reader::read_doubles(std::string_view path) const {
  try {
    return read_doubles_raw(impl_->file, impl_->path, path);
  } catch (const H5::Exception& e) {
    // A dataset of another type or shape than expected (a file from another tool): an input error, not an abort.
    throw InputError(impl_->path, 0, fmt::format("dataset '{}'", path), fmt::format("cannot read: {}", e.getDetailMsg()));
  }
}

static std::vector<std::int64_t> read_ints_raw(const H5::H5File& file_, const std::string& path_, std::string_view path) {
  H5::DataSet ds = open_dataset(file_, path_, path);
  std::vector<std::int64_t> out(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
  if (!out.empty()) ds.read(out.data(), H5::PredType::NATIVE_INT64);
  return out;
}

std::vector<std::int64_t> H5Reader::read_ints(std::string_view path) const {
  try {
    return read_ints_raw(impl_->file, impl_->path, path);
  } catch (const H5::Exception& e) {
    // A dataset of another type or shape than expected (a file from another tool): an input error, not an abort.
    throw InputError(impl_->path, 0, fmt::format("dataset '{}'", path), fmt::format("cannot read: {}", e.getDetailMsg()));
  }
}

std::vector<std::uint8_t> H5Reader::read_bytes(std::string_view path) const {
  try {
    H5::DataSet ds = open_dataset(impl_->file, impl_->path, path);
    std::vector<std::uint8_t> out(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
    if (!out.empty()) ds.read(out.data(), H5::PredType::NATIVE_UINT8);
    return out;
  } catch (const H5::Exception& e) {
    throw InputError(impl_->path, 0, fmt::format("dataset '{}'", path), fmt::format("cannot read: {}", e.getDetailMsg()));
  }
}

static std::vector<std::string> read_strings_raw(const H5::H5File& file_, const std::string& path_, std::string_view path) {
  H5::DataSet ds = open_dataset(file_, path_, path);
  auto n = static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints());
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  std::vector<char*> ptrs(n, nullptr);
  if (n) ds.read(ptrs.data(), type);
  std::vector<std::string> out;
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  if (n) {
    H5::DataSpace space = ds.getSpace();
    H5Dvlen_reclaim(type.getId(), space.getId(), H5P_DEFAULT, ptrs.data());
  }
  return out;
}

std::vector<std::string> H5Reader::read_strings(std::string_view path) const {
  try {
    return read_strings_raw(impl_->file, impl_->path, path);
  } catch (const H5::Exception& e) {
    // A dataset of another type or shape than expected (a file from another tool): an input error, not an abort.
    throw InputError(impl_->path, 0, fmt::format("dataset '{}'", path), fmt::format("cannot read: {}", e.getDetailMsg()));
  }
}

static std::vector<std::string> children_raw(const H5::H5File& file_, const std::string&, std::string_view group) {
  H5::Group g = file_.openGroup(std::string(group));
  std::vector<std::string> out;
  for (hsize_t k = 0; k < g.getNumObjs(); ++k) out.push_back(g.getObjnameByIdx(k));
  return out;
}

std::vector<std::string> H5Reader::children(std::string_view group) const {
  try {
    return children_raw(impl_->file, impl_->path, group);
  } catch (const H5::Exception& e) {
    // A dataset of another type or shape than expected (a file from another tool): an input error, not an abort.
    throw InputError(impl_->path, 0, fmt::format("group '{}'", group), fmt::format("cannot read: {}", e.getDetailMsg()));
  }
}


bool H5Reader::has_attribute(std::string_view object, std::string_view name) const {
  std::string p = object.empty() ? "/" : std::string(object);
  return H5Aexists_by_name(impl_->file.getId(), p.c_str(), std::string(name).c_str(), H5P_DEFAULT) > 0;
}

// Opens an attribute by object path; the caller closes it. Missing -> InputError naming the file.
static hid_t open_attribute(const std::string& file_path, hid_t file, std::string_view object, std::string_view name) {
  std::string obj = object.empty() ? "/" : std::string(object);
  hid_t a = -1;
  if (H5Aexists_by_name(file, obj.c_str(), std::string(name).c_str(), H5P_DEFAULT) > 0)
    a = H5Aopen_by_name(file, obj.c_str(), std::string(name).c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0)
    throw InputError(file_path, 0, fmt::format("attribute '{}' of '{}'", name, obj), "missing from the file");
  return a;
}

double H5Reader::attribute_double(std::string_view object, std::string_view name) const {
  hid_t a = open_attribute(impl_->path, impl_->file.getId(), object, name);
  double v = 0;
  H5Aread(a, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(a);
  return v;
}
std::int64_t H5Reader::attribute_int(std::string_view object, std::string_view name) const {
  hid_t a = open_attribute(impl_->path, impl_->file.getId(), object, name);
  std::int64_t v = 0;
  H5Aread(a, H5T_NATIVE_INT64, &v);
  H5Aclose(a);
  return v;
}
std::string H5Reader::attribute_string(std::string_view object, std::string_view name) const {
  hid_t a = open_attribute(impl_->path, impl_->file.getId(), object, name);
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  char* p = nullptr;
  H5Aread(a, type, &p);
  std::string out = p ? p : "";
  H5free_memory(p);
  H5Tclose(type);
  H5Aclose(a);
  return out;
}

}  // namespace pastemix
