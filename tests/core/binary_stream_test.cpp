// SPDX-License-Identifier: MIT
// Binary records of checkpoints: values come back bit for bit, and a short or damaged record
// is refused naming the field, never read past its end.
#include "tessera/core/binary_stream.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "tessera/core/error.h"

namespace tessera {
namespace {

TEST(BinaryStream, ValuesComeBackBitForBit) {
  BinaryWriter out;
  const double payload_nan = std::bit_cast<double>(0x7ff8000000000123ULL);
  out.f64(-0.0);
  out.f64(payload_nan);
  out.f64(std::numeric_limits<double>::denorm_min());
  out.f32(1.0f / 3.0f);
  out.i32(-7);
  out.i64(-(std::int64_t{1} << 40));
  out.string("atlas");
  Eigen::MatrixXd m(2, 3);
  m << 1, 2, 3, 4, 5, std::nextafter(6.0, 7.0);
  out.matrix(m);
  const std::string bytes = out.bytes();
  EXPECT_EQ(bytes.size(), 8u * 3 + 4 + 4 + 8 + 8 + 5 + 16 + 48);
  BinaryReader in(bytes, "test");
  EXPECT_EQ(std::bit_cast<std::uint64_t>(in.f64("a")), std::bit_cast<std::uint64_t>(-0.0));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(in.f64("b")), 0x7ff8000000000123ULL);
  EXPECT_EQ(in.f64("c"), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(in.f32("d"), 1.0f / 3.0f);
  EXPECT_EQ(in.i32("e"), -7);
  EXPECT_EQ(in.i64("f"), -(std::int64_t{1} << 40));
  EXPECT_EQ(in.string("g"), "atlas");
  const Eigen::MatrixXd back = in.matrix("m", 2, 3);
  EXPECT_TRUE((back.array() == m.array()).all());
  EXPECT_EQ(in.remaining(), 0u);
}

TEST(BinaryStream, ShortOrDamagedRecordsAreRefusedNamingTheField) {
  BinaryWriter out;
  out.string("a long enough string");
  const std::string bytes = out.bytes();
  BinaryReader truncated(std::string_view(bytes).substr(0, 12), "record");
  try {
    truncated.string("chart name");
    ADD_FAILURE() << "read past the end";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("chart name"), std::string::npos) << error.what();
  }
  // A count that the bytes left cannot hold (a flipped length) is refused before allocating.
  BinaryWriter huge;
  huge.u64(std::uint64_t{1} << 60);
  BinaryReader in(huge.bytes(), "record");
  EXPECT_THROW(in.count("polygon", 20), InvalidArgument);
  BinaryWriter shape;
  shape.matrix(Eigen::MatrixXd::Zero(3, 2));
  BinaryReader wrong(shape.bytes(), "record");
  EXPECT_THROW(wrong.matrix("tangent", 3, 3), InvalidArgument);
}

TEST(BinaryStream, ChecksumSeesEveryByte) {
  std::string bytes(1001, 'x');
  const std::uint64_t sum = checksum64(bytes);
  for (std::size_t at : {0u, 7u, 8u, 500u, 999u, 1000u}) {
    std::string changed = bytes;
    changed[at] ^= 1;
    EXPECT_NE(checksum64(changed), sum) << "byte " << at;
  }
  EXPECT_NE(checksum64(bytes.substr(0, 1000)), sum);
}

}  // namespace
}  // namespace tessera
