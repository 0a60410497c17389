// SPDX-License-Identifier: MIT
// Internal to the io layer: a small XML reader for what VTK writes (.vtu), bounds-checked for
// hostile input, with the line of every element for error messages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tessera::io_detail {

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;  ///< values unescaped
  std::string_view text;  ///< character data directly inside (its first run), a view of the input
  std::size_t text_line = 0;          ///< line (from 1) where `text` starts
  std::size_t line = 0;               ///< line of the start tag
  std::vector<std::size_t> children;  ///< indices into the document's elements, in file order

  /// The value of attribute `key`, or nullptr.
  const std::string* attribute(std::string_view key) const;
};

/// Elements, attributes, character data, comments and the declaration; no DTD, no CDATA, no
/// namespaces; entities: the five predefined and &#...; for ASCII. Nesting deeper than 64 is
/// refused, so hostile input cannot exhaust memory beyond its own size.
class XmlDocument {
 public:
  /// Parses `content` (which must outlive the document: texts are views of it).
  /// \throw InvalidArgument "<format> file '<path>', line <L>: ..." if it is not well formed.
  XmlDocument(std::string_view format, const std::string& content, const std::string& path);

  const XmlElement& root() const { return elements_.front(); }
  /// \pre index comes from XmlElement::children of this document.
  const XmlElement& element(std::size_t index) const { return elements_[index]; }
  /// The text of every comment, in file order.
  const std::vector<std::string>& comments() const { return comments_; }
  /// \throw InvalidArgument naming the file and `line`.
  [[noreturn]] void fail(std::size_t line, const std::string& message) const;

 private:
  [[noreturn]] void fail(const std::string& message) const;
  void advance(std::size_t count);
  bool at(std::string_view prefix) const;
  bool skip_past(std::string_view terminator);
  void skip_space();
  std::string name();
  std::string unescaped(std::string_view value) const;
  void parse();
  void start_element(std::vector<std::size_t>& open);

  std::string_view format_;
  std::string_view text_;
  const std::string& path_;
  std::size_t position_ = 0;
  std::size_t line_ = 1;
  std::vector<XmlElement> elements_;
  std::vector<std::string> comments_;
};

}  // namespace tessera::io_detail
