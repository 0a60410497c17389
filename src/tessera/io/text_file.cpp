// SPDX-License-Identifier: MIT
#include "tessera/io/text_file.h"

#include "tessera/io/detail/file_buffer.h"

namespace tessera {

void write_text_file(const std::string& path, std::string_view content, std::string_view what) {
  io_detail::write_whole_file(what, path, content);
}

}  // namespace tessera
