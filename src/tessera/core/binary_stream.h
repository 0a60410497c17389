// SPDX-License-Identifier: MIT
// Little-endian binary records with exact doubles (their bits), for checkpoints: a writer that
// appends to a byte string and a reader that checks every length against what is left.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>

namespace tessera {

/// A 64-bit checksum of `bytes` (FNV-1a over 8-byte words, then the tail): detects flipped and
/// lost bytes of a file, not a deliberate forgery.
std::uint64_t checksum64(std::string_view bytes);

/// Appends values as little-endian bytes, whatever the byte order of this machine. Doubles are
/// written as their 64 bits, so they read back bit for bit (NaN payloads included).
class BinaryWriter {
 public:
  void u8(std::uint8_t value) { bytes_.push_back(static_cast<char>(value)); }
  void i32(std::int32_t value) { u64_bytes(static_cast<std::uint32_t>(value), 4); }
  void u32(std::uint32_t value) { u64_bytes(value, 4); }
  void i64(std::int64_t value) { u64_bytes(static_cast<std::uint64_t>(value), 8); }
  void u64(std::uint64_t value) { u64_bytes(value, 8); }
  void f32(float value);
  void f64(double value);
  /// A length (u64) and the bytes.
  void string(std::string_view text);
  /// rows, cols (i64 each) and the entries in column order.
  void matrix(const Eigen::Ref<const Eigen::MatrixXd>& m);
  void doubles(const double* values, std::size_t count);

  /// Appends what `other` holds.
  void bytes_of(const BinaryWriter& other) { bytes_ += other.bytes_; }
  /// Room for `size` bytes in all (a large record is then not copied as it grows).
  void reserve(std::size_t size) { bytes_.reserve(size); }

  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  void u64_bytes(std::uint64_t value, int count);
  std::string bytes_;
};

/// Reads what BinaryWriter wrote. Every read checks that the bytes are there.
/// \throw InvalidArgument "<what>: truncated: <field> needs N bytes at offset K, M left" (or an
///        implausible length), `what` naming the file or record.
class BinaryReader {
 public:
  BinaryReader(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

  std::uint8_t u8(const char* field);
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(u64_bytes(field, 4)); }
  std::uint32_t u32(const char* field) { return static_cast<std::uint32_t>(u64_bytes(field, 4)); }
  std::int64_t i64(const char* field) { return static_cast<std::int64_t>(u64_bytes(field, 8)); }
  std::uint64_t u64(const char* field) { return u64_bytes(field, 8); }
  float f32(const char* field);
  double f64(const char* field);
  std::string string(const char* field);
  /// \param rows, cols  the expected shape (−1: any); a mismatch throws naming the field.
  Eigen::MatrixXd matrix(const char* field, Eigen::Index rows = -1, Eigen::Index cols = -1);
  void doubles(const char* field, double* values, std::size_t count);
  /// A count of items of at least `item_bytes` each: refused if more than the bytes left hold.
  std::size_t count(const char* field, std::size_t item_bytes);

  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  const std::string& what() const { return what_; }
  /// \throw InvalidArgument "<what>: <message>".
  [[noreturn]] void fail(const std::string& message) const;

 private:
  void need(const char* field, std::size_t size) const;
  std::uint64_t u64_bytes(const char* field, int count);
  std::string_view bytes_;
  std::string what_;
  std::size_t offset_ = 0;
};

}  // namespace tessera
