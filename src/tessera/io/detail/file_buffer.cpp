// SPDX-License-Identifier: MIT
#include "tessera/io/detail/file_buffer.h"

#include <cerrno>
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

OutputFile::OutputFile(std::string_view format, std::string path)
    : format_(format), path_(std::move(path)), buffer_(kBufferSize) {
  file_ = std::fopen(path_.c_str(), "wb");
  if (file_ == nullptr) {
    throw_file_error(format_, path_, "cannot open for writing: " + system_reason());
  }
}

OutputFile::~OutputFile() {
  if (file_ != nullptr) {
    // Only reached when an exception left the writer early; the caller already has an error.
    std::fclose(file_);
  }
}

void OutputFile::bytes(const void* data, std::size_t size) {
  if (used_ + size > buffer_.size()) {
    flush();
    if (size > buffer_.size()) {
      failed_ = failed_ || std::fwrite(data, 1, size, file_) != size;
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

void OutputFile::flush() {
  if (used_ > 0) {
    failed_ = failed_ || std::fwrite(buffer_.data(), 1, used_, file_) != used_;
    used_ = 0;
  }
}

void OutputFile::close() {
  flush();
  const bool failed = failed_ || std::ferror(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || close_failed) {
    throw_file_error(format_, path_, "write failed: " + system_reason());
  }
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
