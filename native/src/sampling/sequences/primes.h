// Prime table for the Halton family: the first kPrimeCount primes, computed at compile time by
// a sieve of Eratosthenes (no copied tables). Pure sequence math.
#pragma once

#include <array>
#include <cstdint>

namespace stratum {

inline constexpr uint32_t kPrimeCount = 1024;

namespace detail {

// The 1024th prime is 8161, so a sieve over [0, 8192) holds the whole table.
inline constexpr uint32_t kPrimeSieveLimit = 8192;

constexpr std::array<uint32_t, kPrimeCount> sieve_primes() {
    std::array<bool, kPrimeSieveLimit> composite{};
    std::array<uint32_t, kPrimeCount> primes{};
    uint32_t count = 0;
    for (uint32_t n = 2; n < kPrimeSieveLimit && count < kPrimeCount; ++n) {
        if (composite[n]) continue;
        primes[count++] = n;
        for (uint32_t m = n * n; m < kPrimeSieveLimit; m += n) composite[m] = true;
    }
    return primes;
}

}  // namespace detail

// kPrimes[0] = 2, kPrimes[1] = 3, ...
inline constexpr std::array<uint32_t, kPrimeCount> kPrimes = detail::sieve_primes();
static_assert(kPrimes[0] == 2 && kPrimes[1] == 3 && kPrimes[999] == 7919 && kPrimes[kPrimeCount - 1] != 0);

}  // namespace stratum
