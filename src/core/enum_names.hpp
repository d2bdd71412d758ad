#pragma once
/// The names an enum's values have in the config, declared beside the enum.
#include <cstddef>
#include <string_view>

namespace sm {

template <class E>
struct EnumName {
  std::string_view name;
  E value;
};

/// The name of `value` among `names` ("" if it has none).
template <class E, std::size_t N>
constexpr std::string_view name_of(E value, const EnumName<E> (&names)[N]) {
  for (const EnumName<E>& n : names)
    if (n.value == value) return n.name;
  return {};
}

}  // namespace sm
