// SPDX-License-Identifier: MIT
#include "tessera/io/detail/xml_document.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/ply_header.h"

namespace tessera::io_detail {

namespace {

constexpr int kMaxDepth = 64;  // VTU nests 5 deep; bounds the work on hostile files

}  // namespace

const std::string* XmlElement::attribute(std::string_view key) const {
  for (const auto& [name, value] : attributes) {
    if (name == key) {
      return &value;
    }
  }
  return nullptr;
}

XmlDocument::XmlDocument(std::string_view format, const std::string& content,
                         const std::string& path)
    : format_(format), text_(content), path_(path) {
  parse();
}

void XmlDocument::fail(std::size_t line, const std::string& message) const {
  throw_file_error(format_, path_, line, message);
}

void XmlDocument::fail(const std::string& message) const { fail(line_, message); }

void XmlDocument::advance(std::size_t count) {
  const std::size_t end = std::min(position_ + count, text_.size());
  line_ +=
      static_cast<std::size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(position_),
                                          text_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
  position_ = end;
}

bool XmlDocument::at(std::string_view prefix) const {
  return text_.substr(position_, prefix.size()) == prefix;
}

// Moves past the next `terminator`; false if there is none.
bool XmlDocument::skip_past(std::string_view terminator) {
  const std::size_t end = text_.find(terminator, position_);
  if (end == std::string_view::npos) {
    return false;
  }
  advance(end + terminator.size() - position_);
  return true;
}

void XmlDocument::skip_space() {
  while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) {
    advance(1);
  }
}

std::string XmlDocument::name() {
  const std::size_t begin = position_;
  while (position_ < text_.size()) {
    const char c = text_[position_];
    if (std::isspace(static_cast<unsigned char>(c)) || c == '=' || c == '>' || c == '/' ||
        c == '<' || c == '"' || c == '\'') {
      break;
    }
    ++position_;
  }
  if (position_ == begin) {
    fail("expected a name, found " + quoted_excerpt(text_.substr(position_, 20)));
  }
  return std::string(text_.substr(begin, position_ - begin));
}

std::string XmlDocument::unescaped(std::string_view value) const {
  std::string out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (value[i] != '&') {
      out += value[i];
      continue;
    }
    const std::size_t end = value.find(';', i);
    if (end == std::string_view::npos) {
      fail("an '&' without ';' in an attribute value");
    }
    const std::string_view entity = value.substr(i + 1, end - i - 1);
    static constexpr std::pair<std::string_view, char> kEntities[] = {
        {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
    bool known = false;
    for (const auto& [entity_name, character] : kEntities) {
      if (entity == entity_name) {
        out += character;
        known = true;
      }
    }
    if (!known && entity.size() >= 2 && entity[0] == '#') {
      const bool hex = entity[1] == 'x' || entity[1] == 'X';
      const std::string_view digits = entity.substr(hex ? 2 : 1);
      unsigned code = 0;
      const auto [ptr, error] =
          std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
      if (error == std::errc() && ptr == digits.data() + digits.size() && code > 0 && code < 128) {
        out += static_cast<char>(code);
        known = true;
      }
    }
    if (!known) {
      fail("unsupported entity " + quoted_excerpt(value.substr(i, end - i + 1)) +
           " in an attribute value");
    }
    i = end;
  }
  return out;
}

void XmlDocument::parse() {
  std::vector<std::size_t> open;  // indices of the elements not yet closed
  while (true) {
    const std::size_t text_begin = position_;
    const std::size_t text_line = line_;
    const std::size_t next = text_.find('<', position_);
    const std::size_t text_end = next == std::string_view::npos ? text_.size() : next;
    if (!open.empty()) {
      XmlElement& parent = elements_[open.back()];
      if (parent.text.empty() && text_end > text_begin) {
        parent.text = text_.substr(text_begin, text_end - text_begin);
        parent.text_line = text_line;
      }
    } else if (text_.substr(text_begin, text_end - text_begin).find_first_not_of(" \t\r\n") !=
               std::string_view::npos) {
      fail("text outside the root element");
    }
    advance(text_end - position_);
    if (position_ >= text_.size()) {
      break;
    }
    if (at("<?")) {
      if (!skip_past("?>")) {
        fail("unterminated '<?'");
      }
    } else if (at("<!--")) {
      advance(4);  // "<!-->" is not a whole comment: its "-->" starts inside "<!--"
      const std::size_t begin = position_;
      if (!skip_past("-->")) {
        fail("unterminated comment");
      }
      comments_.emplace_back(text_.substr(begin, position_ - 3 - begin));
    } else if (at("<!")) {
      fail("DTD and CDATA sections are not supported");
    } else if (at("</")) {
      advance(2);
      const std::string closing = name();
      skip_space();
      if (!at(">")) {
        fail("expected '>' after '</" + closing + "'");
      }
      advance(1);
      if (open.empty() || elements_[open.back()].name != closing) {
        fail("closing tag '</" + closing + ">' does not match " +
             (open.empty() ? std::string("any open element")
                           : "'<" + elements_[open.back()].name + ">'"));
      }
      open.pop_back();
      if (open.empty()) {
        break;
      }
    } else {
      start_element(open);
      if (open.empty()) {
        break;  // an empty root element
      }
    }
  }
  if (elements_.empty()) {
    fail("no root element");
  }
  if (!open.empty()) {
    fail("unexpected end of file: '<" + elements_[open.back()].name + ">' is not closed");
  }
}

void XmlDocument::start_element(std::vector<std::size_t>& open) {
  if (!elements_.empty() && open.empty()) {
    fail("a second root element");
  }
  if (open.size() >= static_cast<std::size_t>(kMaxDepth)) {
    fail("elements nested deeper than " + std::to_string(kMaxDepth));
  }
  advance(1);
  XmlElement element;
  element.line = line_;
  element.name = name();
  while (true) {
    skip_space();
    if (position_ >= text_.size()) {
      fail("unexpected end of file in '<" + element.name + "'");
    }
    if (at("/>") || at(">")) {
      break;
    }
    std::string key = name();
    skip_space();
    if (!at("=")) {
      fail("expected '=' after attribute '" + key + "'");
    }
    advance(1);
    skip_space();
    if (!at("\"") && !at("'")) {
      fail("expected a quoted value for attribute '" + key + "'");
    }
    const char quote = text_[position_];
    const std::size_t end = text_.find(quote, position_ + 1);
    if (end == std::string_view::npos) {
      fail("unterminated value of attribute '" + key + "'");
    }
    std::string value = unescaped(text_.substr(position_ + 1, end - position_ - 1));
    advance(end + 1 - position_);
    element.attributes.emplace_back(std::move(key), std::move(value));
  }
  const bool is_empty = at("/>");
  advance(is_empty ? 2 : 1);
  const std::size_t index = elements_.size();
  if (!open.empty()) {
    elements_[open.back()].children.push_back(index);
  }
  elements_.push_back(std::move(element));
  if (!is_empty) {
    open.push_back(index);
  }
}

}  // namespace tessera::io_detail
