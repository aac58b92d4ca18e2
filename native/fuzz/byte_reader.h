// The fuzzer's input, read front to back as the arguments of a small program over the C ABI
// (native/fuzz/README.md gives the encoding). Every byte string is a valid program: reading
// past the end yields zeros, so a truncated input ends in the default choices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>

namespace stratum::fuzz {

// How a float selector byte in [kFirstScaled, kFirstRaw) maps to a value: the range the
// field usually takes, so that most draws are plausible and valid.
enum class FloatKind {
    Signed,    // (s - 128) / 16: [-6, 5.94] in steps of 1/16 (positions, shifts, offsets)
    Positive,  // (s - 32) / 16: [0, 11.9] (strengths, sizes, distances)
    Unit,      // (s - 32) / 191: [0, 1] (colours, roughness, blends)
};

class ByteReader {
public:
    // Selector bytes below this index the extreme values of special_floats().
    static constexpr uint8_t kSpecialCount = 32;
    // Selector bytes from this one on take the next four bytes as the float's bits.
    static constexpr uint8_t kFirstRaw = 224;

    explicit ByteReader(std::span<const uint8_t> data) : data_(data) {}

    bool exhausted() const { return pos_ >= data_.size(); }
    size_t remaining() const { return exhausted() ? 0 : data_.size() - pos_; }

    uint8_t u8() { return exhausted() ? 0 : data_[pos_++]; }
    uint16_t u16() { return static_cast<uint16_t>(u8() | (u8() << 8)); }
    uint32_t u32() { return static_cast<uint32_t>(u16()) | (static_cast<uint32_t>(u16()) << 16); }
    bool flag() { return (u8() & 1) != 0; }

    // The extreme values every float field is tried with: signed zeros, denormals, the edges of
    // Embree's valid range (FLT_LARGE = 1.844e18), huge values up to FLT_MAX, infinities, NaNs.
    static const float* special_floats() {
        static const float kSpecial[kSpecialCount] = {
            0.0f,
            -0.0f,
            std::numeric_limits<float>::denorm_min(),
            -std::numeric_limits<float>::denorm_min(),
            std::numeric_limits<float>::min(),
            1e-38f,
            1e-18f,
            1e-9f,
            1e-4f,
            1e4f,
            1e9f,
            1e18f,
            1.844e18f,
            1e19f,
            1e30f,
            3e38f,
            std::numeric_limits<float>::max(),
            std::numeric_limits<float>::infinity(),
            std::numeric_limits<float>::quiet_NaN(),
            -1e19f,
            -1e30f,
            -3e38f,
            -std::numeric_limits<float>::max(),
            -std::numeric_limits<float>::infinity(),
            -std::numeric_limits<float>::quiet_NaN(),
            1.0f,
            -1.0f,
            3.14159265f,
            6.28318531f,
            0.5f,
            65536.0f,
            -1e-18f,
        };
        return kSpecial;
    }

    float f32(FloatKind kind) {
        const uint8_t s = u8();
        if (s < kSpecialCount) return special_floats()[s];
        if (s >= kFirstRaw) {
            const uint32_t bits = u32();
            float v;
            std::memcpy(&v, &bits, sizeof v);
            return v;
        }
        switch (kind) {
            case FloatKind::Signed:
                return static_cast<float>(s - 128) / 16.0f;
            case FloatKind::Positive:
                return static_cast<float>(s - kSpecialCount) / 16.0f;
            case FloatKind::Unit:
                return static_cast<float>(s - kSpecialCount) /
                       static_cast<float>(kFirstRaw - 1 - kSpecialCount);
        }
        return 0.0f;
    }

    // Doubles for the float settings: first byte < 8 picks a value no float can hold
    // (beyond FLT_MAX, below the float denormals, DBL_MAX), otherwise a float draw.
    double f64(FloatKind kind) {
        static constexpr double kDoubleSpecial[8] = {1e300,
                                                     -1e300,
                                                     std::numeric_limits<double>::max(),
                                                     3.5e38,
                                                     std::numeric_limits<double>::min(),
                                                     5e-324,
                                                     1e-50,
                                                     -3.5e38};
        const uint8_t s = u8();
        if (s < 8) return kDoubleSpecial[s];
        return static_cast<double>(f32(kind));
    }

    // Integers for the int settings: first byte < 16 picks a boundary value, else 0..239.
    int64_t i64() {
        static constexpr int64_t kIntSpecial[16] = {std::numeric_limits<int64_t>::min(),
                                                    std::numeric_limits<int64_t>::max(),
                                                    -1,
                                                    std::numeric_limits<int32_t>::max(),
                                                    std::numeric_limits<int32_t>::min(),
                                                    0xffffffffll,
                                                    0x100000000ll,
                                                    65535,
                                                    65536,
                                                    65537,
                                                    1 << 24,
                                                    (1 << 24) + 1,
                                                    1024,
                                                    1025,
                                                    -65536,
                                                    0};
        const uint8_t s = u8();
        if (s < 16) return kIntSpecial[s];
        return s - 16;
    }

    // An index into a table of `count` ids: mostly a valid one, sometimes `count` itself (the
    // first invalid id), and for selector 255 any 32-bit value.
    uint32_t id(uint32_t count) {
        const uint8_t s = u8();
        if (s == 255) return u32();
        return s % (count + 1);
    }

    // Either an entry of `table` or, for selectors from 240 on, raw bytes (up to 40, NULs
    // included: the string then ends early, as C strings do).
    std::string name(std::span<const char* const> table) {
        const uint8_t s = u8();
        if (s < 240 && !table.empty()) return table[s % table.size()];
        const size_t n = u8() % 41;
        std::string raw;
        for (size_t i = 0; i < n; ++i) raw.push_back(static_cast<char>(u8()));
        return raw;
    }

    // Up to max_size raw bytes, the length first.
    std::string bytes(size_t max_size) {
        const size_t n = u16() % (max_size + 1);
        std::string out;
        for (size_t i = 0; i < n && !exhausted(); ++i) out.push_back(static_cast<char>(u8()));
        return out;
    }

private:
    std::span<const uint8_t> data_;
    size_t pos_ = 0;
};

}  // namespace stratum::fuzz
