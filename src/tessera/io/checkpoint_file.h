// SPDX-License-Identifier: MIT
// Checkpoint files (.tsc): named binary sections behind a magic number and a format version,
// closed by a checksum, replaced atomically. What goes into the sections is the caller's
// (`tessera mesh --checkpoint`: the command, the problem file's hash, the atlas's state).
//
// Layout, little-endian:
//   8 bytes  magic "TSRCKPT\x1a"
//   u32      format version (kCheckpointFormatVersion)
//   u32      section count
//   per section: u64 name length, name, u64 payload length, payload, u64 checksum64(payload)
//   u64      checksum64 of the header and of every section's name, length and checksum
// (A checksum per section, so that a payload of hundreds of MB is written straight from the
// caller's memory, not copied into one buffer first.)
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

inline constexpr std::uint32_t kCheckpointFormatVersion = 1;

struct CheckpointFile {
  std::vector<std::pair<std::string, std::string>> sections;  ///< (name, payload) in order

  /// The payload of section `name`. \throw InvalidArgument naming `path` if there is none.
  const std::string& section(const std::string& name, const std::string& path) const;
};

/// Writes `file` to `path` through a temporary in the same folder, synced before it is renamed
/// over `path` (io/detail/file_buffer.h's OutputFile): a kill leaves the old file or the new
/// one, never a part. \throw InvalidArgument naming `path` and the system's reason.
void write_checkpoint_file(const std::string& path, const CheckpointFile& file);

/// Reads and checks a checkpoint file: the magic number, the format version, every section's
/// length against the bytes left, and the checksum.
/// \throw InvalidArgument "checkpoint file 'PATH': ..." naming what is wrong (not a checkpoint,
///        another version, truncated, corrupt).
CheckpointFile read_checkpoint_file(const std::string& path);

/// The size and checksum64 of a file's bytes: what a checkpoint keeps of its problem file.
struct FileFingerprint {
  std::uint64_t size = 0;
  std::uint64_t checksum = 0;
  bool operator==(const FileFingerprint&) const = default;
};
/// \throw InvalidArgument naming `path` if it cannot be read.
FileFingerprint fingerprint_file(const std::string& path);

}  // namespace tessera
