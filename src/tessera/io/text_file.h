// SPDX-License-Identifier: MIT
// Whole text files (JSON summaries, reports) written with the same atomic replacement as meshes.
#pragma once

#include <string>
#include <string_view>

namespace tessera {

/// Writes `content` to `path`: into a temporary file in the same folder, synced, then renamed
/// over `path`, so that a failure (disk full, no permission, a kill) never leaves a truncated
/// file; on failure a file already at `path` is unchanged and no temporary is left.
///
/// \param what  the kind of file, named in error messages ("JSON summary").
/// \throw InvalidArgument "<what> file '<path>': <reason>" if the file cannot be written.
void write_text_file(const std::string& path, std::string_view content,
                     std::string_view what = "text");

/// `text` with & < > " ' replaced by XML's entities: for attribute values and comments of VTU
/// files and the titles of SVG pictures.
std::string xml_escaped(std::string_view text);

/// `text` fit for an XML comment, which may not hold "--": each "--" becomes "- -" (a recorded
/// command line `tessera improve … --criterion angle` stays readable).
std::string xml_comment_text(std::string_view text);

}  // namespace tessera
