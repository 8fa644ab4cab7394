#pragma once
// Enums spelt as words on the command line and in JSON. An enum lists its words once, by
// specialising EnumNames; nameOf and parseNamed read that list, and an option of type
// std::optional<E> spells "not given" as "auto".
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace subdfit {

// Specialise with: static constexpr std::array<std::pair<E, std::string_view>, N> names{...};
template <class E>
struct EnumNames;

template <class E>
concept NamedEnum = std::is_enum_v<E> && requires {
    EnumNames<E>::names;
};

inline constexpr std::string_view kAutoName = "auto";

template <NamedEnum E>
std::string_view nameOf(E value) {
    for (const auto& [e, name] : EnumNames<E>::names)
        if (e == value) return name;
    return "?";
}

template <NamedEnum E>
std::string_view nameOf(const std::optional<E>& value) {
    return value ? nameOf(*value) : kAutoName;
}

// The value spelt `text`, or nothing when it names none.
template <NamedEnum E>
std::optional<E> parseNamed(std::string_view text) {
    for (const auto& [e, name] : EnumNames<E>::names)
        if (name == text) return e;
    return std::nullopt;
}

// Every word an option of type T (E or std::optional<E>) takes, as a list for help and errors:
// "plateau or anneal", "auto, geometry, unlit, lambert or pbr".
template <NamedEnum E>
std::string namesOf(bool withAuto = false) {
    std::string list = withAuto ? std::string(kAutoName) : "";
    const auto& names = EnumNames<E>::names;
    for (size_t i = 0; i < names.size(); ++i) {
        if (!list.empty()) list += i + 1 == names.size() ? " or " : ", ";
        list += names[i].second;
    }
    return list;
}

}  // namespace subdfit
