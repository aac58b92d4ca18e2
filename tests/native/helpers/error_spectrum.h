// The error spectrum of an image (research/samplers.md §4): |DFT|² of a w × w error image and
// its low-frequency ratio, the mean power at 0 < |k| <= w/8 over the mean power at all k != 0
// (white noise: 1; blue noise: below it). Shared by the sampler and adaptive-sampling tests.
#pragma once

#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

namespace stratum_test {

// |DFT|^2 of a w x w image, by rows then columns (O(w^3)).
inline std::vector<double> power_spectrum(const std::vector<double>& img, uint32_t w) {
    using C = std::complex<double>;
    std::vector<C> twiddle(w), a(img.begin(), img.end()), b(a.size());
    for (uint32_t k = 0; k < w; ++k) twiddle[k] = std::polar(1.0, -2.0 * M_PI * k / w);
    for (uint32_t y = 0; y < w; ++y)
        for (uint32_t k = 0; k < w; ++k) {
            C sum = 0;
            for (uint32_t x = 0; x < w; ++x) sum += a[y * w + x] * twiddle[(k * x) % w];
            b[y * w + k] = sum;
        }
    std::vector<double> power(a.size());
    for (uint32_t kx = 0; kx < w; ++kx)
        for (uint32_t ky = 0; ky < w; ++ky) {
            C sum = 0;
            for (uint32_t y = 0; y < w; ++y) sum += b[y * w + kx] * twiddle[(ky * y) % w];
            power[ky * w + kx] = std::norm(sum);
        }
    return power;
}

// Sums of an image's spectral power at the low frequencies (0 < |k| <= w/8) and at all k != 0,
// with their counts: accumulated over several images (seeds) before the ratio is taken.
struct SpectrumBands {
    double low = 0, all = 0;
    int n_low = 0, n_all = 0;

    void add(const std::vector<double>& error_image, uint32_t w) {
        const std::vector<double> power = power_spectrum(error_image, w);
        for (uint32_t ky = 0; ky < w; ++ky)
            for (uint32_t kx = 0; kx < w; ++kx) {
                if (kx == 0 && ky == 0) continue;
                const int fx = kx < w / 2 ? int(kx) : int(kx) - int(w);
                const int fy = ky < w / 2 ? int(ky) : int(ky) - int(w);
                all += power[ky * w + kx];
                ++n_all;
                if (fx * fx + fy * fy <= int(w / 8) * int(w / 8)) {
                    low += power[ky * w + kx];
                    ++n_low;
                }
            }
    }
    double low_frequency_ratio() const { return (low / n_low) / (all / n_all); }
};

}  // namespace stratum_test
