// SPDX-License-Identifier: MIT
#include "tessera/picture/detail/svg_compaction.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace tessera::picture_detail {

namespace {

using Attributes = std::vector<std::pair<std::string, std::string>>;

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\n\r");
  if (first == std::string::npos) {
    return "";
  }
  const auto last = text.find_last_not_of(" \t\n\r");
  return text.substr(first, last - first + 1);
}

bool is_blank(const std::string& text) { return trimmed(text).empty(); }

// The attributes of an element's text between its name and "/>"; nullopt where the text is not
// a plain list of name="value" (or name='value').
std::optional<Attributes> parse_attributes(const std::string& text) {
  Attributes attributes;
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) {
      ++i;
    }
    if (i == text.size()) {
      return attributes;
    }
    const auto equals = text.find('=', i);
    if (equals == std::string::npos || equals + 1 >= text.size()) {
      return std::nullopt;
    }
    const char quote = text[equals + 1];
    if (quote != '"' && quote != '\'') {
      return std::nullopt;
    }
    const auto close = text.find(quote, equals + 2);
    if (close == std::string::npos) {
      return std::nullopt;
    }
    attributes.emplace_back(trimmed(text.substr(i, equals - i)),
                            text.substr(equals + 2, close - equals - 2));
    i = close + 1;
  }
}

// "rgb(17.49%,0.33%,21.56%)" → "#2d0137"; anything else as it is.
std::string short_colour(const std::string& value) {
  if (value.rfind("rgb(", 0) != 0 || value.find('%') == std::string::npos) {
    return value;
  }
  const char* p = value.c_str() + 4;
  int channels[3];
  for (int& channel : channels) {
    char* end = nullptr;
    const double percent = std::strtod(p, &end);
    if (end == p) {
      return value;
    }
    channel = static_cast<int>(std::lround(std::clamp(percent, 0.0, 100.0) * 255.0 / 100.0));
    p = end;
    while (*p == '%' || *p == ',' || *p == ' ') {
      ++p;
    }
  }
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", channels[0], channels[1], channels[2]);
  return text;
}

// A number rounded to `decimals` places, without trailing zeros: 325, 333.6, -0.5.
std::string rounded(double value, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string s = text;
  if (s.find('.') != std::string::npos) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') {
      s.pop_back();
    }
  }
  if (s == "-0") {
    s = "0";
  }
  return s;
}

// A length in tenths as SVG path data writes it shortest: 3256 → "325.6", -5 → "-.5", 0 → "0".
std::string tenths_text(long long tenths) {
  std::string text = tenths < 0 ? "-" : "";
  const long long magnitude = tenths < 0 ? -tenths : tenths;
  if (magnitude >= 10 || magnitude == 0) {
    text += std::to_string(magnitude / 10);
  }
  if (magnitude % 10 != 0) {
    text += '.';
    text += static_cast<char>('0' + magnitude % 10);
  }
  return text;
}

// Path data of absolute M, L, C and Z commands rewritten to 0.1: the first point absolute, the
// rest relative (l, c), which is shorter for the small shapes of a picture; no move-to after a
// final close-path (cairo writes "Z M x y", the current point after the close: no drawing).
// nullopt for data with other commands or that does not parse.
std::optional<std::string> compact_path_data(const std::string& d) {
  struct Command {
    char letter;
    std::vector<long long> tenths;
  };
  std::vector<Command> commands;
  std::size_t i = 0;
  while (i < d.size()) {
    const char c = d[i];
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
      ++i;
    } else if (c == 'M' || c == 'L' || c == 'C' || c == 'Z') {
      commands.push_back({c, {}});
      ++i;
    } else {
      char* end = nullptr;
      const double value = std::strtod(d.c_str() + i, &end);
      if (end == d.c_str() + i || commands.empty() || !std::isfinite(value) ||
          std::abs(value) > 1e12) {
        return std::nullopt;
      }
      commands.back().tenths.push_back(std::llround(value * 10.0));
      i = static_cast<std::size_t>(end - d.c_str());
    }
  }
  while (commands.size() >= 2 && commands.back().letter == 'M' &&
         commands[commands.size() - 2].letter == 'Z') {
    commands.pop_back();
  }
  std::string out;
  long long x = 0, y = 0, start_x = 0, start_y = 0;
  char previous = 0;
  auto number = [&](long long tenths) {
    const std::string text = tenths_text(tenths);
    const char last = out.empty() ? ' ' : out.back();
    if (std::isdigit(static_cast<unsigned char>(last)) || last == '.') {
      if (text[0] != '-') {
        out += ' ';
      }
    }
    out += text;
  };
  for (const Command& command : commands) {
    const std::size_t count = command.tenths.size();
    const std::size_t arity = command.letter == 'C' ? 6 : command.letter == 'Z' ? 0 : 2;
    if ((arity == 0 && count != 0) || (arity > 0 && (count == 0 || count % arity != 0))) {
      return std::nullopt;
    }
    if (command.letter == 'Z') {
      out += 'z';
      x = start_x, y = start_y;
      previous = 'z';
      continue;
    }
    for (std::size_t at = 0; at < count; at += arity) {
      const auto* p = &command.tenths[at];
      if (command.letter == 'M' && at == 0) {
        out += 'M';
        number(p[0]);
        number(p[1]);
        x = start_x = p[0];
        y = start_y = p[1];
        previous = 'M';
        continue;
      }
      const char letter = command.letter == 'C' ? 'c' : 'l';  // M's further pairs are lines
      if (previous != letter) {
        out += letter;
      }
      for (std::size_t k = 0; k < arity; k += 2) {
        number(p[k] - x);
        number(p[k + 1] - y);
      }
      x = p[arity - 2];
      y = p[arity - 1];
      previous = letter;
    }
  }
  return out;
}

// The presentation attributes SVG 1.1 defines that cairo writes into styles, and their
// defaults (empty: none to leave out).
const std::map<std::string, std::string>& presentation_defaults() {
  static const std::map<std::string, std::string> defaults = {{"fill", ""},
                                                              {"fill-opacity", "1"},
                                                              {"fill-rule", "nonzero"},
                                                              {"stroke", "none"},
                                                              {"stroke-opacity", "1"},
                                                              {"stroke-width", "1"},
                                                              {"stroke-linecap", "butt"},
                                                              {"stroke-linejoin", "miter"},
                                                              {"stroke-miterlimit", "4"},
                                                              {"stroke-dasharray", "none"},
                                                              {"stroke-dashoffset", "0"},
                                                              {"opacity", "1"}};
  return defaults;
}

struct CompactPath {
  Attributes attributes;  // everything but d, in the order written
  std::string d;
  bool is_mergeable = false;  // filled with the nonzero rule, not stroked or in the fill's colour
};

// Inherited presentation attributes that a <g> may hold for its paths.
bool is_inherited(const std::string& name) {
  return name != "opacity" && presentation_defaults().count(name) > 0;
}

std::optional<CompactPath> compact_path(const std::string& element_attributes) {
  const auto parsed = parse_attributes(element_attributes);
  if (!parsed) {
    return std::nullopt;
  }
  Attributes properties;  // presentation attributes, from the style and the element
  Attributes others;
  std::string style_rest;
  std::optional<std::string> d;
  auto set = [&](const std::string& name, const std::string& value) {
    for (auto& [key, old] : properties) {
      if (key == name) {
        old = value;
        return;
      }
    }
    properties.emplace_back(name, value);
  };
  for (const auto& [name, value] : *parsed) {
    if (name == "d") {
      d = value;
    } else if (name == "style") {
      std::size_t start = 0;
      while (start < value.size()) {
        auto end = value.find(';', start);
        if (end == std::string::npos) {
          end = value.size();
        }
        const std::string declaration = value.substr(start, end - start);
        const auto colon = declaration.find(':');
        if (colon != std::string::npos) {
          const std::string key = trimmed(declaration.substr(0, colon));
          const std::string property = trimmed(declaration.substr(colon + 1));
          if (presentation_defaults().count(key)) {
            set(key, property);
          } else if (!key.empty()) {
            style_rest += key + ":" + property + ";";
          }
        }
        start = end + 1;
      }
    } else if (presentation_defaults().count(name)) {
      set(name, value);
    } else {
      others.emplace_back(name, value);
    }
  }
  if (!d) {
    return std::nullopt;
  }
  const auto data = compact_path_data(*d);
  if (!data) {
    return std::nullopt;
  }
  std::map<std::string, std::string> values;
  for (auto& [name, value] : properties) {
    if (name == "fill" || name == "stroke") {
      value = short_colour(value);
    } else if (name == "stroke-width" || name == "stroke-miterlimit" ||
               name == "stroke-dashoffset") {
      value = rounded(std::strtod(value.c_str(), nullptr), 2);
    }
    values[name] = value;
  }
  const bool is_stroked = values.count("stroke") && values["stroke"] != "none";
  const bool is_miter = !values.count("stroke-linejoin") || values["stroke-linejoin"] == "miter";
  // A shape stroked in its fill's colour (a triangle whose stroke closes the seams to its
  // neighbours) names the colour once: color, with fill and stroke currentColor, which a group
  // can hold for a run of such shapes.
  const bool is_one_colour = is_stroked && values.count("fill") && values["fill"][0] == '#' &&
                             values["fill"] == values["stroke"];
  CompactPath path;
  path.d = *data;
  if (is_one_colour) {
    path.attributes.emplace_back("color", values["fill"]);
  }
  for (const auto& [name, value] : properties) {
    const std::string& fallback = presentation_defaults().at(name);
    const bool is_stroke_property = name.rfind("stroke-", 0) == 0;
    if (value == fallback || (is_stroke_property && !is_stroked) ||
        (name == "stroke-miterlimit" && !is_miter)) {
      continue;
    }
    path.attributes.emplace_back(
        name, is_one_colour && (name == "fill" || name == "stroke") ? "currentColor" : value);
  }
  for (const auto& attribute : others) {
    path.attributes.push_back(attribute);
  }
  if (!style_rest.empty()) {
    path.attributes.emplace_back("style", style_rest);
  }
  auto is_default = [&](const std::string& name) {
    return !values.count(name) || values[name] == presentation_defaults().at(name);
  };
  const bool is_plain = others.empty() && style_rest.empty() && is_default("opacity") &&
                        is_default("fill-opacity") && is_default("stroke-opacity") &&
                        is_default("stroke-dasharray");
  path.is_mergeable = is_plain && (!is_stroked || is_one_colour) &&
                      (!values.count("fill-rule") || values["fill-rule"] == "nonzero");
  return path;
}

std::string attributes_text(const Attributes& attributes) {
  std::string text;
  for (const auto& [name, value] : attributes) {
    text += " " + name + "=\"" + value + "\"";
  }
  return text;
}

// The inherited attributes of `path` that are also in `of`.
Attributes shared(const Attributes& of, const CompactPath& path) {
  Attributes common;
  for (const auto& attribute : of) {
    if (is_inherited(attribute.first) && std::find(path.attributes.begin(), path.attributes.end(),
                                                   attribute) != path.attributes.end()) {
      common.push_back(attribute);
    }
  }
  return common;
}

void write_path(const CompactPath& path, const Attributes& inherited, std::string& out) {
  Attributes own;
  for (const auto& attribute : path.attributes) {
    if (std::find(inherited.begin(), inherited.end(), attribute) == inherited.end()) {
      own.push_back(attribute);
    }
  }
  out += "<path" + attributes_text(own) + " d=\"" + path.d + "\"/>\n";
}

// Consecutive paths, each stretch that shares attributes (those its first two share) in a
// group that holds them, where the stretch is long enough to gain (the triangles of a surface
// share their stroke width and join, and fill and stroke in currentColor).
void write_run(const std::vector<CompactPath>& run, std::string& out) {
  constexpr std::size_t kMinGroup = 4;
  std::size_t i = 0;
  while (i < run.size()) {
    Attributes common = i + 1 < run.size() ? shared(run[i].attributes, run[i + 1]) : Attributes();
    std::size_t end = i + 1;
    if (!common.empty()) {
      while (end < run.size() && shared(common, run[end]).size() == common.size()) {
        ++end;
      }
    }
    if (end - i < kMinGroup || common.empty()) {
      write_path(run[i], {}, out);
      ++i;
      continue;
    }
    out += "<g" + attributes_text(common) + ">\n";
    for (std::size_t k = i; k < end; ++k) {
      write_path(run[k], common, out);
    }
    out += "</g>\n";
    i = end;
  }
}

}  // namespace

std::string compact_svg(const std::string& svg) {
  auto body = svg.find("</defs>");
  if (body == std::string::npos) {
    body = svg.find("<svg");
  }
  if (body == std::string::npos) {
    return svg;
  }
  std::string out = svg.substr(0, body);
  std::vector<CompactPath> run;  // consecutive paths, the last one open to merging
  auto flush = [&] {
    write_run(run, out);
    run.clear();
  };
  // Text between the paths, without the line break that follows the last path written.
  auto append = [&](const std::string& text) {
    out += !out.empty() && out.back() == '\n' && !text.empty() && text[0] == '\n' ? text.substr(1)
                                                                                  : text;
  };
  std::size_t position = body;
  while (true) {
    const auto start = svg.find("<path", position);
    const auto close = start == std::string::npos ? start : svg.find('>', start);
    if (close == std::string::npos) {
      flush();
      append(svg.substr(position));
      return out;
    }
    const std::string between = svg.substr(position, start - position);
    const bool is_self_closing = svg[close - 1] == '/';
    const auto path =
        is_self_closing ? compact_path(svg.substr(start + 5, close - 1 - start - 5)) : std::nullopt;
    if (!is_blank(between) || !path) {
      flush();
      append(between);
    }
    if (!path) {
      out += svg.substr(start, close + 1 - start);
    } else if (!run.empty() && run.back().is_mergeable && path->is_mergeable &&
               run.back().attributes == path->attributes) {
      run.back().d += path->d;
    } else {
      run.push_back(*path);
    }
    position = close + 1;
  }
}

}  // namespace tessera::picture_detail
