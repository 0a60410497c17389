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
  // The index (header, names, lengths, checksums) is checksummed as a whole at the end; each
  // payload goes to the file from the caller's string.
  BinaryWriter index;
  io_detail::OutputFile out("checkpoint", path);
  const auto emit = [&out, &index](const BinaryWriter& piece) {
    out.bytes(piece.bytes().data(), piece.bytes().size());
    index.bytes_of(piece);
  };
  BinaryWriter header;
  for (char c : kMagic) {
    header.u8(static_cast<std::uint8_t>(c));
  }
  header.u32(kCheckpointFormatVersion);
  header.u32(static_cast<std::uint32_t>(file.sections.size()));
  emit(header);
  for (const auto& [name, payload] : file.sections) {
    BinaryWriter before;
    before.string(name);
    before.u64(payload.size());
    emit(before);
    out.bytes(payload.data(), payload.size());
    BinaryWriter after;
    after.u64(checksum64(payload));
    emit(after);
  }
  BinaryWriter end;
  end.u64(checksum64(index.bytes()));
  out.bytes(end.bytes().data(), end.bytes().size());
  out.close();
}

CheckpointFile read_checkpoint_file(const std::string& path) {
  const std::string bytes = io_detail::read_file("checkpoint", path);
  BinaryReader in(bytes, "checkpoint file '" + path + "'");
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    in.fail(
        "not a tessera checkpoint (it does not begin with the magic number TSRCKPT; "
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
  std::string index(bytes.substr(0, in.offset() + 4));
  CheckpointFile file;
  const std::uint32_t count = in.u32("section count");
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::size_t begin = in.offset();
    std::string name = in.string("section name");
    const std::string field = "section '" + name + "'";
    std::string payload = in.string(field.c_str());
    index.append(bytes, begin, in.offset() - begin - payload.size());
    const std::size_t checksum_at = in.offset();
    if (in.u64((field + " checksum").c_str()) != checksum64(payload)) {
      in.fail("corrupt: " + field + " does not match its checksum (a byte was changed or lost)");
    }
    index.append(bytes, checksum_at, 8);
    file.sections.emplace_back(std::move(name), std::move(payload));
  }
  const std::uint64_t stored = in.u64("checksum");
  if (in.remaining() != 0) {
    in.fail("corrupt: " + std::to_string(in.remaining()) + " bytes after the checksum");
  }
  if (stored != checksum64(index)) {
    in.fail("corrupt: its checksum does not match its contents (a byte was changed or lost)");
  }
  return file;
}

FileFingerprint fingerprint_file(const std::string& path) {
  const std::string bytes = io_detail::read_file("problem", path);
  return {bytes.size(), checksum64(bytes)};
}

}  // namespace tessera
