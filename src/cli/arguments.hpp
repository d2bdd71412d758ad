#pragma once
/// The command-line conventions of seqmassage and the programs in tools/, on CLI11: numbers
/// checked against their range with messages naming the option, the help layout of
/// `seqmassage --help`, and usage errors reported one way (the message, a pointer to --help,
/// exit status 2).
#include <CLI/CLI.hpp>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace sm::cli {

/// The exit status of a usage error: a bad option or value, a missing or extra argument.
constexpr int kUsageExit = 2;

/// A usage error of `command` ("seqmassage", "seqmassage measure", "bench_massage").
struct UsageError {
  std::string command;
  std::string message;
};

/// The help (or the version) was printed: the program ends with status 0.
struct InfoShown {};

/// Sets up `app` the way every program here reads its arguments: "-h, --help" as its first
/// option, the last value of an option given twice wins, and the help laid out as
/// `seqmassage --help` is: the app's description, "Options:" (names, then each description from
/// `column` on; a '\n' in a description continues it at that column), the app's footer.
void set_conventions(CLI::App& app, size_t column);

/// Parses argv (argv[0] is the program or command). Prints the help, or the version of a
/// set_version_flag, on stdout and throws InfoShown; throws UsageError for an unknown option
/// ("unknown option '--x'"), an option without its value ("--threads needs a value N"), a value
/// a check refuses ("--threads: expected an integer in [0, 4096], got \"x\"") or an argument
/// that no option takes ("unexpected argument 'x'").
void parse(CLI::App& app, int argc, const char* const* argv);

/// Prints "COMMAND: MESSAGE" and "Try 'COMMAND --help'." on stderr; returns kUsageExit.
int report(const UsageError& error);

/// parse() for the programs of tools/: nothing when the program goes on, else the status to exit
/// with (0 after the help, kUsageExit after a usage error, reported).
std::optional<int> parse_or_exit(CLI::App& app, int argc, const char* const* argv);

/// Accepts an integer in [low, high] (decimal digits, an optional '-'), else "expected an integer
/// in [low, high], got \"VALUE\"". Give it with Option::transform, not check: it hands CLI11
/// the value without leading zeros, which CLI11 would read as octal.
CLI::Validator integer_in(long long low, long long high);

/// Accepts a finite number x with low < x < high (a bound may be infinite), else "expected a
/// number RANGE, got \"VALUE\"", `range` saying it in words ("> 0", "in (0, 180)"). With
/// Option::transform, as integer_in.
CLI::Validator number_in(double low, double high, const std::string& range);

/// Accepts one of `words`, else "expected \"a\" or \"b\", got \"VALUE\"" (as the config says it).
CLI::Validator one_of(std::vector<std::string> words);

}  // namespace sm::cli
