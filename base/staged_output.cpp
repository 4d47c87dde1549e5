// SPDX-License-Identifier: MIT
#include "base/staged_output.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "base/error.h"

namespace pastemix {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& p, const std::string& what, int err) {
  throw InputError(p.string(), 0, "", fmt::format("{}: {}", what, std::strerror(err)));
}

std::string suffix(const char* kind) { return fmt::format(".{}-{}", kind, static_cast<long>(::getpid())); }

// "<name>.partial-<pid>" or "<name>.old-<pid>" of a process that no longer exists: left by a kill -9 or a
// crash. Another live process (a parallel run into the same folder) keeps its own.
bool is_stale_sibling(const fs::path& candidate, const fs::path& final_path) {
  const std::string name = candidate.filename().string(), base = final_path.filename().string();
  for (const char* kind : {".partial-", ".old-"}) {
    const std::string prefix = base + kind;
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string pid = name.substr(prefix.size());
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) return false;
    const long p = std::strtol(pid.c_str(), nullptr, 10);
    return p > 0 && ::kill(static_cast<pid_t>(p), 0) != 0 && errno == ESRCH;
  }
  return false;
}

}  // namespace

void remove_stale_siblings(const fs::path& final_path) {
  std::error_code ec;
  const fs::path dir = final_path.has_parent_path() ? final_path.parent_path() : fs::path(".");
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (is_stale_sibling(it->path(), final_path)) {
      std::error_code rm;
      fs::remove_all(it->path(), rm);
    }
}

namespace {

void checked_rename(const fs::path& from, const fs::path& to, const fs::path& final_path) {
  const char* fault = std::getenv("PASTEMIX_FAULT_RENAME");
  if (fault && *fault && final_path.filename() == fault && to == final_path)
    fail(to, fmt::format("cannot move {} into place (PASTEMIX_FAULT_RENAME)", from.filename().string()), EIO);
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw InputError(to.string(), 0, "", fmt::format("cannot move {} into place: {}", from.string(), ec.message()));
}

}  // namespace

void replace_file_atomically(const fs::path& path, const std::string& bytes) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "", fmt::format("cannot create the folder: {}", ec.message()));
  remove_stale_siblings(path);
  fs::path temp = path;
  temp += suffix("partial");
  try {
    write_file_synced(temp, bytes);
    fs::rename(temp, path, ec);
    if (ec) throw InputError(path.string(), 0, "", fmt::format("cannot move {} into place: {}", temp.string(), ec.message()));
  } catch (...) {
    std::error_code rm;
    fs::remove(temp, rm);
    throw;
  }
  sync_path(dir);
}

void sync_path(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open to sync", errno);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // Some file systems cannot sync a folder (EINVAL); the data files themselves were synced.
  if (rc != 0 && !(err == EINVAL && fs::is_directory(path))) fail(path, "cannot sync to disk", err);
}

void write_file_synced(const fs::path& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) fail(path, "cannot create", errno);
  const bool wrote = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0 &&
                     ::fsync(::fileno(f)) == 0;
  const int err = errno;
  const bool closed = std::fclose(f) == 0;
  if (!wrote || !closed) fail(path, "cannot write", wrote ? errno : err);
}

StagedOutput::~StagedOutput() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& t : temps_) fs::remove(t, ec);
}

fs::path StagedOutput::path(const fs::path& final_path) {
  if (final_path.has_parent_path()) {
    const fs::path dir = final_path.parent_path();
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
      throw InputError(dir.string(), 0, "", "the output folder is a file, not a folder");
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
      throw InputError(dir.string(), 0, "",
                       ec ? fmt::format("cannot create the output folder: {}", ec.message())
                          : "the output folder is a file, not a folder");
  }
  remove_stale_siblings(final_path);
  auto temp = final_path;
  temp += suffix("partial");
  finals_.push_back(final_path);
  temps_.push_back(temp);
  return temp;
}

fs::path StagedOutput::write_text(const fs::path& final_path, const std::string& text) {
  // A TOML file we write is read by the next command of the chain: check that it parses before it can
  // replace a good one. A failure is our bug (exit 1), and nothing is published.
  if (final_path.extension() == ".toml") {
    try {
      (void)toml::parse(text, final_path.string());
    } catch (const toml::parse_error& e) {
      throw std::logic_error(fmt::format("{} would not be valid TOML (line {}: {}); nothing written",
                                         final_path.string(), e.source().begin.line, e.description()));
    }
  }
  const fs::path temp = path(final_path);
  write_file_synced(temp, text);
  return temp;
}

void StagedOutput::commit() {
  for (const auto& t : temps_) sync_path(t);
  // Step 1: the old set aside. Step 2: the new set in. Any failure undoes both steps in reverse.
  std::vector<fs::path> backups(finals_.size());
  std::vector<bool> moved_in(finals_.size(), false);
  auto undo = [&] {
    std::error_code ec;
    for (std::size_t k = finals_.size(); k-- > 0;) {
      if (moved_in[k]) fs::rename(finals_[k], temps_[k], ec);
      if (!backups[k].empty()) fs::rename(backups[k], finals_[k], ec);
    }
  };
  try {
    for (std::size_t k = 0; k < finals_.size(); ++k) {
      std::error_code ec;
      if (!fs::exists(finals_[k], ec)) continue;
      fs::path b = finals_[k];
      b += suffix("old");
      checked_rename(finals_[k], b, finals_[k]);
      backups[k] = b;
    }
    for (std::size_t k = 0; k < finals_.size(); ++k) {
      checked_rename(temps_[k], finals_[k], finals_[k]);
      moved_in[k] = true;
    }
  } catch (...) {
    undo();
    throw;  // the destructor removes the partials
  }
  committed_ = true;
  std::error_code ec;
  for (const auto& b : backups)
    if (!b.empty()) fs::remove_all(b, ec);
  for (const auto& f : finals_)
    if (f.has_parent_path()) sync_path(f.parent_path());
}

}  // namespace pastemix
