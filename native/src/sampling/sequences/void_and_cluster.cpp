#include "sampling/sequences/void_and_cluster.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "sampling/pcg32.h"

namespace stratum::void_and_cluster {

namespace {

// 1D factor of the toroidal Gaussian: g[d] = exp(−min(d, size − d)² / (2σ²)).
std::vector<double> axis_kernel(uint32_t size, double sigma) {
    std::vector<double> g(size);
    for (uint32_t d = 0; d < size; ++d) {
        const double r = std::min(d, size - d);
        g[d] = std::exp(-r * r / (2.0 * sigma * sigma));
    }
    return g;
}

class Field {
public:
    Field(uint32_t size, double sigma)
        : size_(size),
          g_(axis_kernel(size, sigma)),
          row_(size),
          ones_(size_t{size} * size, 0),
          energy_(size_t{size} * size, 0.0) {}

    void set(size_t p, bool one) {
        if (static_cast<bool>(ones_[p]) == one) return;
        ones_[p] = one;
        const double sign = one ? 1.0 : -1.0;
        const uint32_t px = static_cast<uint32_t>(p % size_), py = static_cast<uint32_t>(p / size_);
        for (uint32_t x = 0; x < size_; ++x) row_[x] = sign * g_[(x + size_ - px) % size_];
        for (uint32_t y = 0; y < size_; ++y) {
            const double gy = g_[(y + size_ - py) % size_];
            double* e = &energy_[size_t{y} * size_];
            for (uint32_t x = 0; x < size_; ++x) e[x] += gy * row_[x];
        }
    }
    bool one(size_t p) const { return ones_[p] != 0; }

    // The one with the highest energy (requires at least one one).
    size_t tightest_cluster() const {
        size_t best = energy_.size();
        for (size_t p = 0; p < energy_.size(); ++p)
            if (ones_[p] && (best == energy_.size() || energy_[p] > energy_[best])) best = p;
        return best;
    }
    // The zero with the lowest energy (requires at least one zero).
    size_t largest_void() const {
        size_t best = energy_.size();
        for (size_t p = 0; p < energy_.size(); ++p)
            if (!ones_[p] && (best == energy_.size() || energy_[p] < energy_[best])) best = p;
        return best;
    }

private:
    uint32_t size_;
    std::vector<double> g_, row_;
    std::vector<uint8_t> ones_;
    std::vector<double> energy_;
};

}  // namespace

std::vector<double> energy(const std::vector<uint8_t>& pattern, uint32_t size, double sigma) {
    const std::vector<double> g = axis_kernel(size, sigma);
    std::vector<double> e(size_t{size} * size, 0.0);
    for (size_t p = 0; p < pattern.size(); ++p) {
        if (!pattern[p]) continue;
        const size_t px = p % size, py = p / size;
        for (size_t q = 0; q < e.size(); ++q)
            e[q] += g[(q / size + size - py) % size] * g[(q % size + size - px) % size];
    }
    return e;
}

std::vector<uint32_t> rank_texture(uint32_t size, double sigma, double initial_fraction, uint64_t seed) {
    const size_t n = size_t{size} * size;
    const auto m = std::clamp<size_t>(
        static_cast<size_t>(std::lround(initial_fraction * static_cast<double>(n))), 1, n - 1);

    // 0. Random initial pattern of m ones, then relaxed. A move never raises the total energy
    //    (the void is chosen with the cluster already removed), so the loop settles; the cap
    //    only guards against cycling through exact ties.
    Field prototype(size, sigma);
    Pcg32 rng(seed, 0x76616e64636c7573ull);
    for (size_t placed = 0; placed < m;) {
        const size_t p = rng.next_u32() % n;
        if (!prototype.one(p)) {
            prototype.set(p, true);
            ++placed;
        }
    }
    for (size_t moves = 0; moves < 64 * n; ++moves) {
        const size_t cluster = prototype.tightest_cluster();
        prototype.set(cluster, false);
        const size_t hole = prototype.largest_void();
        prototype.set(hole, true);
        if (hole == cluster) break;
    }

    std::vector<uint32_t> rank(n, 0);
    // 1. Ranks m−1 .. 0: remove the tightest clusters.
    Field field = prototype;
    for (size_t r = m; r-- > 0;) {
        const size_t cluster = field.tightest_cluster();
        field.set(cluster, false);
        rank[cluster] = static_cast<uint32_t>(r);
    }
    // 2 and 3. Ranks m .. n−1: fill the largest voids.
    field = prototype;
    for (size_t r = m; r < n; ++r) {
        const size_t hole = field.largest_void();
        field.set(hole, true);
        rank[hole] = static_cast<uint32_t>(r);
    }
    return rank;
}

}  // namespace stratum::void_and_cluster
