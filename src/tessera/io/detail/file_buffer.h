// SPDX-License-Identifier: MIT
// Internal to the io layer: buffered file output with exact number formatting, whole-file input,
// tokenising of text formats and error messages that name the file.
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera::io_detail {

/// `value` with its bytes in reverse order (to convert between little and big endian).
template <class T>
T byte_swapped(T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
    const char c = bytes[i];
    bytes[i] = bytes[sizeof(T) - 1 - i];
    bytes[sizeof(T) - 1 - i] = c;
  }
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

/// Throws InvalidArgument "<format> file '<path>': <message>".
[[noreturn]] void throw_file_error(std::string_view format, const std::string& path,
                                   const std::string& message);
/// Throws InvalidArgument "<format> file '<path>', line <line>: <message>" (lines count from 1).
[[noreturn]] void throw_file_error(std::string_view format, const std::string& path,
                                   std::size_t line, const std::string& message);

/// The whole content of `path`, byte for byte. \throw InvalidArgument naming the file.
std::string read_file(std::string_view format, const std::string& path);

/// Writes a file through one large buffer, numbers formatted with std::to_chars, and replaces
/// the target only once the whole file is written.
///
/// The bytes go to a temporary file in the folder of `path` (".<name>.tmp.<pid>.<k>", created
/// exclusively), which close() flushes, syncs to disk (fdatasync) and renames over `path`. So a
/// failed write (disk full, file size limit, I/O error), an exception in the writer or a kill
/// before close() leaves a file that existed at `path` untouched; on failure the temporary is
/// removed (a SIGKILL can leave it behind, never a damaged target). An existing target keeps
/// its permission bits. A symbolic link is followed: the file it points to is replaced, the
/// link stays. A target that exists and is not a regular file (a device, a FIFO), a link under
/// /dev/ (/dev/stdout) and a path under /proc/ are written in place, where a temporary and a
/// rename make no sense.
///
/// fdatasync before the rename: without it a crash of the machine (not of the program) soon
/// after the rename may leave an empty target on file systems that commit the rename before the
/// data. It costs one wait for the disk per file, small next to computing a mesh.
class OutputFile {
 public:
  /// Creates the temporary next to `path`.
  /// \throw InvalidArgument naming `path` if it cannot be created (no folder, no permission).
  OutputFile(std::string_view format, std::string path);
  /// Without a successful close(): removes the temporary, leaves `path` as it was.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void text(std::string_view text) { bytes(text.data(), text.size()); }
  void character(char c) {
    make_room(1);
    buffer_[used_++] = c;
  }
  /// Shortest decimal representation that reads back to the same double (std::to_chars).
  void real(double value) {
    make_room(kMaxNumberLength);
    used_ = static_cast<std::size_t>(
        std::to_chars(buffer_.data() + used_, buffer_.data() + buffer_.size(), value).ptr -
        buffer_.data());
  }
  void integer(std::int64_t value) {
    make_room(kMaxNumberLength);
    used_ = static_cast<std::size_t>(
        std::to_chars(buffer_.data() + used_, buffer_.data() + buffer_.size(), value).ptr -
        buffer_.data());
  }
  void bytes(const void* data, std::size_t size);
  /// Little-endian binary values, whatever the byte order of this machine.
  void little_endian_double(double value);
  void little_endian_int32(std::int32_t value);
  void little_endian_int64(std::int64_t value);

  /// Writes the rest of the buffer, syncs, closes and renames the temporary over the target.
  /// \throw InvalidArgument naming the target and the system's reason (e.g. "No space left on
  ///        device") if any step failed; the temporary is then removed and the target is as it
  ///        was before.
  void close();

 private:
  static constexpr std::size_t kBufferSize = std::size_t{1} << 20;
  static constexpr std::size_t kMaxNumberLength = 32;  // "-2.2250738585072014e-308" is 24
  void make_room(std::size_t size) {
    if (used_ + size > buffer_.size()) {
      flush();
    }
  }
  void flush();
  void write_all(const char* data, std::size_t size);
  /// Closes the descriptor and removes the temporary, keeping the first error seen.
  void abandon();

  std::string format_;
  std::string path_;       ///< as given, for messages
  std::string target_;     ///< the file replaced: path_, or what its symbolic link names
  std::string temporary_;  ///< empty when writing in place
  int descriptor_ = -1;
  int error_ = 0;  ///< errno of the first failed write, 0 if none
  std::vector<char> buffer_;
  std::size_t used_ = 0;
};

/// Writes `content` to `path` through OutputFile (so the same atomic replacement); `format`
/// names the kind of file in messages. \throw InvalidArgument as OutputFile.
void write_whole_file(std::string_view format, const std::string& path, std::string_view content);

/// Parses the whole token as a double (std::from_chars, correctly rounded, so text written by
/// OutputFile::real reads back bit for bit). Accepts a leading '+', "inf" and "nan".
bool parse_real(std::string_view token, double& value);
/// Parses the whole token as a decimal integer (a leading '+' is accepted).
bool parse_integer(std::string_view token, std::int64_t& value);

/// Writes one line "3 a b c" per triangle: the face list of ASCII PLY and of legacy VTK.
void write_triangle_lines(OutputFile& file, const std::vector<Triangle>& triangles);

/// Whitespace-separated tokens of a text, with the line number of each token.
class TextCursor {
 public:
  TextCursor(std::string_view text, std::size_t first_line) : text_(text), line_(first_line) {}
  /// The next token, or an empty view at the end of the text.
  std::string_view next_token();
  /// Line of the last token returned (at the end of the text: of the last token).
  std::size_t line() const { return line_; }
  /// Characters not yet consumed.
  std::size_t remaining() const { return text_.size() - position_; }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  std::size_t line_;
};

/// Splits one line into whitespace-separated tokens (spaces, tabs, '\r').
std::vector<std::string_view> split_tokens(std::string_view line);

/// True if `name` is non-empty and has no whitespace or control characters, as needed for a
/// property or array name in PLY and legacy VTK headers.
bool is_plain_name(std::string_view name);

}  // namespace tessera::io_detail
