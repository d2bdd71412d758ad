#include "io/csv.hpp"

#include <cassert>
#include <charconv>
#include <cmath>

namespace sm {

std::string format_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == 0.0) return "0";
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), x);
  assert(ec == std::errc());
  (void)ec;
  return std::string(buffer, end);
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

CsvWriter::CsvWriter(std::vector<std::string> columns) : columns_(std::move(columns)) {
  for (size_t i = 0; i < columns_.size(); ++i) {
    if (i > 0) text_ += ',';
    text_ += csv_field(columns_[i]);
  }
  text_ += '\n';
}

void CsvWriter::append(std::string_view escaped) {
  assert(cells_in_row_ < static_cast<int>(columns_.size()) && "more cells than columns");
  if (cells_in_row_ > 0) text_ += ',';
  text_ += escaped;
  ++cells_in_row_;
}

CsvWriter& CsvWriter::cell(double value) {
  append(format_number(value));
  return *this;
}

CsvWriter& CsvWriter::cell(int value) {
  append(std::to_string(value));
  return *this;
}

CsvWriter& CsvWriter::cell(int64_t value) {
  append(std::to_string(value));
  return *this;
}

CsvWriter& CsvWriter::cell(std::string_view text) {
  append(csv_field(text));
  return *this;
}

CsvWriter& CsvWriter::end_row() {
  while (cells_in_row_ < static_cast<int>(columns_.size())) append("");
  text_ += '\n';
  cells_in_row_ = 0;
  ++rows_;
  return *this;
}

}  // namespace sm
