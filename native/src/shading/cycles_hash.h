// The integer hash Cycles' procedural textures are built on (util/hash.h): Bob Jenkins'
// lookup3 (public domain, 2006) final and mix rounds seeded with 0xdeadbeef + (n << 2) + 13 for n
// 32-bit keys; a float key hashes its bit pattern, and a hash maps to [0,1] by / 0xFFFFFFFF.
// Noise, Voronoi, White Noise, Brick and the other textures must use exactly this to give
// Cycles' patterns. Pure functions, no state.
#pragma once

#include <bit>
#include <cstdint>

namespace stratum::cycles_hash {

inline constexpr uint32_t rotate(uint32_t x, int k) { return (x << k) | (x >> (32 - k)); }

// lookup3's mix(a, b, c).
inline constexpr void mix(uint32_t& a, uint32_t& b, uint32_t& c) {
    a -= c, a ^= rotate(c, 4), c += b;
    b -= a, b ^= rotate(a, 6), a += c;
    c -= b, c ^= rotate(b, 8), b += a;
    a -= c, a ^= rotate(c, 16), c += b;
    b -= a, b ^= rotate(a, 19), a += c;
    c -= b, c ^= rotate(b, 4), b += a;
}

// lookup3's final(a, b, c).
inline constexpr void finish(uint32_t& a, uint32_t& b, uint32_t& c) {
    c ^= b, c -= rotate(b, 14);
    a ^= c, a -= rotate(c, 11);
    b ^= a, b -= rotate(a, 25);
    c ^= b, c -= rotate(b, 16);
    a ^= c, a -= rotate(c, 4);
    b ^= a, b -= rotate(a, 14);
    c ^= b, c -= rotate(b, 24);
}

inline constexpr uint32_t seed(uint32_t keys) { return 0xdeadbeefu + (keys << 2) + 13u; }

inline constexpr uint32_t hash_uint(uint32_t kx) {
    uint32_t a = seed(1), b = a, c = a;
    a += kx;
    finish(a, b, c);
    return c;
}
inline constexpr uint32_t hash_uint2(uint32_t kx, uint32_t ky) {
    uint32_t a = seed(2), b = a, c = a;
    b += ky;
    a += kx;
    finish(a, b, c);
    return c;
}
inline constexpr uint32_t hash_uint3(uint32_t kx, uint32_t ky, uint32_t kz) {
    uint32_t a = seed(3), b = a, c = a;
    c += kz;
    b += ky;
    a += kx;
    finish(a, b, c);
    return c;
}
inline constexpr uint32_t hash_uint4(uint32_t kx, uint32_t ky, uint32_t kz, uint32_t kw) {
    uint32_t a = seed(4), b = a, c = a;
    a += kx;
    b += ky;
    c += kz;
    mix(a, b, c);
    a += kw;
    finish(a, b, c);
    return c;
}

// A hash as a float in [0, 1] (Cycles' uint_to_float_incl).
inline float to_unit(uint32_t h) { return static_cast<float>(h) * (1.0f / static_cast<float>(0xFFFFFFFFu)); }
inline uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

inline float hash_float(float k) { return to_unit(hash_uint(bits(k))); }
inline float hash_float2(float x, float y) { return to_unit(hash_uint2(bits(x), bits(y))); }
inline float hash_float3(float x, float y, float z) { return to_unit(hash_uint3(bits(x), bits(y), bits(z))); }
inline float hash_float4(float x, float y, float z, float w) {
    return to_unit(hash_uint4(bits(x), bits(y), bits(z), bits(w)));
}

// Vector-valued hashes, component by component as Cycles builds them (its hash_floatN_to_floatM).
struct Hash3 {
    float x, y, z;
};
struct Hash4 {
    float x, y, z, w;
};
inline Hash3 hash_float_to_float3(float k) {
    return {hash_float(k), hash_float2(k, 1.0f), hash_float2(k, 2.0f)};
}
inline Hash3 hash_float2_to_float3(float x, float y) {
    return {hash_float2(x, y), hash_float3(x, y, 1.0f), hash_float3(x, y, 2.0f)};
}
inline Hash3 hash_float3_to_float3(float x, float y, float z) {
    return {hash_float3(x, y, z), hash_float4(x, y, z, 1.0f), hash_float4(x, y, z, 2.0f)};
}
inline Hash3 hash_float4_to_float3(float x, float y, float z, float w) {
    return {hash_float4(x, y, z, w), hash_float4(z, x, w, y), hash_float4(w, z, y, x)};
}
inline Hash4 hash_float4_to_float4(float x, float y, float z, float w) {
    return {hash_float4(x, y, z, w), hash_float4(w, x, y, z), hash_float4(z, w, x, y),
            hash_float4(y, z, w, x)};
}
// float2 results: (first, second) components.
inline Hash3 hash_float_to_float2(float k) { return {hash_float(k), hash_float2(k, 1.0f), 0.0f}; }
inline Hash3 hash_float2_to_float2(float x, float y) {
    return {hash_float2(x, y), hash_float3(x, y, 1.0f), 0.0f};
}
inline Hash3 hash_float3_to_float2(float x, float y, float z) {
    return {hash_float3(x, y, z), hash_float3(z, x, y), 0.0f};
}
inline Hash3 hash_float4_to_float2(float x, float y, float z, float w) {
    return {hash_float4(x, y, z, w), hash_float4(z, x, w, y), 0.0f};
}

}  // namespace stratum::cycles_hash
