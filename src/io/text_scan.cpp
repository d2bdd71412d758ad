#include "io/text_scan.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace sm {

std::string_view next_token(std::string_view line, size_t& pos) {
  while (pos < line.size() && is_blank(line[pos])) ++pos;
  const size_t begin = pos;
  while (pos < line.size() && !is_blank(line[pos])) ++pos;
  return line.substr(begin, pos - begin);
}

namespace {

// Drops one leading '+' (std::from_chars rejects it); false if a second sign follows.
bool strip_plus(std::string_view& token) {
  if (token.empty() || token[0] != '+') return true;
  token.remove_prefix(1);
  return token.empty() || (token[0] != '+' && token[0] != '-');
}

}  // namespace

bool parse_double(std::string_view token, double& value) {
  if (!strip_plus(token) || token.empty()) return false;
  const char* first = token.data();
  const char* last = first + token.size();
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range && ptr == last) {
    // Beyond the double range: the wider long double rounds it to ±inf or ±0 as a double.
    long double wide = 0;
    if (std::from_chars(first, last, wide).ec == std::errc()) {
      value = static_cast<double>(wide);
    } else {  // beyond even long double: a negative exponent means underflow
      const size_t e = token.find_first_of("eE");
      const bool tiny = e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
      value = std::copysign(tiny ? 0.0 : HUGE_VAL, *first == '-' ? -1.0 : 1.0);
    }
    return true;
  }
  return ec == std::errc() && ptr == last;
}

bool parse_int(std::string_view token, int64_t& value) {
  if (!strip_plus(token) || token.empty()) return false;
  const char* last = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), last, value);
  return ec == std::errc() && ptr == last;
}

void append_double(std::string& out, double value) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, r.ptr);
}

void append_int(std::string& out, int64_t value) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, r.ptr);
}

std::string non_text_encoding(std::string_view bytes) {
  const std::string_view head = bytes.substr(0, 4096);
  if (head.substr(0, 4) == std::string_view("\xFF\xFE\0\0", 4))
    return "it is UTF-32 (little-endian, byte order mark FF FE 00 00)";
  if (head.substr(0, 4) == std::string_view("\0\0\xFE\xFF", 4))
    return "it is UTF-32 (big-endian, byte order mark 00 00 FE FF)";
  if (head.substr(0, 2) == "\xFF\xFE") return "it is UTF-16 (little-endian, byte order mark FF FE)";
  if (head.substr(0, 2) == "\xFE\xFF") return "it is UTF-16 (big-endian, byte order mark FE FF)";
  size_t even = 0, odd = 0;
  for (size_t i = 0; i < head.size(); ++i) {
    if (head[i] == '\0') ++(i % 2 ? odd : even);
  }
  if (even + odd == 0) return "";
  const size_t half = head.size() / 2;
  if (odd * 10 >= half * 9 && even * 10 < half)
    return "it looks like UTF-16 little-endian (every other byte is NUL)";
  if (even * 10 >= half * 9 && odd * 10 < half)
    return "it looks like UTF-16 big-endian (every other byte is NUL)";
  return "it holds NUL bytes (binary data)";
}

}  // namespace sm
