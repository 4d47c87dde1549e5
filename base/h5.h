// SPDX-License-Identifier: MIT
// Thin helpers over the HDF5 C++ API: write/read datasets and attributes by slash path.
//
// Paths like "/cases/3/C" create their intermediate groups. Datasets are stored row-major with the dims
// given (1-D if none). Strings are variable-length UTF-8. The analysis layer reads model output only
// through files, so the reader side is as important as the writer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pastemix {

// Every failure to write (a full disk, a quota, a file-size limit) is an InputError naming the file and the
// system's cause: exit 2, an environment problem, never an abort. The file is built in memory and reaches
// the disk in close().
class H5Writer {
 public:
  // Creates (truncates) the file.
  explicit H5Writer(const std::filesystem::path& path);
  // Opens a file image (the bytes of an HDF5 file, e.g. image() of an earlier writer) in memory, to go on
  // writing it; close() writes it to `path`. InputError (path) if the bytes are not an HDF5 file.
  H5Writer(const std::filesystem::path& path, const std::string& image);
  ~H5Writer();
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  void create_group(std::string_view path);
  void write(std::string_view path, std::span<const double> data, std::vector<std::uint64_t> dims = {});
  void write(std::string_view path, std::span<const float> data, std::vector<std::uint64_t> dims = {});
  void write(std::string_view path, std::span<const std::int64_t> data, std::vector<std::uint64_t> dims = {});
  void write(std::string_view path, std::span<const std::int32_t> data, std::vector<std::uint64_t> dims = {});
  void write_strings(std::string_view path, const std::vector<std::string>& data);
  void write_bytes(std::string_view path, std::span<const std::uint8_t> data);  // 1-D uint8 (opaque data)
  // Unlinks a dataset or group (its space is not reclaimed in the file).
  void remove(std::string_view path);
  // Attributes on an existing group or dataset ("/" is the root group).
  void attribute(std::string_view object, std::string_view name, double value);
  void attribute(std::string_view object, std::string_view name, std::int64_t value);
  void attribute(std::string_view object, std::string_view name, std::string_view value);
  void flush();
  // The file as it stands (a complete HDF5 file: what close() would write now); the writer stays open.
  std::string image();
  // Writes the file to disk (it is built in memory), syncs and closes it; throws InputError (path and
  // cause) if the data did not reach the disk. Call it before committing the file: a writer destroyed
  // without close() writes nothing.
  void close();
  // Drops the file without writing anything (a writer replaced by one opened from an image).
  void discard();

 private:
  template <class Fn>
  void guard(std::string_view what, Fn&& fn);
  void write_strings_unguarded(std::string_view path, const std::vector<std::string>& data);
  void string_attribute(std::string_view object, std::string_view name, std::string_view value);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class H5Reader {
 public:
  explicit H5Reader(const std::filesystem::path& path);  // throws InputError if it is not an HDF5 file
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  bool exists(std::string_view path) const;
  std::vector<std::uint64_t> dims(std::string_view path) const;
  std::vector<double> read_doubles(std::string_view path) const;
  std::vector<std::int64_t> read_ints(std::string_view path) const;
  std::vector<std::string> read_strings(std::string_view path) const;
  std::vector<std::uint8_t> read_bytes(std::string_view path) const;
  std::vector<std::string> children(std::string_view group) const;
  double attribute_double(std::string_view object, std::string_view name) const;
  std::int64_t attribute_int(std::string_view object, std::string_view name) const;
  std::string attribute_string(std::string_view object, std::string_view name) const;
  bool has_attribute(std::string_view object, std::string_view name) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pastemix
