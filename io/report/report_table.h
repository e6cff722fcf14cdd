// A results table written as Markdown, CSV and JSON from one definition, so every evaluation app
// reports the same numbers in the three formats.
//
//   ReportTable table({"detector", "region", "M_score(5) %", "ResM_5"});
//   table.SetPrecision("M_score(5) %", 1);
//   table.AddRow({"comic", "boundary", 40.9, int64_t{27}});
//   io::WriteFileAtomically("scores.md", table.ToMarkdown());
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

namespace comic::io {

class ReportTable {
 public:
  // A cell: text, an integer, a real number, or empty (written as "" / "–" / null).
  using Cell = std::variant<std::monostate, std::string, int64_t, double>;

  explicit ReportTable(std::vector<std::string> columns);

  // Digits after the decimal point for real numbers in `column` (default 3). Throws
  // comic::Error(kInvalidArgument) for an unknown column.
  void SetPrecision(const std::string& column, int digits);
  // Adds a row; it must have one cell per column (comic::Error otherwise). Non-finite reals are
  // written as "nan"/"inf" in Markdown and CSV and as null in JSON.
  void AddRow(std::vector<Cell> row);

  const std::vector<std::string>& columns() const { return columns_; }
  size_t NumRows() const { return rows_.size(); }
  const Cell& At(size_t row, size_t column) const { return rows_.at(row).at(column); }
  // A cell as Markdown and CSV write it ("" for an empty one).
  std::string CellText(size_t row, size_t column) const {
    return FormatCell(rows_.at(row).at(column), column);
  }
  // Whether every cell of `column` is a number or empty (right-aligned in Markdown).
  bool IsNumericColumn(size_t column) const;

  // GitHub-flavoured Markdown: a header row, numbers right-aligned.
  std::string ToMarkdown() const;
  // RFC 4180 CSV with a header line; fields quoted where needed.
  std::string ToCsv() const;
  // An array of objects, one per row, keyed by column name; numbers as JSON numbers (full
  // precision, not rounded).
  nlohmann::json ToJson() const;

 private:
  std::string FormatCell(const Cell& cell, size_t column) const;

  std::vector<std::string> columns_;
  std::vector<int> precision_;
  std::vector<std::vector<Cell>> rows_;
};

}  // namespace comic::io
