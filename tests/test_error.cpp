// SPDX-License-Identifier: MIT
// Errors by kind (calder/error.hpp): what each check throws, and context added
// without changing the kind.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calder/error.hpp"
#include "calder/scene.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::Error;
using calder::InputError;
using calder::InvalidArgument;
using calder::RunError;

// The message of `error` rethrown with `context`, caught as Kind.
template <typename Kind>
std::string rethrown_as(const Error& error, const char* context) {
  try {
    calder::rethrow_with_context(error, context);
  } catch (const Kind& e) {
    return e.what();
  } catch (const Error& e) {
    ADD_FAILURE() << "the kind changed: " << e.what();
  }
  return {};
}

TEST(ErrorKinds, EveryKindIsACalderError) {
  EXPECT_THROW(throw InvalidArgument("a"), Error);
  EXPECT_THROW(throw InputError("b"), Error);
  EXPECT_THROW(throw RunError("c"), Error);
  EXPECT_THROW(throw RunError("c"), std::invalid_argument);  // as calder::Error always was
}

TEST(ErrorKinds, RejectedArgumentsAreInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(calder::detail::require_finite(nan, "f", "x"), InvalidArgument);
  EXPECT_THROW(calder::detail::require_positive(0.0, "f", "mass"), InvalidArgument);
  EXPECT_THROW(calder::detail::require_non_negative(-1.0, "f", "radius"), InvalidArgument);
  calder::test::expect_error([] { calder::detail::require_positive(-2.0, "World", "dt"); },
                             {"World: dt must be > 0 (got -2)"});
  calder::World world;
  EXPECT_THROW((void)world.add_mover({.mass = 0.0}), InvalidArgument);
}

TEST(ErrorKinds, ContextKeepsTheKindAndPrefixesTheMessage) {
  EXPECT_EQ(rethrown_as<RunError>(RunError("body 3 is NaN"), "rain: frame 7: "),
            "rain: frame 7: body 3 is NaN");
  EXPECT_EQ(rethrown_as<InputError>(InputError("bad"), "a.toml: "), "a.toml: bad");
  EXPECT_EQ(rethrown_as<InvalidArgument>(InvalidArgument("mass"), "x: "), "x: mass");
  // A plain Error stays a plain Error: none of the kinds.
  try {
    calder::rethrow_with_context(Error("plain"), "where: ");
  } catch (const RunError&) {
    ADD_FAILURE() << "became a RunError";
  } catch (const InputError&) {
    ADD_FAILURE() << "became an InputError";
  } catch (const InvalidArgument&) {
    ADD_FAILURE() << "became an InvalidArgument";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "where: plain");
  }
}

TEST(ErrorKinds, SceneValidationKeepsTheFieldsKind) {
  calder::Scene scene;
  scene.name = "s";
  scene.fields.push_back({calder::Friction{.mu = -1.0}, {}});
  try {
    scene.validate();
    ADD_FAILURE() << "expected an error";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("scene s: fields[0]: "), std::string::npos) << e.what();
  }
}

// The "did you mean" search: a typo is one edit in a word of up to 3
// characters, two in a longer one (insertions, deletions, substitutions,
// swaps of neighbours); case alone is no edit.
TEST(DidYouMean, FindsTheCandidateWithinTheWordsEditLimit) {
  using calder::detail::closest;
  const std::vector<std::string_view> fields = {"gravity", "drag", "friction", "wind", "fan"};
  EXPECT_EQ(closest("gravty", fields), "gravity");    // one deletion
  EXPECT_EQ(closest("GRAVITY", fields), "gravity");   // case only
  EXPECT_EQ(closest("grvaity", fields), "gravity");   // neighbours swapped: one edit
  EXPECT_EQ(closest("dargg", fields), "drag");        // a swap and an insertion: two
  EXPECT_EQ(closest("fricton", fields), "friction");  // one deletion in a long word
  EXPECT_EQ(closest("fam", fields), "fan");           // one substitution in a short word
  EXPECT_EQ(closest("wnd", fields), "wind");
  // Ties go to the first candidate in the list.
  EXPECT_EQ(closest("cat", {"bat", "hat"}), "bat");
}

TEST(DidYouMean, RefusesWhatIsNoTypo) {
  using calder::detail::closest;
  const std::vector<std::string_view> fields = {"gravity", "drag", "friction", "wind", "fan"};
  EXPECT_EQ(closest("fxx", fields), std::nullopt);        // two edits in a short word
  EXPECT_EQ(closest("gxavxtx", fields), std::nullopt);    // three edits
  EXPECT_EQ(closest("grav", {"gravity"}), std::nullopt);  // three letters short
  EXPECT_EQ(closest("x", {"y"}), std::nullopt);           // as many edits as letters
  EXPECT_EQ(closest("", fields), std::nullopt);
  EXPECT_EQ(closest("gravity", {}), std::nullopt);
  // A word of a megabyte is refused by its length, before any table is made.
  EXPECT_EQ(closest(std::string(1 << 20, 'g'), fields), std::nullopt);
}

}  // namespace
