#pragma once
/// Options structs described as data. Beside each options struct S, `fields_of<S>()` lists one
/// Field per JSON key: the key, the member, what values it takes (a range, an enum's names), a
/// one-line doc, and whether the key is required; the default is the member's own (that of a
/// default-constructed S). The config reader and writer (io/options_json.hpp), the reference
/// documentation (`seqmassage config --reference`) and check_ranges all read these tables, so a
/// key is declared once. Nothing here depends on JSON.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "core/enum_names.hpp"
#include "core/errors.hpp"

namespace sm {

struct FrameSelection;  // core/frame_selection.hpp

/// What a key accepts beyond its type (which the member's type gives).
struct ValueSpec {
  /// Integers, numbers and every item of an integer list: the allowed interval.
  double lo = -INFINITY, hi = INFINITY;
  bool lo_open = false, hi_open = false;
  std::string_view lo_key;  ///< an integer: at least the value of this sibling key
  std::string_view hi_key;  ///< an integer: below the value of this sibling key
  std::vector<std::pair<std::string_view, int>> names;  ///< an enum: its names and values
  bool auto_word = false;  ///< an optional number: "auto", not null, stands for "no value"
  std::string_view items;  ///< an integer list: what its items are ("vertex indices")

  bool contains(double x) const {
    return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
};

/// The interval of `spec` alone: "[0, 4096]", ">= 1" (integers, hi infinite or not); "> 0",
/// "(0, 1]" (numbers). Integers are closed, their bounds whole.
std::string interval_text(const ValueSpec& spec, bool integer);
/// "an integer >= 1" (hi infinite), "an integer in [0, 4096]".
std::string describe_integers(double lo, double hi);
/// "a number > 0", "a number in [0, 1)".
std::string describe_numbers(const ValueSpec& spec);
/// Why a number is outside `spec`: "expected a number in [0, 1], got 1.5".
std::string number_reason(const ValueSpec& spec, double x);
/// The error of a number outside `spec`: "<path>: expected a number in [0, 1], got 1.5".
ConfigError number_error(const std::string& path, const ValueSpec& spec, double x);

// Value specs, for the tables.
inline ValueSpec interval(double lo, bool lo_open, double hi, bool hi_open) {
  ValueSpec s;
  s.lo = lo;
  s.lo_open = lo_open;
  s.hi = hi;
  s.hi_open = hi_open;
  return s;
}
inline ValueSpec any_value() {
  return {};
}
inline ValueSpec at_least(double lo) {
  return interval(lo, false, INFINITY, false);
}
inline ValueSpec above(double lo) {
  return interval(lo, true, INFINITY, false);
}
inline ValueSpec closed(double lo, double hi) {
  return interval(lo, false, hi, false);
}
inline ValueSpec open(double lo, double hi) {
  return interval(lo, true, hi, true);
}
inline ValueSpec left_open(double lo, double hi) {
  return interval(lo, true, hi, false);
}
inline ValueSpec right_open(double lo, double hi) {
  return interval(lo, false, hi, true);
}

/// The most worker threads a job or `--threads` accepts; 0 asks for one per core.
inline constexpr int kMaxThreads = 4096;
/// The range of every "threads" key and of `--threads`: [0, kMaxThreads].
inline ValueSpec threads_range() {
  return closed(0, kMaxThreads);
}
/// An integer >= the sibling `key` (a range's stop and start).
inline ValueSpec at_least_key(std::string_view key) {
  ValueSpec s;
  s.lo_key = key;
  return s;
}
/// An integer in [0, sibling `key`) (a shard's index and count).
inline ValueSpec below_key(std::string_view key) {
  ValueSpec s = at_least(0);
  s.hi_key = key;
  return s;
}
/// An array of integers >= 0, `items` saying what they index.
inline ValueSpec indices(std::string_view items) {
  ValueSpec s = at_least(0);
  s.items = items;
  return s;
}
/// "auto" or a number in `spec`.
inline ValueSpec auto_or(ValueSpec spec) {
  spec.auto_word = true;
  return spec;
}
/// One of an enum's names (all of `names`, or those the key takes).
template <class E, std::size_t N>
ValueSpec choice(const EnumName<E> (&names)[N]) {
  ValueSpec s;
  for (const EnumName<E>& n : names) s.names.emplace_back(n.name, static_cast<int>(n.value));
  return s;
}

struct Entry;
using Entries = std::vector<Entry>;

/// An enum member, through its value as int.
struct ChoiceRef {
  void* value;
  int (*get)(const void* value);
  void (*set)(void* value, int);
};

/// A glTF element chosen by name or by index: two members (e.g. GltfInputOptions::mesh and
/// mesh_index).
struct SelectorRef {
  std::string* name;
  std::optional<int>* index;
};

/// A nested options struct T: always there (Plain); a std::optional<T>, absent = empty
/// (Optional); a T with `bool enabled`, whose key takes true, false or T's keys (Toggle); or a
/// std::optional<T> whose keys sit beside the field's instead of under a key of its own, present
/// when its first key is (Inline).
struct ObjectRef {
  enum class Mode { Plain, Optional, Toggle, Inline };
  Mode mode;
  void* target;                         ///< the T or the std::optional<T>
  Entries (*entries)(void* target);     ///< T's fields (an empty optional is engaged first)
  bool (*present)(const void* target);  ///< engaged or enabled (always, for Plain)
  void (*set_present)(void* target, bool);
  Entries (*defaults)();  ///< the fields of a default-constructed T
};

/// Where one key's value lives, by type.
using ValueRef = std::variant<bool*, int*, double*, std::optional<int>*, std::optional<double>*,
                              std::filesystem::path*, std::vector<int>*, std::vector<double>*,
                              FrameSelection*, ChoiceRef, SelectorRef, ObjectRef>;

/// A key's description: what the tables hold besides the member.
struct FieldInfo {
  std::string_view key;
  ValueSpec spec;
  std::string_view doc;       ///< one line, Markdown
  std::string_view required;  ///< non-empty: the key must be given; what it holds
};

/// One key of an options struct S.
template <class S>
struct Field {
  FieldInfo info;
  ValueRef (*ref)(S&);
  bool (*written)(const S&) = nullptr;  ///< null, or when the key is written (to_json)

  Field required(std::string_view what) const {
    Field f = *this;
    f.info.required = what;
    return f;
  }
  Field written_if(bool (*when)(const S&)) const {
    Field f = *this;
    f.written = when;
    return f;
  }
};

template <class S>
using Fields = std::vector<Field<S>>;

/// The table of S; each options struct's header defines its specialization.
template <class S>
const Fields<S>& fields_of();

/// A table from groups of lines, in order (a long table as named parts).
template <class S>
Fields<S> concat_fields(std::initializer_list<Fields<S>> groups) {
  Fields<S> out;
  for (const Fields<S>& g : groups) out.insert(out.end(), g.begin(), g.end());
  return out;
}

/// The lambdas of a std::visit over a ValueRef as one visitor.
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

/// One key of one object: the table's line and where the value lives.
struct Entry {
  const FieldInfo* info;
  ValueRef value;
  bool written = true;
};

template <class S>
Entries entries_of(S& object) {
  Entries out;
  for (const Field<S>& f : fields_of<S>())
    out.push_back({&f.info, f.ref(object), !f.written || f.written(object)});
  return out;
}

/// Throws OptionError("<key>", "expected ..., got ...") for the first integer or number (nested
/// objects included, "<object>.<key>") outside its table's range: for options built in code, in
/// the numerical modules, which name the member and leave the config path to their caller.
void check_option_ranges(const Entries& entries);
template <class S>
void check_option_ranges(const S& options) {
  S copy = options;  // entries_of gives write access; the check only reads
  check_option_ranges(entries_of(copy));
}
/// check_option_ranges in the config's words: ConfigError "<prefix>.<key>: expected ..., got ...".
template <class S>
void check_ranges(const S& options, const std::string& prefix) {
  with_option_path(prefix, [&] { check_option_ranges(options); });
}

namespace options_detail {

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};
template <class T, class = void>
struct has_enabled : std::false_type {};
template <class T>
struct has_enabled<T, std::void_t<decltype(std::declval<T&>().enabled)>> : std::true_type {};
template <class M>
struct member;
template <class S, class T>
struct member<T S::*> {
  using owner = S;
};

template <class T>
Entries plain_entries(void* p) {
  return entries_of(*static_cast<T*>(p));
}
template <class T>
Entries optional_entries(void* p) {
  auto& o = *static_cast<std::optional<T>*>(p);
  if (!o) o.emplace();
  return entries_of(*o);
}
template <class T>
Entries default_entries() {
  static T defaults{};
  return entries_of(defaults);
}

template <class T>
ObjectRef optional_ref(std::optional<T>& value, ObjectRef::Mode mode) {
  return {mode,
          &value,
          &optional_entries<T>,
          [](const void* p) { return static_cast<const std::optional<T>*>(p)->has_value(); },
          [](void* p, bool on) {
            auto& o = *static_cast<std::optional<T>*>(p);
            if (!on) o.reset();
            if (on && !o) o.emplace();
          },
          &default_entries<T>};
}

template <class T>
ValueRef make_ref(T& value) {
  if constexpr (std::is_constructible_v<ValueRef, T*>) {
    return ValueRef(&value);
  } else if constexpr (std::is_enum_v<T>) {
    return ChoiceRef{&value,
                     [](const void* p) { return static_cast<int>(*static_cast<const T*>(p)); },
                     [](void* p, int v) { *static_cast<T*>(p) = static_cast<T>(v); }};
  } else if constexpr (is_optional<T>::value) {
    return optional_ref(value, ObjectRef::Mode::Optional);
  } else if constexpr (has_enabled<T>::value) {
    return ObjectRef{ObjectRef::Mode::Toggle,
                     &value,
                     &plain_entries<T>,
                     [](const void* p) { return static_cast<const T*>(p)->enabled; },
                     [](void* p, bool on) { static_cast<T*>(p)->enabled = on; },
                     &default_entries<T>};
  } else {
    return ObjectRef{ObjectRef::Mode::Plain, &value,
                     &plain_entries<T>,      [](const void*) { return true; },
                     [](void*, bool) {},     &default_entries<T>};
  }
}

}  // namespace options_detail

/// The table line of member M: `field<&MassageOptions::iterations>("iterations", at_least(1),
/// "outer iterations")`. Enums, nested options structs, std::optional of one and structs with
/// `bool enabled` (Toggle) are recognised by the member's type.
template <auto M>
Field<typename options_detail::member<decltype(M)>::owner> field(std::string_view key,
                                                                 ValueSpec spec,
                                                                 std::string_view doc) {
  using S = typename options_detail::member<decltype(M)>::owner;
  return {{key, std::move(spec), doc, {}}, [](S& s) { return options_detail::make_ref(s.*M); }};
}

/// The line of a glTF element chosen by name (member Name) or by index (member Index).
template <auto Name, auto Index>
Field<typename options_detail::member<decltype(Name)>::owner> selector_field(std::string_view key,
                                                                             std::string_view doc) {
  using S = typename options_detail::member<decltype(Name)>::owner;
  return {{key, {}, doc, {}}, [](S& s) -> ValueRef {
            return SelectorRef{&(s.*Name), &(s.*Index)};
          }};
}

/// The line of a std::optional member whose keys sit beside it (ObjectRef::Mode::Inline).
template <auto M>
Field<typename options_detail::member<decltype(M)>::owner> inline_field(std::string_view doc) {
  using S = typename options_detail::member<decltype(M)>::owner;
  return {{{}, {}, doc, {}}, [](S& s) -> ValueRef {
            return options_detail::optional_ref(s.*M, ObjectRef::Mode::Inline);
          }};
}

}  // namespace sm
