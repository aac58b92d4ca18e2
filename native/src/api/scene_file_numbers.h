// The numbers of a captured scene file, read by key and converted only when the target type
// holds them. nlohmann's get<float>() and get<int32_t>() cast a double that is out of range
// (1e300 to float, 3.5e38 to int), which is undefined behaviour, and get<uint32_t>() wraps -1
// to 4294967295; a hostile or damaged file must give a message naming the key instead.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace stratum::scene_file {

using nlohmann::json;

// `value` as T (float or an integer type); `what` names it in the error.
template <typename T>
T number(const json& value, const std::string& what) {
    if constexpr (std::is_floating_point_v<T>) {
        const double v = value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN();
        if (!(std::abs(v) <= static_cast<double>(std::numeric_limits<T>::max())))
            throw std::runtime_error(what + " = " + value.dump() + " is not a number in float range");
        return static_cast<T>(v);
    } else {
        const bool in_range =
            value.is_number_unsigned()
                ? value.get<uint64_t>() <= static_cast<uint64_t>(std::numeric_limits<T>::max())
            : value.is_number_integer()
                ? std::cmp_greater_equal(value.get<int64_t>(), std::numeric_limits<T>::min()) &&
                      std::cmp_less_equal(value.get<int64_t>(), std::numeric_limits<T>::max())
                : false;
        if (!in_range)
            throw std::runtime_error(what + " = " + value.dump() + " is not an integer in [" +
                                     std::to_string(std::numeric_limits<T>::min()) + ", " +
                                     std::to_string(std::numeric_limits<T>::max()) + "]");
        // A uint64_t above INT64_MAX (a light linking membership) is read as unsigned.
        return value.is_number_unsigned() ? static_cast<T>(value.get<uint64_t>())
                                          : static_cast<T>(value.get<int64_t>());
    }
}

// object[key] as T.
template <typename T>
T field(const json& object, const char* key) {
    return number<T>(object.at(key), key);
}

// object[key] as T, or `fallback` when the key is absent (files written before it existed).
template <typename T>
T field_or(const json& object, const char* key, T fallback) {
    return object.contains(key) ? number<T>(object.at(key), key) : fallback;
}

// object[key][index] as T.
template <typename T>
T element(const json& object, const char* key, size_t index) {
    return number<T>(object.at(key).at(index), std::string(key) + "[" + std::to_string(index) + "]");
}

// object[key], an array of numbers, as T each (an absent key is an empty array when `optional`).
template <typename T>
std::vector<T> numbers(const json& object, const char* key, bool optional = false) {
    std::vector<T> out;
    if (optional && !object.contains(key)) return out;
    const json& array = object.at(key);
    if (!array.is_array()) throw std::runtime_error(std::string(key) + " is not an array");
    out.reserve(array.size());
    for (size_t i = 0; i < array.size(); ++i)
        out.push_back(number<T>(array[i], std::string(key) + "[" + std::to_string(i) + "]"));
    return out;
}

// object[key], exactly N numbers, into out.
template <typename T, size_t N>
void read_numbers(const json& object, const char* key, T (&out)[N]) {
    const json& array = object.at(key);
    if (!array.is_array() || array.size() != N)
        throw std::runtime_error(std::string(key) + " must be an array of " + std::to_string(N) + " numbers");
    for (size_t i = 0; i < N; ++i)
        out[i] = number<T>(array[i], std::string(key) + "[" + std::to_string(i) + "]");
}

}  // namespace stratum::scene_file
