#pragma once
/// Logical lines of OBJ text: physical lines joined by a trailing backslash, shared by the OBJ
/// reader and writer so both split a file the same way.
#include <cstddef>
#include <string>
#include <string_view>

namespace sm {

struct ObjLine {
  size_t begin = 0;        ///< first byte
  size_t content_end = 0;  ///< end of the content: before the last line break and its '\r'
  size_t end = 0;          ///< after the last line break (or the end of the text)
  int physical_lines = 1;  ///< how many physical lines were joined
};

/// The logical line starting at `pos` (< text.size()). A physical line whose last character
/// before the line break is '\' continues on the next one, unless it is a comment line (first
/// non-blank '#') or the last line of the text.
ObjLine scan_obj_line(std::string_view text, size_t pos);

/// The content of `line` as one string: a view into `text`, or, for a joined line, `buffer` with
/// every backslash and line break replaced by blanks.
std::string_view obj_line_content(std::string_view text, const ObjLine& line, std::string& buffer);

}  // namespace sm
