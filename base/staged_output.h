// SPDX-License-Identifier: MIT
// StagedOutput: write every output file under a temporary name, then publish them together.
//
// "Nothing half-written": a command first reads and checks all of its inputs, then writes its outputs
// through a StagedOutput. Files are written to "<name>.partial-<pid>" beside their final place and moved
// into place only by commit(); if anything throws before that, the destructor removes the partial files,
// so an earlier good result is never replaced by a broken one.
//
// commit() is all-or-nothing: every staged file is synced to disk, every old file is moved aside to
// "<name>.old-<pid>", then the new set is moved in. If any move fails, the new files are taken out again
// and the old ones put back, and the error (path and cause) is thrown: the folder holds the complete old
// set or the complete new one. Partials and old copies left by a process that died (kill -9, power loss)
// are removed the next time a StagedOutput stages the same file.
//
//   StagedOutput out;
//   write_toml(out.path(dir / "parameters.toml"));
//   H5Writer h5(out.path(dir / "lab.h5"));  ...  h5.close();
//   out.commit();
//
// Failures (a folder that cannot be made, a full disk, a rename refused) are InputErrors naming the path and
// the system's cause: exit 2, a problem of the environment. For tests, PASTEMIX_FAULT_RENAME=NAME makes the
// move of the staged file whose final name is NAME fail, as a rename refused by the file system would.
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
  // Writes a whole text file (checked, synced; a .toml file must parse as TOML) and returns its temporary path.
  std::filesystem::path write_text(const std::filesystem::path& final_path, const std::string& text);
  // Publishes every staged file, all or nothing (see above). After this the destructor does nothing.
  void commit();
  const std::vector<std::filesystem::path>& final_paths() const { return finals_; }

 private:
  std::vector<std::filesystem::path> finals_, temps_;
  bool committed_ = false;
};

// Writes `text` to `path`, flushes and fsyncs it; InputError (path, cause) on any failure.
void write_file_synced(const std::filesystem::path& path, const std::string& text);
// Replaces one file atomically (a checkpoint): `bytes` to "<path>.partial-<pid>", fsync, rename over
// `path`, fsync of the folder. A kill at any point leaves the old file or the new one under `path`, never
// a mix; stale partials of dead processes are removed first. InputError (path, cause) on any failure.
void replace_file_atomically(const std::filesystem::path& path, const std::string& bytes);
// Removes "<path>.partial-<pid>" and "<path>.old-<pid>" of processes that no longer run (a kill -9).
void remove_stale_siblings(const std::filesystem::path& path);
// fsyncs an existing file (or folder); InputError (path, cause) on failure.
void sync_path(const std::filesystem::path& path);

}  // namespace pastemix
