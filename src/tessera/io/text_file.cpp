// SPDX-License-Identifier: MIT
#include "tessera/io/text_file.h"

#include "tessera/io/detail/file_buffer.h"

namespace tessera {

void write_text_file(const std::string& path, std::string_view content, std::string_view what) {
  io_detail::write_whole_file(what, path, content);
}

std::string xml_escaped(std::string_view text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string xml_comment_text(std::string_view text) {
  std::string comment(text);
  for (auto at = comment.find("--"); at != std::string::npos; at = comment.find("--", at)) {
    comment.replace(at, 2, "- -");
  }
  return comment;
}

}  // namespace tessera
