#include "scene/placement_conditioning.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stratum {

namespace {

constexpr double kUntraceable = std::numeric_limits<double>::infinity();

struct Linear {
    double a[3][3];
};

Linear linear_part(const Transform& t) {
    Linear l;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) l.a[r][c] = static_cast<double>(t.m[static_cast<size_t>(4 * r + c)]);
    return l;
}

// ‖A⁻¹‖∞ by cofactors; infinite for a singular A.
double inverse_norm(const Linear& l) {
    const auto& a = l.a;
    const double c[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[0][2] * a[2][1] - a[0][1] * a[2][2],
                             a[0][1] * a[1][2] - a[0][2] * a[1][1]},
                            {a[1][2] * a[2][0] - a[1][0] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0],
                             a[0][2] * a[1][0] - a[0][0] * a[1][2]},
                            {a[1][0] * a[2][1] - a[1][1] * a[2][0], a[0][1] * a[2][0] - a[0][0] * a[2][1],
                             a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
    const double det = a[0][0] * c[0][0] + a[0][1] * c[1][0] + a[0][2] * c[2][0];
    if (!(std::abs(det) > 0.0)) return kUntraceable;
    double norm = 0.0;
    for (const auto& row : c) norm = std::max(norm, (std::abs(row[0]) + std::abs(row[1]) + std::abs(row[2])));
    return norm / std::abs(det);
}

// The scales (diagonal of S) and skews (above it) of A = R·S, by Gram–Schmidt on A's columns
// as decompose_transform does (a mirror puts its sign on the third scale), in double.
struct ScaleSkew {
    double scale[3];
    double skew[3];
};

bool scale_skew(const Linear& l, ScaleSkew* out) {
    double col[3][3];
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) col[c][r] = l.a[r][c];
    const auto dot3 = [](const double* x, const double* y) {
        return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    };
    double q[3][3];
    for (int c = 0; c < 3; ++c) {
        double u[3] = {col[c][0], col[c][1], col[c][2]};
        for (int k = 0; k < c; ++k) {
            const double proj = dot3(q[k], col[c]);
            out->skew[c == 1 ? 0 : k + 1] = proj;  // (xy), then (xz), (yz)
            for (int r = 0; r < 3; ++r) u[r] -= proj * q[k][r];
        }
        const double len = std::sqrt(dot3(u, u));
        if (!(len > 0.0)) return false;
        out->scale[c] = len;
        for (int r = 0; r < 3; ++r) q[c][r] = u[r] / len;
    }
    const double cross[3] = {q[0][1] * q[1][2] - q[0][2] * q[1][1], q[0][2] * q[1][0] - q[0][0] * q[1][2],
                             q[0][0] * q[1][1] - q[0][1] * q[1][0]};
    if (dot3(cross, q[2]) < 0.0) out->scale[2] = -out->scale[2];
    return true;
}

}  // namespace

double inverse_norm_bound(const Transform& start, const Transform& end, bool moving) {
    if (!moving) return inverse_norm(linear_part(start));
    ScaleSkew s0, s1;
    if (!scale_skew(linear_part(start), &s0) || !scale_skew(linear_part(end), &s1)) return kUntraceable;
    double m = kUntraceable, big = 0.0, k = 0.0;
    for (int i = 0; i < 3; ++i) {
        if (!(s0.scale[i] * s1.scale[i] > 0.0)) return kUntraceable;  // passes through zero
        m = std::min({m, std::abs(s0.scale[i]), std::abs(s1.scale[i])});
        big = std::max({big, std::abs(s0.scale[i]), std::abs(s1.scale[i])});
        k = std::max({k, std::abs(s0.skew[i]), std::abs(s1.skew[i])});
    }
    return 3.0 * (1.0 / m + k / (m * m) + (k * k + k * big) / (m * m * m));
}

double translation_bound(const Transform& start, const Transform& end) {
    double t = 0.0;
    for (const Transform* x : {&start, &end})
        for (int i = 0; i < 3; ++i) t = std::max(t, std::abs(static_cast<double>(x->translation()[i])));
    return t;
}

}  // namespace stratum
