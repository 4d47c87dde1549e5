// SPDX-License-Identifier: MIT
#include "app/study/ledger.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/csv.h"
#include "base/error.h"

namespace pastemix::app::study {
namespace {

const char* const kHeader = "key,study,task,status,qoi,wall_s,particle_steps,particles,engine,failure";

// A CSV cell, quoted when it holds a comma or a quote (RFC 4180); line breaks become spaces (one row a line).
std::string cell(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

bool is_key(const std::string& k) {
  if (k.size() != 16) return false;
  for (char c : k)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

LedgerRow row_of(const CsvTable& t, const CsvTable::Row& row) {
  LedgerRow r;
  r.line = row.line;
  r.key = t.text(row, "key");
  if (!is_key(r.key)) t.fail(row, "key", "'" + r.key + "' is not a task key (16 hex digits)");
  r.study = t.text(row, "study");
  r.task = t.text(row, "task");
  const std::string status = t.text(row, "status");
  if (status != "done" && status != "failed") t.fail(row, "status", "'" + status + "' is not done or failed");
  r.outcome.failed = status == "failed";
  r.outcome.engine = t.text(row, "engine");
  r.outcome.failure = t.text(row, "failure");
  if (r.outcome.failed) {
    if (r.outcome.failure.empty()) t.fail(row, "failure", "a failed task needs its reason");
    return r;
  }
  std::istringstream q(t.text(row, "qoi"));
  for (std::string v; q >> v;) {
    const auto d = parse_finite_double(v);
    if (!d) t.fail(row, "qoi", "'" + v + "' is not a finite number");
    r.outcome.qoi.push_back(*d);
  }
  if (r.outcome.qoi.empty()) t.fail(row, "qoi", "a finished task needs its QoI value(s)");
  r.outcome.wall_s = t.number(row, "wall_s", Range::non_negative);
  r.outcome.work = t.number(row, "particle_steps", Range::non_negative);
  const long n = t.integer(row, "particles");
  if (n < 0) t.fail(row, "particles", "must be >= 0");
  r.outcome.particles = static_cast<std::size_t>(n);
  return r;
}

bool same(const RunRecord& a, const RunRecord& b) {
  return a.failed == b.failed && a.qoi == b.qoi && a.failure == b.failure;
}

// A last line without its newline is an append cut by a kill: dropped (the file truncated to the last
// whole row) with a warning, so that the task is done again.
void drop_torn_tail(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (text.empty() || text.back() == '\n') return;
  const std::size_t keep = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  fmt::print(stderr, "warning: {}: the last line has no end (an append cut by a kill); dropped: {}\n", p.string(),
             text.substr(keep));
  std::filesystem::resize_file(p, keep);
}

}  // namespace

std::string ledger_line(const std::string& key, const std::string& study, const std::string& task,
                        const RunRecord& r) {
  const std::string qoi = r.failed ? "" : fmt::format("{:.17g}", fmt::join(r.qoi, " "));
  return fmt::format("{},{},{},{},{},{},{},{},{},{}\n", key, cell(study), cell(task), r.failed ? "failed" : "done",
                     qoi, r.failed ? "" : fmt::format("{:.6g}", r.wall_s),
                     r.failed ? "" : fmt::format("{:.17g}", r.work), r.failed ? "" : std::to_string(r.particles),
                     cell(r.engine), cell(r.failure));
}

LedgerRow parse_ledger_line(const std::string& line, const std::string& where) {
  const CsvTable t = CsvTable::parse(std::string(kHeader) + "\n" + line, where);
  if (t.rows().size() != 1) throw InputError(where, 0, "", "not one ledger row");
  return row_of(t, t.rows().front());
}

Ledger::Ledger(std::filesystem::path path) : path_(std::move(path)) {
  std::error_code ec;
  if (path_.empty() || !std::filesystem::exists(path_, ec)) return;
  drop_torn_tail(path_);
  if (std::filesystem::file_size(path_) == 0) return;
  // A ledger whose rows were all taken out (to rerun them) is its header alone: no finished task. Only a file
  // no longer than the header and a line end can be that, so a real ledger is read once.
  if (std::filesystem::file_size(path_) <= std::strlen(kHeader) + 2) {
    std::ifstream in(path_);
    std::stringstream text;
    text << in.rdbuf();
    std::string body = text.str();
    while (!body.empty() && (body.back() == '\n' || body.back() == '\r')) body.pop_back();
    if (body == kHeader) return;
  }
  const CsvTable t = CsvTable::read(path_);
  t.require_columns({"key", "study", "task", "status", "qoi", "wall_s", "particle_steps", "particles", "engine", "failure"});
  t.require_only_columns({"key", "study", "task", "status", "qoi", "wall_s", "particle_steps", "particles", "engine", "failure"});
  for (const auto& row : t.rows()) {
    LedgerRow r = row_of(t, row);
    const auto it = rows_.find(r.key);
    if (it != rows_.end()) {
      if (!same(it->second.outcome, r.outcome))
        t.fail(row, "key", fmt::format("task {} is listed twice with different outcomes (lines {} and {})", r.key,
                                       it->second.line, r.line));
      continue;
    }
    rows_.emplace(r.key, std::move(r));
  }
}

const LedgerRow* Ledger::find(const std::string& key) const {
  const auto it = rows_.find(key);
  return it == rows_.end() ? nullptr : &it->second;
}

void Ledger::append(const std::string& key, const std::string& study, const std::string& task, const RunRecord& r) {
  if (!enabled() || rows_.count(key)) return;
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path());
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) throw InputError(path_.string(), 0, "", std::string("cannot open the ledger: ") + std::strerror(errno));
  std::string text = ledger_line(key, study, task, r);
  if (::lseek(fd, 0, SEEK_END) == 0) text = std::string(kHeader) + "\n" + text;
  // One write of the whole row: a kill leaves the row or a torn last line, which the next load drops.
  const ssize_t n = ::write(fd, text.data(), text.size());
  const int err = errno;
  const bool ok = n == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) throw InputError(path_.string(), 0, "", std::string("cannot append to the ledger: ") + std::strerror(err));
  LedgerRow row = parse_ledger_line(ledger_line(key, study, task, r), path_.string());
  rows_.emplace(key, std::move(row));
}

std::size_t Ledger::other_engine(const std::string& engine) const {
  std::size_t n = 0;
  for (const auto& [k, r] : rows_) n += r.outcome.engine != engine;
  return n;
}

}  // namespace pastemix::app::study
