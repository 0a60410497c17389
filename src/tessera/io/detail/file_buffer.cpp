// SPDX-License-Identifier: MIT
#include "tessera/io/detail/file_buffer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <system_error>

#include "tessera/core/error.h"

namespace tessera::io_detail {

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

std::string system_reason() { return std::generic_category().message(errno); }

}  // namespace

void throw_file_error(std::string_view format, const std::string& path,
                      const std::string& message) {
  throw InvalidArgument(std::string(format) + " file '" + path + "': " + message);
}

void throw_file_error(std::string_view format, const std::string& path, std::size_t line,
                      const std::string& message) {
  throw InvalidArgument(std::string(format) + " file '" + path + "', line " + std::to_string(line) +
                        ": " + message);
}

std::string read_file(std::string_view format, const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    throw_file_error(format, path, "cannot open for reading: " + system_reason());
  }
  std::string content;
  char block[1 << 16];
  std::size_t count = 0;
  while ((count = std::fread(block, 1, sizeof block, file)) > 0) {
    content.append(block, count);
  }
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) {
    throw_file_error(format, path, "read error: " + system_reason());
  }
  return content;
}

namespace {

// Distinguishes the temporaries of several OutputFiles of one process writing into one folder.
std::atomic<unsigned> temporary_counter{0};

std::string reason(int error) { return std::generic_category().message(error); }

}  // namespace

OutputFile::OutputFile(std::string_view format, std::string path)
    : format_(format), path_(std::move(path)), target_(path_) {
  namespace fs = std::filesystem;
  std::error_code error;
  // /dev/stdout, /dev/fd/N and /proc/... name streams, not files to replace: with `> out.json`
  // the link resolves to a regular file, and a rename over it would leave the shell's stream
  // unchanged. (A file in a folder such as /dev/shm is replaced as anywhere else.)
  const bool is_stream =
      path_.rfind("/proc/", 0) == 0 ||
      (path_.rfind("/dev/", 0) == 0 && fs::is_symlink(fs::symlink_status(path_, error)));
  if (!is_stream && fs::is_symlink(fs::symlink_status(path_, error))) {
    // Replace what the link names, not the link: writing through it is what fopen did.
    const fs::path resolved = fs::canonical(path_, error);
    if (!error) {
      target_ = resolved.string();
    }
  }
  const fs::file_status status = fs::status(target_, error);
  if (is_stream || (fs::exists(status) && !fs::is_regular_file(status))) {
    if (fs::is_directory(status)) {
      throw_file_error(format_, path_, "cannot open for writing: it is a folder");
    }
    // A device or a FIFO: no folder to put a temporary in that could be renamed over it. As
    // fopen(path, "wb") would: a regular file behind /dev/stdout is truncated first.
    descriptor_ = ::open(target_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (descriptor_ < 0) {
      throw_file_error(format_, path_, "cannot open for writing: " + system_reason());
    }
    buffer_.resize(kBufferSize);
    return;
  }
  const fs::path target(target_);
  temporary_ = (target.parent_path() /
                ("." + target.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
                 std::to_string(temporary_counter++)))
                   .string();
  descriptor_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (descriptor_ < 0) {
    const std::string why = system_reason();
    temporary_.clear();
    throw_file_error(format_, path_,
                     "cannot open for writing (temporary file in its folder): " + why);
  }
  if (fs::is_regular_file(status)) {
    // The replacement keeps the permissions of the file it replaces, as writing in place did.
    struct stat existing {};
    if (::stat(target_.c_str(), &existing) == 0) {
      ::fchmod(descriptor_, existing.st_mode & 07777);
    }
  }
  buffer_.resize(kBufferSize);
}

OutputFile::~OutputFile() {
  // Only reached with the descriptor open when the writer left early by an exception; the
  // caller already has an error, and the target must stay as it was.
  abandon();
}

void OutputFile::abandon() {
  if (descriptor_ >= 0) {
    ::close(descriptor_);
    descriptor_ = -1;
  }
  if (!temporary_.empty()) {
    ::unlink(temporary_.c_str());
    temporary_.clear();
  }
}

void OutputFile::write_all(const char* data, std::size_t size) {
  while (size > 0 && error_ == 0) {
    const ssize_t written = ::write(descriptor_, data, size);
    if (written < 0) {
      if (errno != EINTR) {
        error_ = errno;
      }
      continue;
    }
    if (written == 0) {
      error_ = EIO;  // write(2) makes no progress only on a broken device
      continue;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

void OutputFile::bytes(const void* data, std::size_t size) {
  if (used_ + size > buffer_.size()) {
    flush();
    if (size > buffer_.size()) {
      write_all(static_cast<const char*>(data), size);
      return;
    }
  }
  std::memcpy(buffer_.data() + used_, data, size);
  used_ += size;
}

void OutputFile::little_endian_double(double value) {
  if constexpr (std::endian::native == std::endian::big) {
    value = byte_swapped(value);
  }
  bytes(&value, sizeof value);
}

void OutputFile::little_endian_int32(std::int32_t value) {
  if constexpr (std::endian::native == std::endian::big) {
    value = byte_swapped(value);
  }
  bytes(&value, sizeof value);
}

void OutputFile::little_endian_int64(std::int64_t value) {
  if constexpr (std::endian::native == std::endian::big) {
    value = byte_swapped(value);
  }
  bytes(&value, sizeof value);
}

void OutputFile::flush() {
  if (used_ > 0) {
    write_all(buffer_.data(), used_);
    used_ = 0;
  }
}

void OutputFile::close() {
  TESSERA_ASSERT(descriptor_ >= 0);
  flush();
  const bool in_place = temporary_.empty();
  auto fail = [&](int error, const std::string& step) {
    abandon();
    throw_file_error(format_, path_,
                     step + ": " + reason(error) + (in_place ? "" : "; the file was not changed"));
  };
  if (error_ != 0) {
    fail(error_, "write failed");
  }
  if (!in_place && ::fdatasync(descriptor_) != 0) {
    fail(errno, "write failed (fdatasync)");
  }
  const int descriptor = descriptor_;
  descriptor_ = -1;
  if (::close(descriptor) != 0 && errno != EINTR) {
    fail(errno, "write failed (close)");
  }
  if (!in_place) {
    if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
      fail(errno, "cannot replace the file by the temporary '" + temporary_ + "'");
    }
    temporary_.clear();
  }
}

void write_whole_file(std::string_view format, const std::string& path, std::string_view content) {
  OutputFile file(format, path);
  file.text(content);
  file.close();
}

void write_triangle_lines(OutputFile& file, const std::vector<Triangle>& triangles) {
  for (const auto& triangle : triangles) {
    file.character('3');
    for (const int v : triangle) {
      file.character(' ');
      file.integer(v);
    }
    file.character('\n');
  }
}

namespace {

// The whole token must be a number; a leading '+' is accepted (from_chars does not).
template <class Number>
bool parse_whole_token(std::string_view token, Number& value) {
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
  }
  if (token.empty()) {
    return false;
  }
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size();
}

}  // namespace

bool parse_real(std::string_view token, double& value) { return parse_whole_token(token, value); }

bool parse_integer(std::string_view token, std::int64_t& value) {
  return parse_whole_token(token, value);
}

std::string_view TextCursor::next_token() {
  // Line breaks count only once a token follows them, so that "unexpected end of file" names
  // the last line that has data rather than the empty line after it.
  std::size_t line_breaks = 0;
  while (position_ < text_.size() && is_space(text_[position_])) {
    if (text_[position_] == '\n') {
      ++line_breaks;
    }
    ++position_;
  }
  if (position_ < text_.size()) {
    line_ += line_breaks;
  }
  const std::size_t begin = position_;
  while (position_ < text_.size() && !is_space(text_[position_])) {
    ++position_;
  }
  return text_.substr(begin, position_ - begin);
}

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t position = 0;
  while (true) {
    while (position < line.size() && is_space(line[position])) {
      ++position;
    }
    if (position == line.size()) {
      return tokens;
    }
    const std::size_t begin = position;
    while (position < line.size() && !is_space(line[position])) {
      ++position;
    }
    tokens.push_back(line.substr(begin, position - begin));
  }
}

bool is_plain_name(std::string_view name) {
  if (name.empty()) {
    return false;
  }
  for (const char c : name) {
    if (static_cast<unsigned char>(c) <= ' ' || c == 127) {
      return false;
    }
  }
  return true;
}

}  // namespace tessera::io_detail
