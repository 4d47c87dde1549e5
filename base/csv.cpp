// SPDX-License-Identifier: MIT
#include "base/csv.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "base/error.h"
#include "base/range.h"
#include "base/suggest.h"

namespace pastemix {

std::optional<double> parse_finite_double(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (text.empty()) return std::nullopt;
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

namespace {

// Splits the text into records of fields, honouring quotes (a quoted field may hold commas, doubled
// quotes and newlines). Records remember the line they start on.
struct Record {
  int line;
  std::vector<std::string> fields;
};

std::vector<Record> split_records(std::string_view text, const std::string& path) {
  std::vector<Record> records;
  Record current{1, {}};
  std::string field;
  bool in_quotes = false, field_started = false, record_has_content = false;
  int line = 1, quote_line = 0;
  auto end_field = [&] {
    current.fields.push_back(std::move(field));
    field.clear();
    field_started = false;
  };
  auto end_record = [&] {
    end_field();
    if (record_has_content) records.push_back(std::move(current));
    current = Record{line + 1, {}};
    record_has_content = false;
  };
  for (std::size_t k = 0; k < text.size(); ++k) {
    char c = text[k];
    if (in_quotes) {
      if (c == '"') {
        if (k + 1 < text.size() && text[k + 1] == '"') {
          field.push_back('"');
          ++k;
        } else {
          in_quotes = false;
        }
      } else {
        if (c == '\n') ++line;
        field.push_back(c);
      }
      continue;
    }
    if (c == '"' && !field_started) {
      in_quotes = true;
      field_started = true;
      record_has_content = true;
      quote_line = line;
    } else if (c == ',') {
      record_has_content = true;
      end_field();
    } else if (c == '\r') {
      // Tolerate CRLF line ends.
    } else if (c == '\n') {
      end_record();
      ++line;
    } else {
      field.push_back(c);
      field_started = true;
      if (c != ' ' && c != '\t') record_has_content = true;
    }
  }
  if (in_quotes) throw InputError(path, quote_line, "", "unterminated quoted field");
  if (record_has_content || !field.empty()) end_record();
  return records;
}

std::string trim(std::string s) {
  auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) throw InputError(path.string(), 0, "", "is a folder, not a CSV file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path.string());
}

CsvTable CsvTable::parse(std::string_view text, std::string display_path) {
  CsvTable table;
  table.path_ = std::move(display_path);
  // A UTF-8 byte-order mark is harmless; strip it so the first column name is clean.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  auto records = split_records(text, table.path_);
  if (records.empty()) throw InputError(table.path_, 0, "", "file is empty (expected a header row)");
  for (auto& name : records.front().fields) {
    name = trim(name);
    if (name.empty())
      throw InputError(table.path_, records.front().line, "", "empty column name in the header");
    for (const auto& seen : table.header_)
      if (seen == name)
        throw InputError(table.path_, records.front().line, fmt::format("column '{}'", shown(name)),
                         "duplicate column name in the header");
    table.header_.push_back(name);
  }
  if (records.size() == 1) throw InputError(table.path_, 0, "", "file has a header but no data rows");
  for (std::size_t r = 1; r < records.size(); ++r) {
    auto& rec = records[r];
    if (rec.fields.size() != table.header_.size())
      throw InputError(table.path_, rec.line, "",
                       fmt::format("expected {} cells (as in the header), found {}", table.header_.size(),
                                   rec.fields.size()));
    for (auto& cell : rec.fields) cell = trim(cell);
    table.rows_.push_back(Row{rec.line, std::move(rec.fields)});
  }
  return table;
}

bool CsvTable::has_column(std::string_view name) const {
  for (const auto& h : header_)
    if (h == name) return true;
  return false;
}

std::string CsvTable::missing_column_hint(std::string_view column) const {
  // A file saved with ';' (a comma-decimal locale) or tabs reads as one column holding the whole header.
  if (header_.size() == 1) {
    for (auto [sep, name] : {std::pair{';', "semicolons"}, std::pair{'\t', "tabs"}})
      if (header_.front().find(sep) != std::string::npos)
        return fmt::format(" (the header is one column '{}': the file seems to be separated by {}; pastemix "
                           "reads comma-separated files with '.' as the decimal point)",
                           shown(header_.front()), name);
  }
  return did_you_mean(column, header_);
}

void CsvTable::require_columns(const std::vector<std::string>& names) const {
  for (const auto& n : names)
    if (!has_column(n))
      throw InputError(path_, 1, fmt::format("column '{}'", n),
                       "required column is missing from the header" + missing_column_hint(n));
}

void CsvTable::require_only_columns(const std::vector<std::string>& known) const {
  for (const auto& h : header_) {
    bool ok = false;
    for (const auto& k : known) ok = ok || (k == h);
    if (!ok)
      throw InputError(path_, 1, fmt::format("column '{}'", shown(h)),
                       fmt::format("unknown column{} (expected only: {})", did_you_mean(h, known),
                                   fmt::join(known, ", ")));
  }
}

std::size_t CsvTable::index_of(std::string_view column) const {
  for (std::size_t k = 0; k < header_.size(); ++k)
    if (header_[k] == column) return k;
  throw InputError(path_, 1, fmt::format("column '{}'", column),
                   "required column is missing from the header" + missing_column_hint(column));
}

void CsvTable::fail(const Row& row, std::string_view column, const std::string& message) const {
  throw InputError(path_, row.line, fmt::format("column '{}'", column), message);
}

const std::string& CsvTable::text(const Row& row, std::string_view column) const {
  return row.cells[index_of(column)];
}

const char* range_words(Range range) {
  switch (range) {
    case Range::positive: return "a positive number";
    case Range::non_negative: return "a non-negative number";
    case Range::fraction: return "a number in [0, 1]";
    case Range::any: break;
  }
  return "a number";
}

bool in_range(double v, Range range) {
  switch (range) {
    case Range::positive: return v > 0.0;
    case Range::non_negative: return v >= 0.0;
    case Range::fraction: return v >= 0.0 && v <= 1.0;
    case Range::any: break;
  }
  return true;
}

std::optional<double> CsvTable::optional_number(const Row& row, std::string_view column, Range range) const {
  const std::string& cell = text(row, column);
  if (cell.empty()) return std::nullopt;
  auto value = parse_finite_double(cell);
  if (!value) fail(row, column, fmt::format("expected {}, got '{}'", range_words(range), shown(cell)));
  if (!in_range(*value, range)) fail(row, column, fmt::format("expected {}, got '{}'", range_words(range), shown(cell)));
  return value;
}

double CsvTable::number(const Row& row, std::string_view column, Range range) const {
  auto value = optional_number(row, column, range);
  if (!value) fail(row, column, fmt::format("expected {}, the cell is empty", range_words(range)));
  return *value;
}

long CsvTable::integer(const Row& row, std::string_view column) const {
  const std::string& cell = text(row, column);
  long value = 0;
  auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || ec != std::errc() || end != cell.data() + cell.size())
    fail(row, column, fmt::format("expected an integer, got '{}'", shown(cell)));
  return value;
}

}  // namespace pastemix
