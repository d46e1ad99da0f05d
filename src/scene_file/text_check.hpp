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
#include <utility>
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

// Scans a text once, character by character, for its first problem (see above).
class TextScanner {
 public:
  explicit TextScanner(std::string_view text) : text_(text) {}

  std::optional<TextProblem> first_problem() {
    while (i_ < text_.size()) {
      const auto decoded = decode_utf8(text_, i_);
      if (!decoded) return problem(i_, "the file is not valid UTF-8");
      const auto [cp, length] = *decoded;
      if (cp == '\n') {
        if (auto p = line_break()) return p;
        continue;
      }
      if (cp < 0x20 && cp != '\t' && cp != '\r') {
        return problem(i_,
                       "control character " + hex(cp) + " (only tab and line breaks may appear)");
      }
      if (cp == 0x7F) return problem(i_, "control character U+007F");
      moved_ = false;
      if (auto p = character(cp)) return p;
      if (!moved_) i_ += length;
    }
    if (text_.size() - line_start_ > kMaxLineBytes) return line_too_long();
    return std::nullopt;
  }

 private:
  enum class In { code, basic, literal, ml_basic, ml_literal, comment };
  // Each open '[' or '{' of a value, with the nesting it adds (1 + the parts
  // of the key that led to it); a table header adds its parts.
  struct Open {
    char bracket;
    std::size_t depth;
  };

  [[nodiscard]] TextProblem problem(std::size_t at, std::string what) const {
    return TextProblem{line_, at - line_start_ + 1, std::move(what)};
  }
  [[nodiscard]] TextProblem line_too_long() const {
    return problem(line_start_, "a line longer than " + std::to_string(kMaxLineBytes) +
                                    " bytes (the limit of scene files)");
  }
  [[nodiscard]] TextProblem too_deep(std::size_t at) const {
    return problem(at, "keys, tables and arrays nested more than " + std::to_string(kMaxNesting) +
                           " deep (the limit of scene files)");
  }
  static std::string hex(char32_t cp) {
    static const char* digits = "0123456789ABCDEF";
    std::string s = "U+";
    const int width = cp > 0xFFFF ? 6 : 4;
    for (int shift = (width - 1) * 4; shift >= 0; shift -= 4) s += digits[(cp >> shift) & 0xF];
    return s;
  }
  [[nodiscard]] bool starts(std::string_view s) const {
    return text_.compare(i_, s.size(), s) == 0;
  }
  // Moves past n bytes (the step takes care of the position itself).
  void skip(std::size_t n) {
    i_ += n;
    moved_ = true;
  }

  std::optional<TextProblem> line_break() {
    if (i_ - line_start_ > kMaxLineBytes) return line_too_long();
    ++line_;
    line_start_ = i_ + 1;
    if (in_ == In::basic || in_ == In::literal || in_ == In::comment) in_ = In::code;
    if (in_ == In::code && open_.empty()) {
      expect_key_ = true;
      in_key_ = false;
      in_header_ = false;
    }
    ++i_;
    return std::nullopt;
  }

  // Any character but a line break or a control character.
  std::optional<TextProblem> character(char32_t cp) {
    switch (in_) {
      case In::comment:
        break;
      case In::literal:
        if (text_[i_] == '\'') in_ = In::code;
        break;
      case In::ml_literal:
        if (starts("'''")) close_multiline('\'');
        break;
      case In::basic:
      case In::ml_basic:
        return in_basic_string(cp);
      case In::code:
        return in_code(cp);
    }
    return std::nullopt;
  }

  // Past the closing quotes of a multi-line string (and quotes just before them).
  void close_multiline(char quote) {
    skip(3);
    while (i_ < text_.size() && text_[i_] == quote) ++i_;
    in_ = In::code;
  }

  std::optional<TextProblem> in_basic_string(char32_t cp) {
    const char c = text_[i_];
    if (after_escape_newline_ && cp != ' ' && cp != '\t' && cp != '\r') {
      after_escape_newline_ = false;
      if (cp >= 0x80) return problem(i_, "non-ASCII text right after a line-ending backslash");
    }
    if (c == '\\') {
      if (i_ + 1 < text_.size()) {
        const unsigned char next = static_cast<unsigned char>(text_[i_ + 1]);
        if (next >= 0x80) return problem(i_, "a backslash before non-ASCII text");
        if (in_ == In::ml_basic && (next == ' ' || next == '\t' || next == '\n' || next == '\r')) {
          after_escape_newline_ = true;
        }
      }
      // The escaped character is ASCII (checked above); a line break stays to be counted.
      skip(i_ + 1 < text_.size() && text_[i_ + 1] == '\n' ? std::size_t{1} : std::size_t{2});
      return std::nullopt;
    }
    if (in_ == In::ml_basic && starts("\"\"\"")) {
      close_multiline('"');
      after_escape_newline_ = false;
      return std::nullopt;
    }
    if (in_ == In::basic && c == '"') in_ = In::code;
    return std::nullopt;
  }

  std::optional<TextProblem> in_code(char32_t cp) {
    const char c = text_[i_];
    if (cp >= 0x80) {
      return problem(i_, "non-ASCII character " + hex(cp) +
                             " outside a string or comment (TOML allows it only there)");
    }
    if (c == ' ' || c == '\t' || c == '\r') return std::nullopt;
    if (c == '#') {
      in_ = In::comment;
      return std::nullopt;
    }
    if (expect_key_ && !in_key_ && begin_key(c)) return std::nullopt;
    if (in_key_) {
      if (auto p = key_character(c)) return p;
      if (moved_) return std::nullopt;
    } else {
      if (auto p = bracket_or_comma(c)) return p;
    }
    if (c == '"' || c == '\'') {
      const bool triple = starts(c == '"' ? "\"\"\"" : "'''");
      in_ =
          c == '"' ? (triple ? In::ml_basic : In::basic) : (triple ? In::ml_literal : In::literal);
      skip(triple ? std::size_t{3} : std::size_t{1});
    }
    return std::nullopt;
  }

  // A key-value or, at the top level, a table header begins here; true when
  // it is a header (then the scanner is past its brackets).
  bool begin_key(char c) {
    in_key_ = true;
    key_parts_ = 1;
    key_start_ = i_;
    in_header_ = false;
    if (c != '[' || !open_.empty()) return false;
    in_header_ = true;
    skip(starts("[[") ? std::size_t{2} : std::size_t{1});
    key_start_ = i_;
    return true;
  }

  std::optional<TextProblem> key_character(char c) {
    if (c == '.') ++key_parts_;
    const bool key_ends = in_header_ ? c == ']' : c == '=';
    // The key's bytes so far: through this character, or up to the '=' or
    // ']' without the spaces before it (a quoted key included).
    std::size_t key_end = key_ends ? i_ : i_ + 1;
    while (key_ends && key_end > key_start_ &&
           (text_[key_end - 1] == ' ' || text_[key_end - 1] == '\t')) {
      --key_end;
    }
    if (key_end - key_start_ > kMaxKeyBytes) {
      return problem(key_start_, "a key longer than " + std::to_string(kMaxKeyBytes) +
                                     " bytes (the limit of scene files)");
    }
    if ((in_header_ || !open_.empty() ? 0 : header_parts_) + depth_ + key_parts_ > kMaxNesting) {
      return too_deep(key_start_);
    }
    if (!key_ends) return std::nullopt;
    in_key_ = false;
    expect_key_ = false;
    value_key_parts_ = key_parts_;
    if (in_header_) {
      header_parts_ = key_parts_;
      value_key_parts_ = 0;
      in_header_ = false;
      skip(starts("]]") ? std::size_t{2} : std::size_t{1});
    }
    return std::nullopt;
  }

  std::optional<TextProblem> bracket_or_comma(char c) {
    if (c == '[' || c == '{') {
      const std::size_t adds = (open_.empty() ? header_parts_ : 0) + value_key_parts_ + 1;
      value_key_parts_ = 0;
      open_.push_back({c, adds});
      depth_ += adds;
      if (depth_ > kMaxNesting) return too_deep(i_);
      expect_key_ = c == '{';
    } else if ((c == ']' || c == '}') && !open_.empty()) {
      depth_ -= open_.back().depth;
      open_.pop_back();
      expect_key_ = false;
    } else if (c == ',' && !open_.empty() && open_.back().bracket == '{') {
      expect_key_ = true;
    }
    return std::nullopt;
  }

  std::string_view text_;
  std::size_t i_ = 0;   // byte offset of the character being scanned
  bool moved_ = false;  // the step moved i_ itself
  In in_ = In::code;
  std::size_t line_ = 1;
  std::size_t line_start_ = 0;
  std::vector<Open> open_;
  std::size_t depth_ = 0;              // sum of the open entries' depths
  bool expect_key_ = true;             // at the start of a key-value or a header
  bool in_key_ = false;                // between a key's first character and its '=' or ']'
  bool in_header_ = false;             // the key is a [table] or [[array]] header
  std::size_t key_parts_ = 0;          // dots seen in the key so far, plus one
  std::size_t key_start_ = 0;          // byte offset of the key
  std::size_t value_key_parts_ = 0;    // parts of the key whose value comes next
  std::size_t header_parts_ = 0;       // parts of the last table header
  bool after_escape_newline_ = false;  // in a """ string, after a line-ending backslash
};

// The first problem of the text, if any (see above).
inline std::optional<TextProblem> check_text(std::string_view text) {
  return TextScanner(text).first_problem();
}

}  // namespace calder::scene_file_detail
