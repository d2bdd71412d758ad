#pragma once
/// A small CSV writer with deterministic number formatting: shortest round-trip decimals
/// (std::to_chars), "inf", "-inf" and "nan" for non-finite values, RFC 4180 quoting.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sm {

/// Shortest decimal that reads back as exactly `x` ("0.1", "1e-07", "12"); "-0" is written "0";
/// non-finite values are "inf", "-inf" and "nan". Independent of the locale.
std::string format_number(double x);

/// `text` as one CSV field: quoted (with inner quotes doubled) when it holds a comma, a quote or
/// a line break, as is otherwise.
std::string csv_field(std::string_view text);

/// Builds a CSV document row by row: a header line, then rows of exactly as many cells, each line
/// ended by "\n".
class CsvWriter {
 public:
  explicit CsvWriter(std::vector<std::string> columns);

  CsvWriter& cell(double value);
  CsvWriter& cell(int value);
  CsvWriter& cell(int64_t value);
  CsvWriter& cell(std::string_view text);
  CsvWriter& cell(const char* text) { return cell(std::string_view(text)); }
  /// Ends the current row. Missing cells are written empty; extra cells are a programming error.
  CsvWriter& end_row();

  const std::vector<std::string>& columns() const { return columns_; }
  int rows() const { return rows_; }
  /// The document so far (header and the completed rows).
  const std::string& str() const { return text_; }

 private:
  void append(std::string_view escaped);
  std::vector<std::string> columns_;
  std::string text_;
  int cells_in_row_ = 0;
  int rows_ = 0;
};

}  // namespace sm
