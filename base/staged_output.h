// SPDX-License-Identifier: MIT
// StagedOutput: write every output file under a temporary name, then publish them together.
//
// "Nothing half-written": a command first reads and checks all of its inputs, then writes its outputs
// through a StagedOutput. Files are written to "<name>.partial-<pid>" beside their final place and renamed
// into place only by commit(); if anything throws before that, the destructor removes the partial files,
// so an earlier good result is never replaced by a broken one.
//
//   StagedOutput out;
//   write_toml(out.path(dir / "parameters.toml"));
//   H5Writer h5(out.path(dir / "lab.h5"));  ...
//   out.commit();
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pastemix {

class StagedOutput {
 public:
  StagedOutput() = default;
  StagedOutput(const StagedOutput&) = delete;
  StagedOutput& operator=(const StagedOutput&) = delete;
  ~StagedOutput();

  // Registers `final_path` and returns the temporary path to write it to. Creates the parent folder.
  std::filesystem::path path(const std::filesystem::path& final_path);
  // Writes a whole text file.
  void write_text(const std::filesystem::path& final_path, const std::string& text);
  // Renames every staged file into place. After this the destructor does nothing.
  void commit();
  const std::vector<std::filesystem::path>& final_paths() const { return finals_; }

 private:
  std::vector<std::filesystem::path> finals_, temps_;
  bool committed_ = false;
};

}  // namespace pastemix
