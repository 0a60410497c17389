// SPDX-License-Identifier: MIT
#include "tessera/core/binary_stream.h"

#include <bit>
#include <cstring>

#include "tessera/core/error.h"

namespace tessera {

std::uint64_t checksum64(std::string_view bytes) {
  constexpr std::uint64_t kPrime = 0x100000001b3ULL;
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  std::size_t i = 0;
  // Whole words first (8× fewer multiplications than byte-wise FNV-1a: a checkpoint of
  // hundreds of MB is hashed in a fraction of a second).
  for (; i + 8 <= bytes.size(); i += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, bytes.data() + i, 8);
    if constexpr (std::endian::native == std::endian::big) {
      word = __builtin_bswap64(word);
    }
    hash = (hash ^ word) * kPrime;
    hash ^= hash >> 29;
  }
  for (; i < bytes.size(); ++i) {
    hash = (hash ^ static_cast<unsigned char>(bytes[i])) * kPrime;
  }
  return hash;
}

void BinaryWriter::u64_bytes(std::uint64_t value, int count) {
  for (int b = 0; b < count; ++b) {
    bytes_.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
  }
}

void BinaryWriter::f32(float value) { u32(std::bit_cast<std::uint32_t>(value)); }

void BinaryWriter::f64(double value) { u64(std::bit_cast<std::uint64_t>(value)); }

void BinaryWriter::string(std::string_view text) {
  u64(text.size());
  bytes_.append(text.data(), text.size());
}

void BinaryWriter::matrix(const Eigen::Ref<const Eigen::MatrixXd>& m) {
  i64(m.rows());
  i64(m.cols());
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      f64(m(i, j));
    }
  }
}

void BinaryWriter::doubles(const double* values, std::size_t count) {
  if (count == 0) {
    return;  // values may be null
  }
  if constexpr (std::endian::native == std::endian::little) {
    bytes_.append(reinterpret_cast<const char*>(values), count * sizeof(double));
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      f64(values[k]);
    }
  }
}

void BinaryReader::fail(const std::string& message) const {
  throw InvalidArgument(what_ + ": " + message);
}

void BinaryReader::need(const char* field, std::size_t size) const {
  if (size > remaining()) {
    fail("truncated: " + std::string(field) + " needs " + std::to_string(size) +
         " bytes at offset " + std::to_string(offset_) + ", " + std::to_string(remaining()) +
         " left");
  }
}

std::uint64_t BinaryReader::u64_bytes(const char* field, int count) {
  need(field, static_cast<std::size_t>(count));
  std::uint64_t value = 0;
  for (int b = 0; b < count; ++b) {
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[offset_ + b])) << (8 * b);
  }
  offset_ += static_cast<std::size_t>(count);
  return value;
}

std::uint8_t BinaryReader::u8(const char* field) {
  return static_cast<std::uint8_t>(u64_bytes(field, 1));
}

float BinaryReader::f32(const char* field) { return std::bit_cast<float>(u32(field)); }

double BinaryReader::f64(const char* field) { return std::bit_cast<double>(u64(field)); }

std::size_t BinaryReader::count(const char* field, std::size_t item_bytes) {
  const std::uint64_t value = u64(field);
  if (item_bytes > 0 && value > remaining() / item_bytes) {
    fail("truncated or corrupt: " + std::string(field) + " = " + std::to_string(value) +
         " items of " + std::to_string(item_bytes) + " bytes, but only " +
         std::to_string(remaining()) + " bytes are left");
  }
  return static_cast<std::size_t>(value);
}

std::string BinaryReader::string(const char* field) {
  const std::size_t size = count(field, 1);
  std::string text(bytes_.substr(offset_, size));
  offset_ += size;
  return text;
}

Eigen::MatrixXd BinaryReader::matrix(const char* field, Eigen::Index rows, Eigen::Index cols) {
  const std::int64_t r = i64(field);
  const std::int64_t c = i64(field);
  if (r < 0 || c < 0 || (rows >= 0 && r != rows) || (cols >= 0 && c != cols)) {
    fail("corrupt: " + std::string(field) + " is " + std::to_string(r) + "×" + std::to_string(c) +
         (rows >= 0 ? ", expected " + std::to_string(rows) + "×" + std::to_string(cols) : ""));
  }
  if (r > 0 && static_cast<std::uint64_t>(c) > remaining() / 8 / static_cast<std::uint64_t>(r)) {
    need(field, static_cast<std::size_t>(r) * static_cast<std::size_t>(c) * 8);
  }
  Eigen::MatrixXd m(r, c);
  doubles(field, m.data(), static_cast<std::size_t>(m.size()));
  return m;
}

void BinaryReader::doubles(const char* field, double* values, std::size_t count) {
  if (count == 0) {
    return;  // an empty matrix's data() may be null, which memcpy must not get
  }
  if (count > remaining() / sizeof(double)) {
    need(field, count * sizeof(double));
  }
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(values, bytes_.data() + offset_, count * sizeof(double));
    offset_ += count * sizeof(double);
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      values[k] = f64(field);
    }
  }
}

}  // namespace tessera
