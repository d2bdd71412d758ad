#include "cli/arguments.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "core/spelling.hpp"

namespace sm::cli {

namespace {

// The help of an app: description, options (long names, short ones first), footer.
class HelpLayout : public CLI::FormatterBase {
 public:
  std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode) const override {
    std::string out = app->get_description() + "\nOptions:\n";
    for (const CLI::Option* option : app->get_options())
      if (option->nonpositional()) out += line(*option);
    const std::string footer = app->get_footer();
    return footer.empty() ? out : out + "\n" + footer;
  }

 private:
  // "  -q, --quiet           DESCRIPTION" or "      --threads N       DESCRIPTION"
  std::string line(const CLI::Option& option) const {
    std::string names;
    for (const std::string& s : option.get_snames()) names += "-" + s + ", ";
    if (names.empty()) names = "    ";
    for (const std::string& l : option.get_lnames()) names += "--" + l + ", ";
    names.resize(names.size() - 2);
    const std::string type = option.get_type_name();
    if (!type.empty()) names += " " + type;
    std::string out = "  " + names;
    const size_t column = get_column_width();
    out += out.size() + 2 > column ? "\n" + std::string(column, ' ')
                                   : std::string(column - out.size(), ' ');
    for (const char c : option.get_description())
      out += c == '\n' ? "\n" + std::string(column, ' ') : std::string(1, c);
    return out + "\n";
  }
};

// "--threads needs a value N" from CLI11's "--threads: 1 required N missing".
std::string missing_value(const CLI::App& app, const std::string& what) {
  const std::string name = what.substr(0, what.find(':'));
  const CLI::Option* option = app.get_option_no_throw(name);
  if (!option || what.find(" required ") == std::string::npos) return what;
  const std::string type = option->get_type_name();
  return name + " needs a value" + (type.empty() ? "" : " " + type);
}

// "unknown option '--thread' (did you mean "--threads"?)", the suggestion among `app`'s long
// options, as the config suggests among its keys.
std::string unknown_option(const CLI::App& app, const std::string& extra) {
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options())
    for (const std::string& l : option->get_lnames()) names.push_back("--" + l);
  const std::string given = extra.substr(0, extra.find('='));
  return "unknown option '" + extra + "'" + (given.size() > 2 ? did_you_mean(given, names) : "");
}

}  // namespace

void set_conventions(CLI::App& app, size_t column) {
  app.set_help_flag("-h,--help", "print this help and exit");
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  auto layout = std::make_shared<HelpLayout>();
  layout->column_width(column);
  app.formatter(layout);
}

void parse(CLI::App& app, int argc, const char* const* argv) {
  app.allow_extras();  // reported below, in this project's words
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    throw InfoShown{};
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what();
    throw InfoShown{};
  } catch (const CLI::ArgumentMismatch& e) {
    throw UsageError{app.get_name(), missing_value(app, e.what())};
  } catch (const CLI::ParseError& e) {
    throw UsageError{app.get_name(), e.what()};
  }
  for (const std::string& extra : app.remaining()) {
    if (extra == "--") continue;  // the end of the options, kept by CLI11 among the extras
    const bool option = extra.size() > 1 && extra[0] == '-';
    throw UsageError{app.get_name(),
                     option ? unknown_option(app, extra) : "unexpected argument '" + extra + "'"};
  }
}

int report(const UsageError& error) {
  std::cerr << error.command << ": " << error.message << "\nTry '" << error.command
            << " --help'.\n";
  return kUsageExit;
}

std::optional<int> parse_or_exit(CLI::App& app, int argc, const char* const* argv) {
  try {
    parse(app, argc, argv);
  } catch (const InfoShown&) {
    return 0;
  } catch (const UsageError& e) {
    return report(e);
  }
  return std::nullopt;
}

CLI::Validator integer_in(long long low, long long high) {
  const std::string range = "[" + std::to_string(low) + ", " + std::to_string(high) + "]";
  return CLI::Validator(
      [=](std::string& value) -> std::string {
        const size_t digits = value.rfind('-', 0) == 0 ? 1 : 0;
        if (value.size() > digits && value.size() <= digits + 18 &&
            value.find_first_not_of("0123456789", digits) == std::string::npos) {
          const long long x = std::stoll(value);
          if (x >= low && x <= high) {
            value = std::to_string(x);  // CLI11 reads "010" as octal: hand it "10"
            return {};
          }
        }
        return "expected an integer in " + range + ", got \"" + value + "\"";
      },
      "");
}

CLI::Validator number_in(double low, double high, const std::string& range) {
  return CLI::Validator(
      [=](std::string& value) -> std::string {
        errno = 0;
        char* end = nullptr;
        const double x = value.empty() ? NAN : std::strtod(value.c_str(), &end);
        if (errno == 0 && end == value.c_str() + value.size() && std::isfinite(x) && x > low &&
            x < high) {
          char exact[32];
          std::snprintf(exact, sizeof exact, "%.17g", x);  // what CLI11 converts, as checked
          value = exact;
          return {};
        }
        return "expected a number " + range + ", got \"" + value + "\"";
      },
      "");
}

CLI::Validator one_of(std::vector<std::string> words) {
  const std::string expected = quoted_list(words);
  return CLI::Validator(
      [=](std::string& value) -> std::string {
        for (const std::string& word : words)
          if (value == word) return {};
        return "expected " + expected + ", got \"" + value + "\"";
      },
      "");
}

}  // namespace sm::cli
