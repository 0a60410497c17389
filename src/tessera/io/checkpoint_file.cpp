// SPDX-License-Identifier: MIT
#include "tessera/io/checkpoint_file.h"

#include <cstring>

#include "tessera/core/binary_stream.h"
#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"

namespace tessera {
namespace {

constexpr char kMagic[8] = {'T', 'S', 'R', 'C', 'K', 'P', 'T', '\x1a'};

}  // namespace

const std::string& CheckpointFile::section(const std::string& name, const std::string& path) const {
  for (const auto& [section_name, payload] : sections) {
    if (section_name == name) {
      return payload;
    }
  }
  throw InvalidArgument("checkpoint file '" + path + "': it has no section '" + name + "'");
}

void write_checkpoint_file(const std::string& path, const CheckpointFile& file) {
  BinaryWriter out;
  for (char c : kMagic) {
    out.u8(static_cast<std::uint8_t>(c));
  }
  out.u32(kCheckpointFormatVersion);
  out.u32(static_cast<std::uint32_t>(file.sections.size()));
  for (const auto& [name, payload] : file.sections) {
    out.string(name);
    out.string(payload);
  }
  out.u64(checksum64(out.bytes()));
  io_detail::write_whole_file("checkpoint", path, out.bytes());
}

CheckpointFile read_checkpoint_file(const std::string& path) {
  const std::string bytes = io_detail::read_file("checkpoint", path);
  BinaryReader in(bytes, "checkpoint file '" + path + "'");
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    in.fail("not a tessera checkpoint (it does not begin with the magic number TSRCKPT; "
            "`tessera mesh --checkpoint FILE` writes them)");
  }
  for (std::size_t k = 0; k < sizeof(kMagic); ++k) {
    in.u8("magic");
  }
  const std::uint32_t version = in.u32("format version");
  if (version != kCheckpointFormatVersion) {
    in.fail("format version " + std::to_string(version) + ", but this tessera reads version " +
            std::to_string(kCheckpointFormatVersion) +
            ": resume it with the tessera that wrote it, or start the run again");
  }
  CheckpointFile file;
  const std::uint32_t count = in.u32("section count");
  for (std::uint32_t k = 0; k < count; ++k) {
    std::string name = in.string("section name");
    std::string payload = in.string(("section '" + name + "'").c_str());
    file.sections.emplace_back(std::move(name), std::move(payload));
  }
  const std::size_t body = in.offset();
  const std::uint64_t stored = in.u64("checksum");
  if (in.remaining() != 0) {
    in.fail("corrupt: " + std::to_string(in.remaining()) + " bytes after the checksum");
  }
  const std::uint64_t computed = checksum64(std::string_view(bytes).substr(0, body));
  if (stored != computed) {
    in.fail("corrupt: its checksum does not match its contents (a byte was changed or lost)");
  }
  return file;
}

FileFingerprint fingerprint_file(const std::string& path) {
  const std::string bytes = io_detail::read_file("problem", path);
  return {bytes.size(), checksum64(bytes)};
}

}  // namespace tessera
