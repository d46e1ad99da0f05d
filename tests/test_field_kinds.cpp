// SPDX-License-Identifier: MIT
// The places outside the field kinds' headers that name them agree with
// the kinds' descriptions (FieldKind<F>, the Field variant): the field table
// of docs/SCENES.md lists every kind a scene file can hold, once; README.md,
// python/README.md and calder/bulk.hpp name only kinds that exist, and
// bulk.hpp's exceptions are the kinds without a law. A kind added, renamed or
// removed without its docs fails here.
#include <gtest/gtest.h>

#include <cctype>
#include <cstddef>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <variant>

#include "../src/field_kinds/laws.hpp"  // HasLaw: the kinds with a law
#include "calder/fields.hpp"

namespace {

// "edge_force" -> "EdgeForce": the C++ struct's and the Python class's name.
std::string class_name(const std::string& name) {
  std::string out;
  bool upper = true;
  for (const char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

struct Kinds {
  std::set<std::string> classes;         // every kind
  std::set<std::string> in_scene_files;  // by name
  std::set<std::string> without_law;     // classes
};

template <class... Fs>
Kinds kinds_of(const std::variant<Fs...>*) {
  Kinds k;
  (
      [&] {
        const std::string name = calder::FieldKind<Fs>::name;
        k.classes.insert(class_name(name));
        if (calder::in_scene_files<Fs>()) k.in_scene_files.insert(name);
        if (!calder::HasLaw<Fs>) k.without_law.insert(class_name(name));
      }(),
      ...);
  return k;
}

const Kinds& kinds() {
  static const Kinds k = kinds_of(static_cast<const calder::Field*>(nullptr));
  return k;
}

std::string read(const std::string& relative) {
  std::ifstream in(std::string(CALDER_SOURCE_DIR) + "/" + relative);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The text from `start` (included) to `end` (excluded) in file; fails when
// either is missing.
std::string between(const std::string& file, const std::string& start, const std::string& end) {
  const std::string text = read(file);
  const std::size_t a = text.find(start);
  EXPECT_NE(a, std::string::npos) << file << ": no \"" << start << "\"";
  if (a == std::string::npos) return "";
  const std::size_t b = text.find(end, a + start.size());
  EXPECT_NE(b, std::string::npos) << file << ": no \"" << end << "\" after \"" << start << "\"";
  return text.substr(a, b == std::string::npos ? std::string::npos : b - a);
}

// The words of text that look like a kind's class name (capitalised, with a
// lower-case letter, not a file name), and that are one or end in Force,
// Attraction, Wind: what a list of kinds would hold.
std::set<std::string> capitalised_words(const std::string& text) {
  std::set<std::string> words;
  std::string word;
  const auto flush = [&] {
    if (!word.empty() && std::isupper(static_cast<unsigned char>(word[0])) != 0) words.insert(word);
    word.clear();
  };
  for (const char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_') {
      word += c;
    } else {
      flush();
    }
  }
  flush();
  return words;
}

// Every capitalised word of text that names no kind but looks like one.
void expect_only_kinds(const std::string& where, const std::string& text) {
  for (const std::string& word : capitalised_words(text)) {
    const bool kind_like = word.ends_with("Force") || word.ends_with("Attraction") ||
                           word.ends_with("Wind") || word == "Gravity" || word == "Drag" ||
                           word == "Lift" || word == "Liquid" || word == "Fan" ||
                           word == "Helium" || word == "Friction" || word == "Attractor";
    if (kind_like) {
      EXPECT_TRUE(kinds().classes.contains(word)) << where << " names " << word;
    }
  }
}

TEST(FieldKindDocs, ScenesTableHasARowForEveryKindInSceneFiles) {
  const std::string table = between("docs/SCENES.md", "| `type` | keys (default) |", "\n\n");
  std::set<std::string> rows;
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("| `")) continue;
    const std::size_t end = line.find('`', 3);
    const std::string name = line.substr(3, end - 3);
    EXPECT_TRUE(rows.insert(name).second) << "docs/SCENES.md: two rows for " << name;
  }
  rows.erase("type");
  EXPECT_EQ(rows, kinds().in_scene_files);
}

TEST(FieldKindDocs, ReadmesNameOnlyKindsThatExist) {
  const std::string readme = between("README.md", "| fields (`fields.hpp`) |", "\n");
  EXPECT_TRUE(readme.find("docs/SCENES.md") != std::string::npos);
  expect_only_kinds("README.md", readme);
  const std::string python = between("python/README.md", "every field", "the force laws");
  EXPECT_TRUE(python.find("docs/SCENES.md") != std::string::npos);
  expect_only_kinds("python/README.md", python);
  expect_only_kinds("docs/API.md", between("docs/API.md", "## Fields", "## Randomness"));
}

TEST(FieldKindDocs, BulkHeaderNamesTheKindsWithoutALaw) {
  const std::string what = between("include/calder/bulk.hpp", "What they run:", "\n//\n");
  expect_only_kinds("include/calder/bulk.hpp", what);
  for (const std::string& kind : kinds().without_law) {
    EXPECT_NE(what.find(kind), std::string::npos)
        << "calder/bulk.hpp doesn't say " << kind << " has no kernel";
  }
  EXPECT_EQ(kinds().without_law, (std::set<std::string>{"CustomForce", "MutualAttraction"}));
}

// The names the docs and Python use are the structs' (FieldKind::name in
// CamelCase), checked on two kinds with underscores.
TEST(FieldKindDocs, ClassNamesComeFromTheKindNames) {
  EXPECT_EQ(class_name(calder::FieldKind<calder::EdgeForce>::name), "EdgeForce");
  EXPECT_EQ(class_name(calder::FieldKind<calder::MutualAttraction>::name), "MutualAttraction");
  EXPECT_EQ(kinds().classes.size(), std::variant_size_v<calder::Field>);
}

}  // namespace
