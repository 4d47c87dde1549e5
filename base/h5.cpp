// SPDX-License-Identifier: MIT
#include "base/h5.h"

#include <H5Cpp.h>
#include <fmt/format.h>

#include "base/error.h"

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
H5::Group ensure_groups(H5::H5File& file, const std::vector<std::string>& parts, std::size_t count) {
  H5::Group g = file.openGroup("/");
  std::string at;
  for (std::size_t k = 0; k < count; ++k) {
    at += "/" + parts[k];
    if (g.nameExists(parts[k])) g = g.openGroup(parts[k]);
    else g = g.createGroup(parts[k]);
  }
  return g;
}

template <class T>
void write_numeric(H5::H5File& file, std::string_view path, std::span<const T> data,
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

struct H5Writer::Impl {
  H5::H5File file;
};

H5Writer::H5Writer(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  H5::Exception::dontPrint();
  impl_->file = H5::H5File(path.string(), H5F_ACC_TRUNC);
}
H5Writer::~H5Writer() = default;

void H5Writer::create_group(std::string_view path) {
  auto parts = split_path(path);
  ensure_groups(impl_->file, parts, parts.size());
}
void H5Writer::write(std::string_view path, std::span<const double> data, std::vector<std::uint64_t> dims) {
  write_numeric(impl_->file, path, data, std::move(dims), H5::PredType::NATIVE_DOUBLE);
}
void H5Writer::write(std::string_view path, std::span<const float> data, std::vector<std::uint64_t> dims) {
  write_numeric(impl_->file, path, data, std::move(dims), H5::PredType::NATIVE_FLOAT);
}
void H5Writer::write(std::string_view path, std::span<const std::int64_t> data, std::vector<std::uint64_t> dims) {
  write_numeric(impl_->file, path, data, std::move(dims), H5::PredType::NATIVE_INT64);
}
void H5Writer::write(std::string_view path, std::span<const std::int32_t> data, std::vector<std::uint64_t> dims) {
  write_numeric(impl_->file, path, data, std::move(dims), H5::PredType::NATIVE_INT32);
}

void H5Writer::write_strings(std::string_view path, const std::vector<std::string>& data) {
  auto parts = split_path(path);
  H5::Group parent = ensure_groups(impl_->file, parts, parts.size() - 1);
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
  with_new_attribute(impl_->file.getId(), object, name, H5T_NATIVE_DOUBLE,
                     [&](hid_t a) { return H5Awrite(a, H5T_NATIVE_DOUBLE, &value); });
}
void H5Writer::attribute(std::string_view object, std::string_view name, std::int64_t value) {
  with_new_attribute(impl_->file.getId(), object, name, H5T_NATIVE_INT64,
                     [&](hid_t a) { return H5Awrite(a, H5T_NATIVE_INT64, &value); });
}
void H5Writer::attribute(std::string_view object, std::string_view name, std::string_view value) {
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  std::string s(value);
  const char* p = s.c_str();
  with_new_attribute(impl_->file.getId(), object, name, type, [&](hid_t a) { return H5Awrite(a, type, &p); });
  H5Tclose(type);
}
void H5Writer::flush() { impl_->file.flush(H5F_SCOPE_GLOBAL); }

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

std::vector<std::uint64_t> H5Reader::dims(std::string_view path) const {
  H5::DataSet ds = open_dataset(impl_->file, impl_->path, path);
  H5::DataSpace space = ds.getSpace();
  int rank = space.getSimpleExtentNdims();
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  space.getSimpleExtentDims(d.data());
  return {d.begin(), d.end()};
}

std::vector<double> H5Reader::read_doubles(std::string_view path) const {
  H5::DataSet ds = open_dataset(impl_->file, impl_->path, path);
  std::vector<double> out(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
  if (!out.empty()) ds.read(out.data(), H5::PredType::NATIVE_DOUBLE);
  return out;
}

std::vector<std::int64_t> H5Reader::read_ints(std::string_view path) const {
  H5::DataSet ds = open_dataset(impl_->file, impl_->path, path);
  std::vector<std::int64_t> out(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
  if (!out.empty()) ds.read(out.data(), H5::PredType::NATIVE_INT64);
  return out;
}

std::vector<std::string> H5Reader::read_strings(std::string_view path) const {
  H5::DataSet ds = open_dataset(impl_->file, impl_->path, path);
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

std::vector<std::string> H5Reader::children(std::string_view group) const {
  H5::Group g = impl_->file.openGroup(std::string(group));
  std::vector<std::string> out;
  for (hsize_t k = 0; k < g.getNumObjs(); ++k) out.push_back(g.getObjnameByIdx(k));
  return out;
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
