#include "io/obj_lines.hpp"

#include <cstring>

#include "io/text_scan.hpp"

namespace sm {

ObjLine scan_obj_line(std::string_view text, size_t pos) {
  ObjLine line;
  line.begin = pos;
  line.physical_lines = 0;
  size_t first = pos;
  while (first < text.size() && is_blank(text[first])) ++first;
  const bool comment = first < text.size() && text[first] == '#';
  for (;;) {
    ++line.physical_lines;
    const void* nl = std::memchr(text.data() + pos, '\n', text.size() - pos);
    const size_t brk =
        nl ? static_cast<size_t>(static_cast<const char*>(nl) - text.data()) : text.size();
    size_t content_end = brk;
    if (nl && content_end > pos && text[content_end - 1] == '\r') --content_end;
    if (nl && !comment && content_end > pos && text[content_end - 1] == '\\' &&
        brk + 1 < text.size()) {
      pos = brk + 1;
      continue;
    }
    line.content_end = content_end;
    line.end = nl ? brk + 1 : text.size();
    return line;
  }
}

std::string_view obj_line_content(std::string_view text, const ObjLine& line, std::string& buffer) {
  const std::string_view content = text.substr(line.begin, line.content_end - line.begin);
  if (line.physical_lines == 1) return content;
  buffer.assign(content);
  for (size_t i = 0; i < buffer.size(); ++i) {
    if (buffer[i] != '\n') continue;
    // Only joins hold line breaks, each as "\\\n" or "\\\r\n".
    size_t j = i;
    buffer[j] = ' ';
    if (buffer[j - 1] == '\r') buffer[--j] = ' ';
    buffer[j - 1] = ' ';
  }
  return buffer;
}

}  // namespace sm
