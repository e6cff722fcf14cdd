#include "io/report/report_table.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/core/error.h"

namespace comic::io {

ReportTable::ReportTable(std::vector<std::string> columns)
    : columns_(std::move(columns)), precision_(columns_.size(), 3) {
  COMIC_CHECK(!columns_.empty(), kInvalidArgument, "a report table needs at least one column");
}

void ReportTable::SetPrecision(const std::string& column, int digits) {
  COMIC_CHECK(digits >= 0 && digits <= 12, kInvalidArgument,
              "precision must be in [0, 12], got " << digits);
  for (size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c] == column) {
      precision_[c] = digits;
      return;
    }
  }
  throw Error(ErrorKind::kInvalidArgument, "report table has no column '" + column + "'");
}

void ReportTable::AddRow(std::vector<Cell> row) {
  COMIC_CHECK(row.size() == columns_.size(), kInvalidArgument,
              "report row has " << row.size() << " cells for " << columns_.size() << " columns");
  rows_.push_back(std::move(row));
}

std::string ReportTable::FormatCell(const Cell& cell, size_t column) const {
  if (std::holds_alternative<std::monostate>(cell)) return "";
  if (const auto* text = std::get_if<std::string>(&cell)) return *text;
  if (const auto* integer = std::get_if<int64_t>(&cell)) return std::to_string(*integer);
  const double value = std::get<double>(cell);
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision_[column]) << value;
  return out.str();
}

bool ReportTable::IsNumericColumn(size_t column) const {
  bool numeric = !rows_.empty();
  for (const auto& row : rows_) {
    const Cell& cell = row.at(column);
    numeric =
        numeric && (std::holds_alternative<int64_t>(cell) || std::holds_alternative<double>(cell) ||
                    std::holds_alternative<std::monostate>(cell));
  }
  return numeric;
}

std::string ReportTable::ToMarkdown() const {
  std::ostringstream out;
  out << "|";
  for (const std::string& column : columns_) out << " " << column << " |";
  out << "\n|";
  for (size_t c = 0; c < columns_.size(); ++c) out << (IsNumericColumn(c) ? "---:|" : "---|");
  out << "\n";
  for (const auto& row : rows_) {
    out << "|";
    for (size_t c = 0; c < columns_.size(); ++c) {
      std::string text = FormatCell(row[c], c);
      if (text.empty()) text = "–";
      // A pipe inside a cell would split it.
      for (size_t pos = 0; (pos = text.find('|', pos)) != std::string::npos; pos += 2) {
        text.replace(pos, 1, "\\|");
      }
      out << " " << text << " |";
    }
    out << "\n";
  }
  return out.str();
}

namespace {

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

std::string ReportTable::ToCsv() const {
  std::ostringstream out;
  for (size_t c = 0; c < columns_.size(); ++c) out << (c ? "," : "") << CsvField(columns_[c]);
  out << "\n";
  for (const auto& row : rows_) {
    for (size_t c = 0; c < columns_.size(); ++c) {
      out << (c ? "," : "") << CsvField(FormatCell(row[c], c));
    }
    out << "\n";
  }
  return out.str();
}

nlohmann::json ReportTable::ToJson() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : rows_) {
    nlohmann::json object = nlohmann::json::object();
    for (size_t c = 0; c < columns_.size(); ++c) {
      const Cell& cell = row[c];
      if (const auto* text = std::get_if<std::string>(&cell)) {
        object[columns_[c]] = *text;
      } else if (const auto* integer = std::get_if<int64_t>(&cell)) {
        object[columns_[c]] = *integer;
      } else if (const auto* real = std::get_if<double>(&cell); real && std::isfinite(*real)) {
        object[columns_[c]] = *real;
      } else {
        object[columns_[c]] = nullptr;
      }
    }
    rows.push_back(std::move(object));
  }
  return rows;
}

}  // namespace comic::io
