// The words of messages: edit distance, the "did you mean" suggestion and quoted lists, as the
// config reader and the command line use them.
#include <catch2/catch.hpp>

#include "core/spelling.hpp"

using sm::did_you_mean;
using sm::edit_distance;
using sm::quoted_list;

TEST_CASE("edit distance") {
  CHECK(edit_distance("iterations", "iteratons") == 1);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("kitten", "sitting") == 3);
  CHECK(edit_distance("same", "same") == 0);
  CHECK(edit_distance("strat", "start") == 1);  // a transposition counts once
}

TEST_CASE("did you mean: the nearest candidate, if near enough to be a typo") {
  const std::vector<std::string> keys{"iterations", "lambda", "mu", "weights"};
  CHECK(did_you_mean("iteratons", keys) == " (did you mean \"iterations\"?)");
  CHECK(did_you_mean("Lambda", keys) == " (did you mean \"lambda\"?)");  // case is ignored
  CHECK(did_you_mean("nu", keys) == " (did you mean \"mu\"?)");
  CHECK(did_you_mean("xyz", keys) == "");  // 3 letters: 1 edit at most
  CHECK(did_you_mean("wieghts", keys) == " (did you mean \"weights\"?)");
  CHECK(did_you_mean("anything", {}) == "");
  // The limit grows with the word: 2 edits up to 8 letters, 3 beyond.
  CHECK(did_you_mean("lmbd", keys) == " (did you mean \"lambda\"?)");
  CHECK(did_you_mean("itrtions", keys) == " (did you mean \"iterations\"?)");
  CHECK(did_you_mean("wgts", keys) == "");
}

TEST_CASE("quoted lists") {
  CHECK(quoted_list({}) == "");
  CHECK(quoted_list({"a"}) == "\"a\"");
  CHECK(quoted_list({"a", "b"}) == "\"a\" or \"b\"");
  CHECK(quoted_list({"a", "b", "c"}) == "\"a\", \"b\", or \"c\"");
}
