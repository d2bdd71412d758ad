#pragma once
/// Words for messages: the nearest known word to a typo ("did you mean"), and a quoted list of
/// the words that are accepted. Shared by the config reader (io/options_json.hpp) and the command
/// line (cli/arguments.hpp), so that both suggest and list alike.
#include <string>
#include <string_view>
#include <vector>

namespace sm {

/// Optimal string alignment distance between two strings: insertions, deletions, substitutions
/// and adjacent transpositions each count one.
int edit_distance(std::string_view a, std::string_view b);

/// ` (did you mean "x"?)` for the candidate nearest to `word` (ignoring case), if it is near
/// enough to be a typo (1 edit up to 3 letters, 2 up to 8, 3 beyond); "" otherwise.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

/// `"a"`, `"a" or "b"`, `"a", "b", or "c"`.
std::string quoted_list(const std::vector<std::string>& words);

}  // namespace sm
