#include "film/film.h"

#include <algorithm>
#include <cmath>
#include <mutex>

namespace stratum {

namespace {

bool is_finite(const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

// The passes a film holds: those asked for, the Error pass's sums of squares when it tracks
// prefixes (its error estimate scales them), and the Shadow Catcher pass's sums when Combined
// is read from them.
std::vector<Pass> film_passes(std::span<const Pass> passes, bool track_prefixes, CatcherCombined catcher) {
    std::vector<Pass> out(passes.begin(), passes.end());
    const auto add = [&](Pass pass) {
        if (std::find(out.begin(), out.end(), pass) == out.end()) out.push_back(pass);
    };
    if (track_prefixes) add(Pass::Error);
    if (catcher != CatcherCombined::Off) add(Pass::ShadowCatcher);
    return out;
}

// s²/n: the variance of the mean of n independent samples estimated from their sum and sum of
// squares, s² = n/(n−1)·(Σx²/n − x̄²). The fixed-point means of x and x² are each within
// ε = 2^-41 of the exact ones, so Σx²/n − x̄² is within ε(1 + 2|x̄| + 3ε) of its exact value,
// plus the double arithmetic's few roundings of x̄² (4·x̄²·2^-53): a spread within that is no
// spread (a constant pixel has an error of 0).
double independent_variance(FilmSum sum, FilmSum sum_sq, double n) {
    if (n < 2.0) return 0.0;
    const double mean = from_fixed(sum) / n;
    const double rounding =
        kFixedRounding * (1.0 + 2.0 * std::abs(mean) + 3.0 * kFixedRounding) + 4.0 * mean * mean * 0x1p-53;
    const double spread = std::max(0.0, from_fixed(sum_sq) / n - mean * mean - rounding);
    return spread / (n - 1.0);
}

}  // namespace

FilmLayout::FilmLayout(std::span<const Pass> passes, uint32_t lightgroups) {
    slots_.fill(kAbsent);
    for (const Pass pass : passes) {
        if (pass == Pass::Combined || slots_[index(pass)] != kAbsent) continue;
        const PassInfo& info = pass_info(pass);
        slots_[index(pass)] = count_;
        entries_[count_++] = {pass,          info.kind,          info.channels, sample_channels_,
                              sum_channels_, published_channels_};
        sample_channels_ += sample_channels(info);
        sum_channels_ += stored_channels(info);
        published_channels_ += info.channels;
    }
    lightgroups_ = lightgroups;
    lightgroup_sample_offset_ = sample_channels_;
    lightgroup_sum_offset_ = sum_channels_;
    lightgroup_published_offset_ = published_channels_;
    sample_channels_ += 3 * lightgroups;
    sum_channels_ += 3 * lightgroups;
    published_channels_ += 3 * lightgroups;
}

Film::Film(const PixelRegion& region, uint32_t frame_width, uint32_t frame_height, const PixelFilter& filter,
           std::span<const Pass> passes, bool light_paths, bool track_prefixes, CatcherCombined catcher,
           uint32_t lightgroups)
    : region_(region),
      frame_width_(frame_width),
      frame_height_(frame_height),
      filter_(filter),
      catcher_(catcher),
      layout_(film_passes(passes, track_prefixes, catcher), lightgroups),
      sums_(region.pixel_count() * sums_stride(), 0),
      counts_(region.pixel_count(), 0),
      splat_sums_(light_paths ? 3 * region.pixel_count() : 0, 0),
      prefix_sums_(layout_.has(Pass::Error) ? 9 * region.pixel_count() : 0, 0),
      prefix_counts_(tracks_prefixes() ? 3 * region.pixel_count() : 0, 0),
      estimates_(tracks_prefixes() ? region.pixel_count() : 0),
      published_(region.pixel_count() * published_stride(), 0.0f) {}

double Film::bytes_per_pixel(std::span<const Pass> passes, bool light_paths, bool track_prefixes,
                             CatcherCombined catcher, uint32_t lightgroups) {
    const FilmLayout layout(film_passes(passes, track_prefixes, catcher), lightgroups);
    const bool prefixes = layout.has(Pass::Error);
    return (4.0 + layout.sum_channels()) * sizeof(FilmSum) +
           (4.0 + layout.published_channels()) * sizeof(float) + sizeof(uint32_t) +
           (light_paths ? 3 * sizeof(FilmSum) : 0) +
           (prefixes ? 9 * sizeof(FilmSum) + 3 * sizeof(uint32_t) + sizeof(PixelErrorEstimate) : 0);
}

void Film::load_sums(size_t pixel, FilmSum* out) const {
    std::copy_n(&sums_[pixel * sums_stride()], sums_stride(), out);
}

void Film::store_sums(size_t pixel, const FilmSum* sums, uint32_t count) {
    std::copy_n(sums, sums_stride(), &sums_[pixel * sums_stride()]);
    counts_[pixel] = count;
    if (tracks_prefixes() && count > 0 && (count & (count - 1)) == 0) {
        // The levels move down one (P becomes P/2, P/2 becomes P/4) and P's sums come in.
        FilmSum* level = &prefix_sums_[9 * pixel];
        uint32_t* counts = &prefix_counts_[3 * pixel];
        std::copy_n(level, 6, level + 3);
        std::copy_n(sums, 3, level);
        counts[2] = counts[1];
        counts[1] = counts[0];
        counts[0] = count;
    }
}

Rgb Film::mean(size_t pixel) const {
    const FilmSum* sum = &sums_[pixel * sums_stride()];
    const double n = counts_[pixel];
    if (n == 0) return Rgb(0.0f);
    return Rgb(static_cast<float>(from_fixed(sum[0]) / n), static_cast<float>(from_fixed(sum[1]) / n),
               static_cast<float>(from_fixed(sum[2]) / n));
}

double Film::standard_error(size_t pixel, uint32_t c, bool with_gain) const {
    if (!layout_.has(Pass::Error)) return 0.0;
    const FilmSum* sum = &sums_[pixel * sums_stride()];
    const FilmSum* sum_sq = sum + 4 + layout_.entry(Pass::Error).sum_offset;
    const double gain =
        with_gain && !estimates_.empty() && estimates_[pixel].count > 0 ? estimates_[pixel].gain : 1.0;
    return std::sqrt(gain * independent_variance(sum[c], sum_sq[c], counts_[pixel]));
}

void Film::estimate_errors() {
    if (!tracks_prefixes()) return;
    const size_t pixels = region_.pixel_count();
    std::vector<PrefixMeans> prefixes(pixels);
    for (size_t p = 0; p < pixels; ++p) {
        const uint32_t* counts = &prefix_counts_[3 * p];
        const FilmSum* level = &prefix_sums_[9 * p];
        // The levels are nested prefixes only when each halves the one above (a pixel whose
        // sums were stored at other counts has none).
        const uint32_t levels = counts[0] >= 4 && counts[1] * 2 == counts[0] && counts[2] * 4 == counts[0] ? 3
                                : counts[0] >= 2 && counts[1] * 2 == counts[0]                             ? 2
                                                                               : 0;
        // The sums hold P samples (as they do when every pixel reaches a power of two).
        if (levels == 0 || counts_[p] != counts[0]) continue;
        prefixes[p].count = counts[0];
        prefixes[p].levels = levels;
        const FilmSum* sum = &sums_[p * sums_stride()];
        const FilmSum* sum_sq = sum + 4 + layout_.entry(Pass::Error).sum_offset;
        for (uint32_t c = 0; c < 3; ++c)
            prefixes[p].iid_variance += independent_variance(sum[c], sum_sq[c], counts[0]);
        for (uint32_t l = 0; l < levels; ++l)
            for (uint32_t c = 0; c < 3; ++c)
                prefixes[p].mean[l][c] = from_fixed(level[3 * l + c]) / counts[l];
    }
    std::vector<PixelErrorEstimate> estimates(pixels);
    estimate_pixel_errors(region_, prefixes, estimates);
    std::unique_lock lock(published_mutex_);
    estimates_ = std::move(estimates);
}

bool Film::add_sample(FilmSum* sums, uint32_t sample_index, Rgb radiance, float alpha,
                      const float* values) const {
    bool clamped = false;
    const auto fixed = [&](double v) { return to_fixed(v, kFixedSampleLimit, &clamped); };
    sums[0] += fixed(radiance.r);
    sums[1] += fixed(radiance.g);
    sums[2] += fixed(radiance.b);
    sums[3] += fixed(alpha);
    for (const FilmLayout::Entry& e : layout_.entries()) {
        FilmSum* sum = sums + 4 + e.sum_offset;
        const float* value = values + e.sample_offset;
        switch (e.kind) {
            case PassKind::Average:
                for (uint32_t c = 0; c < e.channels; ++c) sum[c] += fixed(value[c]);
                break;
            case PassKind::ShadowCatcher:
                for (uint32_t c = 0; c < kShadowCatcherSums; ++c) sum[c] += fixed(value[c]);
                break;
            case PassKind::FirstSample:
                if (sample_index == 0)
                    for (uint32_t c = 0; c < e.channels; ++c) sum[c] = fixed(value[c]);
                break;
            case PassKind::StandardError:
                sum[0] += fixed(static_cast<double>(radiance.r) * radiance.r);
                sum[1] += fixed(static_cast<double>(radiance.g) * radiance.g);
                sum[2] += fixed(static_cast<double>(radiance.b) * radiance.b);
                break;
            case PassKind::Radiance:
            case PassKind::SampleCount:
                break;
        }
    }
    FilmSum* groups = sums + 4 + layout_.lightgroup_sum_offset();
    const float* group_values = values + layout_.lightgroup_sample_offset();
    for (uint32_t c = 0; c < 3 * layout_.lightgroups(); ++c) groups[c] += fixed(group_values[c]);
    return clamped;
}

void Film::splat(Vec2 s, Rgb value, std::vector<Splat>& out) const {
    if (value.is_black() || !is_finite(value)) return;
    const float r = filter_.radius();
    const PixelRegion& g = region_;
    // Pixel centres c = k + ½ with |s − c| <= r.
    const float x_lo = std::max(std::ceil(s.x - r - 0.5f), static_cast<float>(g.x));
    const float x_hi = std::min(std::floor(s.x + r - 0.5f), static_cast<float>(g.x + g.width) - 1.0f);
    const float y_lo = std::max(std::ceil(s.y - r - 0.5f), static_cast<float>(g.y));
    const float y_hi = std::min(std::floor(s.y + r - 0.5f), static_cast<float>(g.y + g.height) - 1.0f);
    for (float y = y_lo; y <= y_hi; y += 1.0f) {
        for (float x = x_lo; x <= x_hi; x += 1.0f) {
            const float w = filter_.pdf({s.x - (x + 0.5f), s.y - (y + 0.5f)});
            if (!(w > 0.0f)) continue;
            const uint32_t px = static_cast<uint32_t>(x) - g.x, py = static_cast<uint32_t>(y) - g.y;
            out.push_back({py * g.width + px, value * w});
        }
    }
}

uint64_t Film::add_splats(std::span<const Splat> splats, uint64_t* clamped) {
    uint64_t dropped = 0;
    for (const Splat& sp : splats) {
        if (!is_finite(sp.value)) {
            ++dropped;
            continue;
        }
        bool over = false;
        splat_sums_[3 * sp.pixel] += to_fixed(sp.value.r, kFixedSplatLimit, &over);
        splat_sums_[3 * sp.pixel + 1] += to_fixed(sp.value.g, kFixedSplatLimit, &over);
        splat_sums_[3 * sp.pixel + 2] += to_fixed(sp.value.b, kFixedSplatLimit, &over);
        if (over) ++*clamped;
    }
    return dropped;
}

void Film::publish_pixel(size_t p, double n, const FilmSum* splats) {
    const FilmSum* sum = &sums_[p * sums_stride()];
    float* px = &published_[p * published_stride()];
    // Camera and splat sums are added exactly, then converted once.
    for (uint32_t c = 0; c < 3; ++c)
        px[c] = saturate_to_float(from_fixed(splats ? sum[c] + splats[c] : sum[c]) / n);
    px[3] = saturate_to_float(from_fixed(sum[3]) / n);
    // The other passes are of the camera samples of this pixel.
    const uint32_t count = counts_[p];
    if (count == 0) return;
    const double camera_samples = count;
    for (const FilmLayout::Entry& e : layout_.entries()) {
        const FilmSum* s = sum + 4 + e.sum_offset;
        float* out = px + 4 + e.published_offset;
        switch (e.kind) {
            case PassKind::Average:
                for (uint32_t c = 0; c < e.channels; ++c)
                    out[c] = saturate_to_float(from_fixed(s[c]) / camera_samples);
                break;
            case PassKind::FirstSample:
                for (uint32_t c = 0; c < e.channels; ++c) out[c] = saturate_to_float(from_fixed(s[c]));
                break;
            case PassKind::SampleCount:
                out[0] = static_cast<float>(count);
                break;
            case PassKind::StandardError:
                for (uint32_t c = 0; c < e.channels; ++c) out[c] = saturate_to_float(standard_error(p, c));
                break;
            case PassKind::ShadowCatcher: {
                std::array<double, kShadowCatcherSums> means;
                for (uint32_t c = 0; c < kShadowCatcherSums; ++c)
                    means[c] = from_fixed(s[c]) / camera_samples;
                const Rgb pass = shadow_catcher_pass(Rgb(px[0], px[1], px[2]), px[3], means.data());
                out[0] = pass.r;
                out[1] = pass.g;
                out[2] = pass.b;
                // Cycles shows the matte as Combined (its shadow catcher ratio reads Combined
                // first, so Combined is replaced after it).
                if (catcher_ != CatcherCombined::Off)
                    std::ranges::copy(matte_combined(catcher_, pass, means.data()), px);
                break;
            }
            case PassKind::Radiance:
                break;
        }
    }
    const FilmSum* groups = sum + 4 + layout_.lightgroup_sum_offset();
    float* group_out = px + 4 + layout_.lightgroup_published_offset();
    for (uint32_t c = 0; c < 3 * layout_.lightgroups(); ++c)
        group_out[c] = saturate_to_float(from_fixed(groups[c]) / camera_samples);
}

void Film::publish(uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1) {
    std::shared_lock lock(published_mutex_);
    for (uint32_t y = y0; y < y1; ++y) {
        for (uint32_t x = x0; x < x1; ++x) {
            const size_t p = region_.index(x, y);
            if (counts_[p] == 0) continue;
            publish_pixel(p, counts_[p], nullptr);
        }
    }
}

void Film::publish_all(uint32_t sample_indices) {
    std::unique_lock lock(published_mutex_);
    for (size_t p = 0; p < region_.pixel_count(); ++p)
        publish_pixel(p, sample_indices, splat_sums_.empty() ? nullptr : &splat_sums_[3 * p]);
}

bool Film::read(Pass pass, float* out) const {
    if (!layout_.has(pass)) return false;
    const uint32_t stride = published_stride();
    const uint32_t first = pass == Pass::Combined ? 0 : 4 + layout_.entry(pass).published_offset;
    const uint32_t channels = pass_info(pass).channels;
    std::unique_lock lock(published_mutex_);
    for (size_t p = 0; p < region_.pixel_count(); ++p)
        std::copy_n(&published_[p * stride + first], channels, out + p * channels);
    return true;
}

bool Film::read_lightgroup(uint32_t group, float* out) const {
    if (group == 0 || group > layout_.lightgroups()) return false;
    const uint32_t stride = published_stride();
    const uint32_t first = 4 + layout_.lightgroup_published_offset() + 3 * (group - 1);
    std::unique_lock lock(published_mutex_);
    for (size_t p = 0; p < region_.pixel_count(); ++p)
        std::copy_n(&published_[p * stride + first], 3, out + p * 3);
    return true;
}

}  // namespace stratum
