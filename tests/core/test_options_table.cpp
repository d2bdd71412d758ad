// Options tables (core/options_table.hpp): the references a table gives to a struct's members,
// enum names, and check_ranges for options built in code.
#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "core/frame_selection.hpp"
#include "core/options_table.hpp"

namespace {

enum class Color { Red, Green };
constexpr sm::EnumName<Color> kColorNames[] = {{"red", Color::Red}, {"green", Color::Green}};

struct Inner {
  double weight = 0.5;
};

struct Example {
  int count = 3;
  Color color = Color::Green;
  std::optional<double> scale;
  Inner inner;
};

}  // namespace

template <>
const sm::Fields<Inner>& sm::fields_of<Inner>() {
  static const Fields<Inner> fields = {field<&Inner::weight>("weight", open(0, 1), "a weight")};
  return fields;
}

template <>
const sm::Fields<Example>& sm::fields_of<Example>() {
  static const Fields<Example> fields = {
      field<&Example::count>("count", closed(1, 10), "how many"),
      field<&Example::color>("color", choice(kColorNames), "which colour"),
      field<&Example::scale>("scale", above(0), "a scale"),
      field<&Example::inner>("inner", any_value(), "nested"),
  };
  return fields;
}

using namespace sm;

TEST_CASE("a table's entries reach the members, by type") {
  Example e;
  const Entries entries = entries_of(e);
  REQUIRE(entries.size() == 4);
  CHECK(entries[0].info->key == "count");
  **std::get_if<int*>(&entries[0].value) = 7;
  CHECK(e.count == 7);
  const ChoiceRef& color = std::get<ChoiceRef>(entries[1].value);
  CHECK(color.get(color.value) == static_cast<int>(Color::Green));
  color.set(color.value, static_cast<int>(Color::Red));
  CHECK(e.color == Color::Red);
  CHECK(std::holds_alternative<std::optional<double>*>(entries[2].value));
  const ObjectRef& inner = std::get<ObjectRef>(entries[3].value);
  CHECK(inner.mode == ObjectRef::Mode::Plain);
  **std::get_if<double*>(&inner.entries(inner.target)[0].value) = 0.25;
  CHECK(e.inner.weight == 0.25);
  CHECK(name_of(Color::Green, kColorNames) == "green");
}

TEST_CASE("check_ranges names the first value out of its table's range") {
  Example e;
  CHECK_NOTHROW(check_ranges(e, "example"));
  e.count = 11;
  CHECK_THROWS_WITH(check_ranges(e, "example"),
                    "example.count: expected an integer in [1, 10], got 11");
  e.count = 1;
  e.scale = 0.0;
  CHECK_THROWS_WITH(check_ranges(e, "example"), "example.scale: expected a number > 0, got 0");
  e.scale.reset();
  e.inner.weight = 1.0;
  CHECK_THROWS_WITH(check_ranges(e, "example"),
                    "example.inner.weight: expected a number in (0, 1), got 1");
  e.inner.weight = NAN;
  CHECK_THROWS_AS(check_ranges(e, "example"), ConfigError);
}

TEST_CASE("check_option_ranges names the member and leaves the path to the caller") {
  Example e;
  CHECK_NOTHROW(check_option_ranges(e));
  e.inner.weight = 1.0;
  try {
    check_option_ranges(e);
    FAIL("no OptionError");
  } catch (const OptionError& error) {
    CHECK(error.key() == "inner.weight");
    CHECK(error.reason() == "expected a number in (0, 1), got 1");
    CHECK(error.under("outer").key() == "outer.inner.weight");
  }
  // The caller that knows the path: the config's words, as a ConfigError.
  CHECK_THROWS_AS(with_option_path("job.example", [&] { check_option_ranges(e); }), ConfigError);
  CHECK_THROWS_WITH(with_option_path("job.example", [&] { check_option_ranges(e); }),
                    "job.example.inner.weight: expected a number in (0, 1), got 1");
  CHECK_THROWS_WITH(with_option_path("", [&] { check_option_ranges(e); }),
                    "inner.weight: expected a number in (0, 1), got 1");
  CHECK(with_option_path("x", [] { return 7; }) == 7);
}
