// SPDX-License-Identifier: MIT
// A small, strict CSV reader (RFC 4180 quoting, one header row, '.' decimal point).
//
// Strict because the lab data are hand-transcribed: a ragged row, an unknown column, a non-numeric or NaN
// cell is an InputError naming file, line and column, never a silently skipped row. Numbers are parsed
// with std::from_chars (locale-independent); "nan" and "inf" are rejected.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pastemix {

// Constraints a numeric cell must satisfy; checked at parse time so the error names the cell.
enum class Range { any, positive, non_negative, fraction /* [0,1] */ };

class CsvTable {
 public:
  struct Row {
    int line = 0;  // 1-based line number in the file (the header is line 1)
    std::vector<std::string> cells;
  };

  // Parses a whole file. Throws InputError for a missing/empty file, an empty header, duplicate column
  // names, unterminated quotes, or a row whose cell count differs from the header.
  static CsvTable read(const std::filesystem::path& path);
  // Parses text as if it came from `display_path` (for tests and embedded data).
  static CsvTable parse(std::string_view text, std::string display_path);

  const std::string& path() const { return path_; }
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<Row>& rows() const { return rows_; }
  bool has_column(std::string_view name) const;
  // Throws InputError (line 1) naming the missing column.
  void require_columns(const std::vector<std::string>& names) const;
  // Every column must be one of `known`: an unexpected column is an error too (catches typos).
  void require_only_columns(const std::vector<std::string>& known) const;

  const std::string& text(const Row& row, std::string_view column) const;
  // A required number; empty, non-numeric, NaN/inf or out-of-range cells throw InputError.
  double number(const Row& row, std::string_view column, Range range = Range::any) const;
  // An optional number: an empty cell gives nullopt; anything else must parse.
  std::optional<double> optional_number(const Row& row, std::string_view column,
                                        Range range = Range::any) const;
  // An integer-valued cell (e.g. a trial or case number).
  long integer(const Row& row, std::string_view column) const;

  [[noreturn]] void fail(const Row& row, std::string_view column, const std::string& message) const;

 private:
  std::size_t index_of(std::string_view column) const;
  // A hint for a missing column: the separator the file seems to use, or the nearest column name.
  std::string missing_column_hint(std::string_view column) const;

  std::string path_;
  std::vector<std::string> header_;
  std::vector<Row> rows_;
};

// Parses a finite double from the whole of `text`; nullopt if it is not one (used by CSV and TOML code).
std::optional<double> parse_finite_double(std::string_view text);

}  // namespace pastemix
