#pragma once
/// Lexing shared by the text mesh formats: whitespace tokens and exact, locale-independent numbers.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace sm {

/// Space, tab, carriage return, vertical tab and form feed (line feeds end lines before lexing).
inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// The token of `line` starting at or after `pos` (skipping blanks), or an empty view when only
/// blanks are left; `pos` moves past the token.
std::string_view next_token(std::string_view line, size_t& pos);

/// Parses the whole of `token` as a decimal floating-point number (a leading '+' is allowed).
/// Magnitudes beyond the double range give ±infinity or ±0; "nan" and "inf" parse too, so callers
/// check std::isfinite. Returns false if `token` is not a number.
bool parse_double(std::string_view token, double& value);

/// Parses the whole of `token` as a decimal integer (a leading '+' is allowed). Returns false if it
/// is not an integer or does not fit in 64 bits.
bool parse_int(std::string_view token, int64_t& value);

/// Why `bytes` is not a text file in an ASCII-compatible encoding (UTF-8, Latin-1), judged by the
/// first 4 KiB: "it is UTF-16 (little-endian, byte order mark FF FE)", "it looks like UTF-16
/// big-endian (every other byte is NUL)", "it holds NUL bytes (binary data)"; empty if text.
std::string non_text_encoding(std::string_view bytes);

/// Appends the shortest decimal text that reads back as exactly `value` (std::to_chars), e.g.
/// "0.1", "-2.5e-07", "1e+20". Independent of the locale, hence byte-deterministic.
void append_double(std::string& out, double value);

/// Appends the decimal text of `value`.
void append_int(std::string& out, int64_t value);

}  // namespace sm
