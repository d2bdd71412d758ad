// The command-line conventions of seqmassage and tools/ (cli/arguments): numbers checked against
// their range with messages naming the option, unknown options, missing values and stray
// arguments as usage errors, the last of a repeated option winning, and the help layout.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>
#include <sstream>

#include "cli/arguments.hpp"

namespace {

// A small program: --count N in [0, 4096], --ratio X > 0, --kind a|b, --sizes LIST, -q.
struct Program {
  CLI::App app{"Usage: prog [options]\n", "prog"};
  int count = -1;
  double ratio = 0.25;
  std::string kind;
  std::vector<int> sizes = {1};
  bool quiet = false;

  Program() {
    sm::cli::set_conventions(app, 18);
    app.add_option("--count", count, "how many")->type_name("N")->transform(sm::cli::integer_in(0, 4096));
    app.add_option("--ratio", ratio, "a ratio,\ncontinued")
        ->type_name("X")
        ->transform(sm::cli::number_in(0, INFINITY, "> 0"));
    app.add_option("--kind", kind, "a or b")->type_name("K")->check(sm::cli::one_of({"a", "b"}));
    app.add_option("--sizes", sizes, "sizes")
        ->type_name("A,B,...")
        ->delimiter(',')
        ->transform(sm::cli::integer_in(1, 100));
    app.add_flag("-q,--quiet", quiet, "quiet");
  }

  // The usage error's message for these arguments, "" when they parse.
  std::string error(const std::vector<std::string>& args) {
    std::vector<const char*> argv{"prog"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    try {
      sm::cli::parse(app, int(argv.size()), argv.data());
    } catch (const sm::cli::UsageError& e) {
      CHECK(e.command == "prog");
      return e.message;
    }
    return "";
  }
};

}  // namespace

TEST_CASE("integers are decimal and checked against their range") {
  Program p;
  CHECK(p.error({"--count", "12"}) == "");
  CHECK(p.count == 12);
  CHECK(p.error({"--count=010"}) == "");
  CHECK(p.count == 10);  // not octal
  CHECK(p.error({"--count", "0", "--count", "4096"}) == "");
  CHECK(p.count == 4096);  // the last one wins
  for (const char* bad : {"4097", "many", "1.5", "0x10", "", "99999999999999999999999"})
    CHECK(Program().error({"--count", bad}) ==
          "--count: expected an integer in [0, 4096], got \"" + std::string(bad) + "\"");
  CHECK(Program().error({"--count", "-1"}) ==
        "--count: expected an integer in [0, 4096], got \"-1\"");
}

TEST_CASE("numbers are finite and inside their range") {
  Program p;
  CHECK(p.error({"--ratio", "0.5"}) == "");
  CHECK(p.ratio == 0.5);
  CHECK(p.error({"--ratio=1e-3"}) == "");
  CHECK(p.ratio == 1e-3);
  for (const char* bad : {"0", "-2", "inf", "nan", "1e999", "0.5x", "x"})
    CHECK(Program().error({"--ratio", bad}) ==
          "--ratio: expected a number > 0, got \"" + std::string(bad) + "\"");
}

TEST_CASE("words, lists, unknown options, missing values and stray arguments") {
  Program p;
  CHECK(p.error({"--kind", "b", "--sizes", "3,4,5", "-q"}) == "");
  CHECK(p.kind == "b");
  CHECK(p.sizes == std::vector<int>{3, 4, 5});
  CHECK(p.quiet);
  CHECK(Program().error({"--kind", "c"}) == "--kind: expected \"a\" or \"b\", got \"c\"");
  CHECK(Program().error({"--sizes", "3,0"}) ==
        "--sizes: expected an integer in [1, 100], got \"0\"");
  CHECK(Program().error({"--bogus"}) == "unknown option '--bogus'");
  CHECK(Program().error({"--bogus=3"}) == "unknown option '--bogus=3'");
  CHECK(Program().error({"-x"}) == "unknown option '-x'");
  CHECK(Program().error({"--quite"}) == "unknown option '--quite' (did you mean \"--quiet\"?)");
  CHECK(Program().error({"--cont=3"}) ==
        "unknown option '--cont=3' (did you mean \"--count\"?)");
  CHECK(Program().error({"--count"}) == "--count needs a value N");
  CHECK(Program().error({"stray"}) == "unexpected argument 'stray'");
}

TEST_CASE("a usage error is reported with a pointer to --help, exit status 2") {
  std::ostringstream err;
  std::streambuf* const saved = std::cerr.rdbuf(err.rdbuf());
  const int code = sm::cli::report({"prog sub", "unknown option '--x'"});
  std::cerr.rdbuf(saved);
  CHECK(code == 2);
  CHECK(err.str() == "prog sub: unknown option '--x'\nTry 'prog sub --help'.\n");
}

TEST_CASE("the help: description, the options from their definitions, footer") {
  Program p;
  p.app.footer("Exit status: 0.\n");
  const std::string expected =
      "Usage: prog [options]\n"
      "\n"
      "Options:\n"
      "  -h, --help      print this help and exit\n"
      "      --count N   how many\n"
      "      --ratio X   a ratio,\n"
      "                  continued\n"
      "      --kind K    a or b\n"
      "      --sizes A,B,...\n"
      "                  sizes\n"
      "  -q, --quiet     quiet\n"
      "\n"
      "Exit status: 0.\n";
  CHECK(p.app.help() == expected);
  std::ostringstream out;
  std::streambuf* const saved = std::cout.rdbuf(out.rdbuf());
  const char* help[] = {"prog", "-h", "stray"};
  CHECK_THROWS_AS(sm::cli::parse(p.app, 3, help), sm::cli::InfoShown);
  std::cout.rdbuf(saved);
  CHECK(out.str() == expected);
}

TEST_CASE("positional arguments, also after --, are not options") {
  CLI::App app{"Usage: prog FILE...\n", "prog"};
  sm::cli::set_conventions(app, 16);
  std::vector<std::string> files;
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "quiet");
  app.add_option("FILE", files);
  const char* argv[] = {"prog", "a", "-q", "--", "-b", "--quiet"};
  sm::cli::parse(app, 6, argv);
  CHECK(files == std::vector<std::string>{"a", "-b", "--quiet"});
  CHECK(quiet);
  CHECK(app.help() ==
        "Usage: prog FILE...\n\nOptions:\n  -h, --help    print this help and exit\n"
        "  -q, --quiet   quiet\n");
}
