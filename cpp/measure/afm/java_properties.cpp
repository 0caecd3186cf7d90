// Parser of Java .properties text (the format of java.util.Properties.load).
#include "java_properties.hpp"

#include <cstdint>

namespace coatcontact::afm::detail {

namespace {

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out.push_back(static_cast<char>(code));
  } else if (code < 0x800) {
    out.push_back(static_cast<char>(0xc0 | (code >> 6)));
    out.push_back(static_cast<char>(0x80 | (code & 0x3f)));
  } else {
    out.push_back(static_cast<char>(0xe0 | (code >> 12)));
    out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3f)));
    out.push_back(static_cast<char>(0x80 | (code & 0x3f)));
  }
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Logical lines: continuation (an odd number of trailing backslashes) joins the next line
// without its leading blanks.
std::string next_logical_line(const std::string& text, std::size_t& pos) {
  std::string line;
  bool continued = true;
  bool first = true;
  while (continued && pos < text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    std::size_t start = pos;
    if (!first) {
      while (start < end && (text[start] == ' ' || text[start] == '\t' || text[start] == '\f')) ++start;
    }
    std::string piece = text.substr(start, end - start);
    pos = end;
    if (pos < text.size() && text[pos] == '\r') ++pos;
    if (pos < text.size() && text[pos] == '\n') ++pos;
    std::size_t backslashes = 0;
    while (backslashes < piece.size() && piece[piece.size() - 1 - backslashes] == '\\') ++backslashes;
    continued = backslashes % 2 == 1;
    if (continued) piece.pop_back();
    line += piece;
    first = false;
  }
  return line;
}

std::string unescape(const std::string& raw) {
  if (raw.find('\\') == std::string::npos) return raw;
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const char c = raw[i];
    if (c != '\\' || i + 1 >= raw.size()) {
      out.push_back(c);
      continue;
    }
    const char e = raw[++i];
    switch (e) {
      case 't': out.push_back('\t'); break;
      case 'n': out.push_back('\n'); break;
      case 'r': out.push_back('\r'); break;
      case 'f': out.push_back('\f'); break;
      case 'u': {
        std::uint32_t code = 0;
        bool ok = i + 4 < raw.size();
        for (std::size_t k = 1; ok && k <= 4; ++k) {
          const int h = hex_value(raw[i + k]);
          if (h < 0) ok = false;
          code = code * 16 + static_cast<std::uint32_t>(h < 0 ? 0 : h);
        }
        if (ok) {
          append_utf8(out, code);
          i += 4;
        } else {
          out.push_back('u');
        }
        break;
      }
      default: out.push_back(e);
    }
  }
  return out;
}

}  // namespace

Properties parse_properties(const std::string& text) {
  Properties properties;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::string line = next_logical_line(text, pos);
    std::size_t i = 0;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\f')) ++i;
    if (i >= line.size() || line[i] == '#' || line[i] == '!') continue;
    // The key ends at the first unescaped '=', ':' or blank.
    std::size_t key_end = i;
    while (key_end < line.size()) {
      const char c = line[key_end];
      if (c == '\\') {
        key_end += 2;
        continue;
      }
      if (c == '=' || c == ':' || c == ' ' || c == '\t' || c == '\f') break;
      ++key_end;
    }
    if (key_end > line.size()) key_end = line.size();
    std::size_t value_start = key_end;
    while (value_start < line.size() && (line[value_start] == ' ' || line[value_start] == '\t' || line[value_start] == '\f')) ++value_start;
    if (value_start < line.size() && (line[value_start] == '=' || line[value_start] == ':')) {
      ++value_start;
      while (value_start < line.size() && (line[value_start] == ' ' || line[value_start] == '\t' || line[value_start] == '\f')) ++value_start;
    }
    properties[unescape(line.substr(i, key_end - i))] = unescape(line.substr(value_start));
  }
  return properties;
}

}  // namespace coatcontact::afm::detail
