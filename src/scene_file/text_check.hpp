// SPDX-License-Identifier: MIT
// calder scene files: the checks on the raw text, before toml++ sees it.
//
// toml++ 3.3.0 (Debian 12) recurses once per part of a dotted key and per
// table, and overflows the stack on a key of tens of thousands of parts; it
// also reaches __builtin_unreachable when it asks whether some non-ASCII code
// points are whitespace (is_non_ascii_horizontal_whitespace, fixed upstream
// after 3.3.0). TOML 1.0 allows non-ASCII text only inside strings and
// comments, so refusing it elsewhere costs no valid file. This scanner knows
// just enough TOML (strings, comments, keys, brackets) to enforce the limits
// of docs/SCENES.md on the text itself:
//   - well-formed UTF-8, no other control characters than tab and line breaks;
//   - lines of at most kMaxLineBytes bytes;
//   - keys of at most kMaxKeyBytes bytes and nesting (key parts, tables and
//     arrays within each other) at most kMaxNesting deep;
//   - non-ASCII text only inside strings and comments, and never where
//     toml++ 3.3.0 would test it for whitespace (after a backslash).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace calder::scene_file_detail {

constexpr std::size_t kMaxFileBytes = std::size_t{4} << 20;  // 4 MiB
constexpr std::size_t kMaxLineBytes = 65536;
constexpr std::size_t kMaxKeyBytes = 256;
constexpr std::size_t kMaxNesting = 32;

struct TextProblem {
  std::size_t line = 1;
  std::size_t column = 1;
  std::string what;
};

// The code point of the UTF-8 sequence at text[i] and its length, or nullopt
// for a malformed one (overlong, surrogate, beyond U+10FFFF, cut short).
inline std::optional<std::pair<char32_t, std::size_t>> decode_utf8(std::string_view text,
                                                                   std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return std::pair<char32_t, std::size_t>{b0, 1};
  std::size_t length = 0;
  char32_t cp = 0;
  char32_t min = 0;
  if ((b0 & 0xE0) == 0xC0) {
    length = 2, cp = b0 & 0x1F, min = 0x80;
  } else if ((b0 & 0xF0) == 0xE0) {
    length = 3, cp = b0 & 0x0F, min = 0x800;
  } else if ((b0 & 0xF8) == 0xF0) {
    length = 4, cp = b0 & 0x07, min = 0x10000;
  } else {
    return std::nullopt;
  }
  if (i + length > text.size()) return std::nullopt;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return std::nullopt;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return std::nullopt;
  return std::pair<char32_t, std::size_t>{cp, length};
}

// The first problem of the text, if any (see above).
inline std::optional<TextProblem> check_text(std::string_view text) {
  enum class In { code, basic, literal, ml_basic, ml_literal, comment };
  In in = In::code;
  std::size_t line = 1;
  std::size_t line_start = 0;
  // Each open '[' or '{' of a value, with the nesting it adds (1 + the parts
  // of the key that led to it); a table header adds its parts.
  struct Open {
    char bracket;
    std::size_t depth;
  };
  std::vector<Open> open;
  std::size_t depth = 0;              // sum of the open entries' depths
  bool expect_key = true;             // at the start of a key-value or a header
  bool in_key = false;                // between a key's first character and its '=' or ']'
  bool in_header = false;             // the key is a [table] or [[array]] header
  std::size_t key_parts = 0;          // dots seen in the key so far, plus one
  std::size_t key_start = 0;          // byte offset of the key
  std::size_t value_key_parts = 0;    // parts of the key whose value comes next
  std::size_t header_parts = 0;       // parts of the last table header
  bool after_escape_newline = false;  // in a """ string, after a line-ending backslash

  const auto problem = [&](std::size_t at, std::string what) {
    return TextProblem{line, at - line_start + 1, std::move(what)};
  };
  const auto hex = [](char32_t cp) {
    static const char* digits = "0123456789ABCDEF";
    std::string s = "U+";
    const int width = cp > 0xFFFF ? 6 : 4;
    for (int shift = (width - 1) * 4; shift >= 0; shift -= 4) s += digits[(cp >> shift) & 0xF];
    return s;
  };
  const auto starts = [&](std::size_t i, std::string_view s) {
    return text.compare(i, s.size(), s) == 0;
  };

  for (std::size_t i = 0; i < text.size();) {
    const auto decoded = decode_utf8(text, i);
    if (!decoded) return problem(i, "the file is not valid UTF-8");
    const auto [cp, length] = *decoded;
    const char c = text[i];

    if (cp == '\n') {
      if (i - line_start > kMaxLineBytes) {
        return problem(line_start, "a line longer than " + std::to_string(kMaxLineBytes) +
                                       " bytes (the limit of scene files)");
      }
      ++line;
      line_start = i + 1;
      if (in == In::basic || in == In::literal || in == In::comment) in = In::code;
      if (in == In::code && open.empty()) {
        expect_key = true;
        in_key = false;
        in_header = false;
      }
      ++i;
      continue;
    }
    if (cp < 0x20 && cp != '\t' && cp != '\r') {
      return problem(i, "control character " + hex(cp) + " (only tab and line breaks may appear)");
    }
    if (cp == 0x7F) return problem(i, "control character U+007F");

    switch (in) {
      case In::comment:
        break;
      case In::literal:
        if (c == '\'') in = In::code;
        break;
      case In::ml_literal:
        if (starts(i, "'''")) {
          i += 3;
          while (i < text.size() && text[i] == '\'') ++i;
          in = In::code;
          continue;
        }
        break;
      case In::basic:
      case In::ml_basic:
        if (after_escape_newline && cp != ' ' && cp != '\t' && cp != '\r') {
          after_escape_newline = false;
          if (cp >= 0x80) {
            return problem(i, "non-ASCII text right after a line-ending backslash");
          }
        }
        if (c == '\\') {
          if (i + 1 < text.size()) {
            const unsigned char next = static_cast<unsigned char>(text[i + 1]);
            if (next >= 0x80) return problem(i, "a backslash before non-ASCII text");
            if (in == In::ml_basic &&
                (next == ' ' || next == '\t' || next == '\n' || next == '\r')) {
              after_escape_newline = true;
            }
          }
          // The escaped character is ASCII (checked above); a line break
          // stays to be counted.
          i += i + 1 < text.size() && text[i + 1] == '\n' ? std::size_t{1} : std::size_t{2};
          continue;
        }
        if (in == In::ml_basic && starts(i, "\"\"\"")) {
          i += 3;
          while (i < text.size() && text[i] == '"') ++i;
          in = In::code;
          after_escape_newline = false;
          continue;
        }
        if (in == In::basic && c == '"') in = In::code;
        break;
      case In::code: {
        if (cp >= 0x80) {
          return problem(i, "non-ASCII character " + hex(cp) +
                                " outside a string or comment (TOML allows it only there)");
        }
        if (c == ' ' || c == '\t' || c == '\r') break;
        if (c == '#') {
          in = In::comment;
          break;
        }
        if (expect_key && !in_key) {
          // A key-value or, at the top level, a table header begins here.
          in_key = true;
          key_parts = 1;
          key_start = i;
          in_header = false;
          if (c == '[' && open.empty()) {
            in_header = true;
            i += starts(i, "[[") ? std::size_t{2} : std::size_t{1};
            key_start = i;
            continue;
          }
        }
        if (in_key) {
          if (c == '.') ++key_parts;
          const bool key_ends = in_header ? c == ']' : c == '=';
          // The key's bytes so far: through this character, or up to the
          // '=' or ']' without the spaces before it (a quoted key included).
          std::size_t key_end = key_ends ? i : i + 1;
          while (key_ends && key_end > key_start &&
                 (text[key_end - 1] == ' ' || text[key_end - 1] == '\t')) {
            --key_end;
          }
          if (key_end - key_start > kMaxKeyBytes) {
            return problem(key_start, "a key longer than " + std::to_string(kMaxKeyBytes) +
                                          " bytes (the limit of scene files)");
          }
          if ((in_header || !open.empty() ? 0 : header_parts) + depth + key_parts > kMaxNesting) {
            return problem(key_start, "keys, tables and arrays nested more than " +
                                          std::to_string(kMaxNesting) +
                                          " deep (the limit of scene files)");
          }
          if (key_ends) {
            in_key = false;
            expect_key = false;
            value_key_parts = key_parts;
            if (in_header) {
              header_parts = key_parts;
              value_key_parts = 0;
              in_header = false;
              i += starts(i, "]]") ? std::size_t{2} : std::size_t{1};
              continue;
            }
          }
        } else if (c == '[' || c == '{') {
          const std::size_t adds = (open.empty() ? header_parts : 0) + value_key_parts + 1;
          value_key_parts = 0;
          open.push_back({c, adds});
          depth += adds;
          if (depth > kMaxNesting) {
            return problem(i, "keys, tables and arrays nested more than " +
                                  std::to_string(kMaxNesting) + " deep (the limit of scene files)");
          }
          expect_key = c == '{';
        } else if ((c == ']' || c == '}') && !open.empty()) {
          depth -= open.back().depth;
          open.pop_back();
          expect_key = false;
        } else if (c == ',' && !open.empty() && open.back().bracket == '{') {
          expect_key = true;
        }
        if (c == '"' || c == '\'') {
          const bool triple = starts(i, c == '"' ? "\"\"\"" : "'''");
          in = c == '"' ? (triple ? In::ml_basic : In::basic)
                        : (triple ? In::ml_literal : In::literal);
          i += triple ? std::size_t{3} : std::size_t{1};
          continue;
        }
        break;
      }
    }
    i += length;
  }
  if (text.size() - line_start > kMaxLineBytes) {
    return problem(line_start, "a line longer than " + std::to_string(kMaxLineBytes) +
                                   " bytes (the limit of scene files)");
  }
  return std::nullopt;
}

}  // namespace calder::scene_file_detail
