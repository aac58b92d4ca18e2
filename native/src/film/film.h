// The film: what camera samples and light paths leave in the pixels of the rendered region.
// It owns the pixel filter, the per-pixel sums, the sample counts, the light paths' splats and
// the passes (AOVs, film/passes.h) a render asked for, and publishes the averaged image the
// host reads while the render runs.
//
// Exact sums: every sum is a fixed-point integer (FilmSum, kFixedScale units per 1.0), so
// addition is exact, associative and commutative. The image is therefore bit-identical for any
// thread count, any order of splats, and any split of a frame's sample indices into ranges
// rendered apart (by other processes or machines) whose sums are added afterwards
// (film/film_exchange.cpp). Sums become double only when published.
//
// | quantity               | value / bound                                                  |
// |------------------------|----------------------------------------------------------------|
// | kFixedScale            | 2^40 units per 1.0: a sample is rounded to within 2^-41 ≈ 4.5e-13 |
// | kFixedSampleLimit      | 2^55 ≈ 3.6e16: a sample's magnitude (and a squared radiance of |
// |                        | the error pass) is clamped there and counted (a notice)        |
// | camera sums            | < 2^32 samples × 2^55 × 2^40 = 2^127: fits __int128            |
// | kFixedSplatLimit       | 2^45 ≈ 3.5e13 per splat: 2^42 splats per pixel fit             |
//
// | published value        | formula                                                        |
// |------------------------|----------------------------------------------------------------|
// | without light paths    | sum of the pixel's camera samples / their count                |
// | with light paths       | (camera sample sum + splat sum) / sample indices done (all     |
// |                        | pixels at once, when a pass of light paths ends)               |
// | Average passes         | sum / count of the pixel's camera samples                      |
// | FirstSample passes     | the value of sample index 0                                    |
// | Debug Sample Count     | the count of the pixel's camera samples                        |
// | Stratum Error          | sqrt(G·(Σx²/n − x̄²)/(n − 1)) per RGB channel over the pixel's  |
// |                        | n camera samples x (0 for n < 2; light-path splats not         |
// |                        | included), G the sampler's gain film/error_estimate.h measures |
// |                        | from the prefixes (1 before estimate_errors() ran, and for     |
// |                        | films combined from sample ranges rendered apart)              |
//
// Prefix tracking (films with the Stratum Error pass or adaptive sampling, which adds the pass's
// sums of squares to its film): at each power-of-two count P a pixel's RGB sums are kept, with
// those at P/2 and P/4, so that estimate_errors() can measure the error of its mean from its
// nested prefixes. They are this render's own: the
// exchange of sums between renders does not carry them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <shared_mutex>
#include <span>
#include <string>
#include <vector>

#include "core/math.h"
#include "film/error_estimate.h"
#include "film/light_groups.h"
#include "film/passes.h"
#include "film/pixel_filter.h"
#include "film/pixel_region.h"
#include "film/shadow_catcher_film.h"
#include "scene/camera.h"

namespace stratum {

// A fixed-point sum: value × kFixedScale, rounded to an integer.
__extension__ typedef __int128 FilmSum;
inline constexpr double kFixedScale = 0x1p40;
// The largest error of one sample rounded to fixed point: half a unit.
inline constexpr double kFixedRounding = 0.5 / kFixedScale;
inline constexpr double kFixedSampleLimit = 0x1p55;
inline constexpr double kFixedSplatLimit = 0x1p45;

// v in fixed point, its magnitude clamped to `limit`; *clamped is set when it was.
inline FilmSum to_fixed(double v, double limit, bool* clamped) {
    if (v > limit || v < -limit) {
        *clamped = true;
        v = v > 0 ? limit : -limit;
    }
    // v·2^40 is exact (a power-of-two scale); rounding it to an integer is the only error.
    const double scaled = std::nearbyint(v * kFixedScale);
    // Nearly every sample fits 64 bits, whose conversion is one instruction where the 128-bit
    // one is a library call; both are exact for an integer-valued double in range.
    if (std::abs(scaled) < 0x1p62) return static_cast<int64_t>(scaled);
    return static_cast<FilmSum>(scaled);
}
// The double nearest to a fixed-point sum (the int128 → double conversion rounds to nearest;
// the scale by 2^-40 is exact).
inline double from_fixed(FilmSum s) { return static_cast<double>(s) / kFixedScale; }

// Where the channels of each enabled pass (other than Combined) sit: among the values an
// integrator writes per camera sample, among the doubles the film sums per pixel (after
// Combined's 4), and among the floats it publishes per pixel (after Combined's 4). After the
// passes come the light groups' RGB (film/light_groups.h), 3 channels per group in each.
class FilmLayout {
public:
    struct Entry {
        Pass pass;
        PassKind kind;
        uint32_t channels;
        uint32_t sample_offset, sum_offset, published_offset;
    };

    FilmLayout() { slots_.fill(kAbsent); }
    explicit FilmLayout(std::span<const Pass> passes, uint32_t lightgroups = 0);
    bool has(Pass pass) const { return pass == Pass::Combined || slots_[index(pass)] != kAbsent; }
    // The placement of a held pass other than Combined (only for has(pass)).
    const Entry& entry(Pass pass) const { return entries_[slots_[index(pass)]]; }
    std::span<const Entry> entries() const { return {entries_.data(), count_}; }
    // Channels the integrator writes per camera sample (Average and FirstSample passes).
    uint32_t extra_channels() const { return sample_channels_; }
    // Doubles summed and floats published per pixel besides Combined's 4.
    uint32_t sum_channels() const { return sum_channels_; }
    uint32_t published_channels() const { return published_channels_; }
    // The light groups (group k = 1..lightgroups()) and where their first channel sits.
    uint32_t lightgroups() const { return lightgroups_; }
    uint32_t lightgroup_sample_offset() const { return lightgroup_sample_offset_; }
    uint32_t lightgroup_sum_offset() const { return lightgroup_sum_offset_; }
    uint32_t lightgroup_published_offset() const { return lightgroup_published_offset_; }

private:
    static constexpr uint32_t kAbsent = ~0u;
    static size_t index(Pass pass) { return static_cast<size_t>(pass); }
    std::array<uint32_t, kPasses.size()> slots_{};
    std::array<Entry, kPasses.size()> entries_{};
    uint32_t count_ = 0;
    uint32_t sample_channels_ = 0, sum_channels_ = 0, published_channels_ = 0;
    uint32_t lightgroups_ = 0;
    uint32_t lightgroup_sample_offset_ = 0, lightgroup_sum_offset_ = 0, lightgroup_published_offset_ = 0;
};

// The extra pass values of one camera sample, written by the integrator. Passes the render did
// not ask for (or that the film derives itself) are not stored, so writing them costs nothing.
// `camera` is the render's camera, for the passes measured in its space (Depth, Denoising Normal).
class PassValues {
public:
    PassValues() = default;
    PassValues(const FilmLayout* layout, float* values, const Camera* camera = nullptr)
        : layout_(layout), values_(values), camera_(camera) {}
    bool wants(Pass pass) const {
        return layout_ && !lightgroups_only_ && pass != Pass::Combined && layout_->has(pass) &&
               sample_channels(pass_info(pass)) > 0;
    }
    // Whether any pass the integrator writes is held.
    bool any() const { return layout_ && !lightgroups_only_ && layout_->extra_channels() > 0; }
    // The same values, of which only the light groups take writes (for the catcher-only copy of a
    // path, integrators/shadow_catcher.h, whose other passes are the main path's).
    PassValues lightgroups_only() const {
        PassValues v = *this;
        v.lightgroups_only_ = true;
        return v;
    }
    // Adds `value` to light group `group` (1..layout lightgroups(); 0 = none, and groups the film
    // does not hold, take nothing).
    void add_lightgroup(uint32_t group, Rgb value) {
        if (!layout_ || group == 0 || group > layout_->lightgroups()) return;
        float* out = values_ + layout_->lightgroup_sample_offset() + 3 * (group - 1);
        out[0] += value.r;
        out[1] += value.g;
        out[2] += value.b;
    }
    const Camera* camera() const { return camera_; }
    void write(Pass pass, Vec3 v) {
        if (!wants(pass) || pass_info(pass).channels != 3) return;
        float* out = values_ + layout_->entry(pass).sample_offset;
        out[0] = v.x;
        out[1] = v.y;
        out[2] = v.z;
    }
    void write(Pass pass, float v) {
        if (!wants(pass) || pass_info(pass).channels != 1) return;
        values_[layout_->entry(pass).sample_offset] = v;
    }
    void write(const ShadowCatcherSample& sample) {
        if (!wants(Pass::ShadowCatcher)) return;
        const auto v = sample.values();
        std::copy(v.begin(), v.end(), values_ + layout_->entry(Pass::ShadowCatcher).sample_offset);
    }

private:
    const FilmLayout* layout_ = nullptr;
    float* values_ = nullptr;
    const Camera* camera_ = nullptr;
    bool lightgroups_only_ = false;
};

// One light path's contribution to one pixel of the rendered region.
struct Splat {
    uint32_t pixel;  // PixelRegion::index of the pixel
    Rgb value;
};

class Film {
public:
    // `passes`: the passes besides Combined; `light_paths`: whether splats will be added;
    // `track_prefixes`: keep the prefix sums of error estimates (always with the Error pass);
    // `catcher`: what Combined shows of a scene with shadow catchers (not Off: the film holds the
    // Shadow Catcher pass's sums, film/shadow_catcher_film.h); `lightgroups`: the light groups'
    // passes it holds (film/light_groups.h).
    Film(const PixelRegion& region, uint32_t frame_width, uint32_t frame_height, const PixelFilter& filter,
         std::span<const Pass> passes, bool light_paths, bool track_prefixes = false,
         CatcherCombined catcher = CatcherCombined::Off, uint32_t lightgroups = 0);
    // The memory a film of these passes takes per pixel (for the renderer's memory budget).
    static double bytes_per_pixel(std::span<const Pass> passes, bool light_paths, bool track_prefixes = false,
                                  CatcherCombined catcher = CatcherCombined::Off, uint32_t lightgroups = 0);

    const PixelRegion& region() const { return region_; }
    uint32_t frame_width() const { return frame_width_; }
    uint32_t frame_height() const { return frame_height_; }
    const PixelFilter& filter() const { return filter_; }
    const FilmLayout& layout() const { return layout_; }
    bool has_light_paths() const { return !splat_sums_.empty(); }
    bool tracks_prefixes() const { return !prefix_sums_.empty(); }
    CatcherCombined catcher_combined() const { return catcher_; }

    // A copy of the pixel's sums: the thread adds a pass's samples to it and stores it back with
    // store_sums only if the pass completed (a pixel cancelled mid-pass keeps its previous sum).
    // `count` is the number of camera samples the sums hold.
    void load_sums(size_t pixel, FilmSum* out) const;
    void store_sums(size_t pixel, const FilmSum* sums, uint32_t count);
    // Recomputes every pixel's gain G from its prefix sums (films that track prefixes; not while
    // samples are stored): called when the pixels reach a power-of-two count. Not for
    // independent samples, whose gain is known: G = 1, s²/n is unbiased.
    void estimate_errors();
    // The estimated standard error of channel c of the pixel's Combined mean: what the Error
    // pass shows (films that track prefixes or hold the Error pass); without the gain, the
    // independent-samples estimate s/√n (what adaptive sampling stops on).
    double standard_error(size_t pixel, uint32_t c, bool with_gain = true) const;
    // The pixel's camera samples and the mean of its Combined RGB.
    uint32_t sample_count(size_t pixel) const { return counts_[pixel]; }
    Rgb mean(size_t pixel) const;
    // Sums per pixel in load_sums / store_sums.
    uint32_t sums_stride() const { return 4 + layout_.sum_channels(); }
    // Adds camera sample `sample_index` (radiance, alpha and the integrator's pass values) to a
    // pixel's sums loaded with load_sums; returns whether a value was clamped (kFixedSampleLimit).
    bool add_sample(FilmSum* sums, uint32_t sample_index, Rgb radiance, float alpha,
                    const float* values) const;

    // The splats of a contribution reaching film point s (full-frame pixel units): every pixel
    // of the region whose centre lies within the filter's radius, weighted by the filter
    // density at its offset (PixelFilter::pdf). Non-finite or black values give none.
    void splat(Vec2 s, Rgb value, std::vector<Splat>& out) const;
    // Adds splats; returns how many were dropped as not finite. *clamped counts those clamped
    // to kFixedSplatLimit.
    uint64_t add_splats(std::span<const Splat> splats, uint64_t* clamped);

    // Publishes the pixels [x0, x1) x [y0, y1) (full-frame coordinates) that have samples:
    // concurrent calls must cover disjoint pixels. Films without light paths only.
    void publish(uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1);
    // Publishes every pixel with `sample_indices` done (films with light paths).
    void publish_all(uint32_t sample_indices);
    // The published values of `pass` (its channels per pixel, rows bottom to top); false when
    // the film does not hold the pass. out holds region().pixel_count() * channels floats.
    bool read(Pass pass, float* out) const;
    // The published RGB of light group `group` (1..layout().lightgroups()); false when the film
    // does not hold it. out holds region().pixel_count() * 3 floats.
    bool read_lightgroup(uint32_t group, float* out) const;

    // The sample indices [begin, end) every pixel's sums hold (set by the renderer as passes end).
    void set_sample_range(uint32_t begin, uint32_t end) {
        sample_begin_ = begin;
        sample_end_ = end;
    }
    uint32_t sample_begin() const { return sample_begin_; }
    uint32_t sample_end() const { return sample_end_; }

    // Exchange of exact sums between renders of one frame (film/film_exchange.cpp): the bytes
    // of a film's frame, passes, sample range, counts and sums; a film made from them (nullptr
    // and *error set when they are not such bytes); and the addition of another film's sums of
    // an adjacent sample range (an error message when the films are not of the same frame and
    // passes, or the ranges do not meet), after which every pixel is published again.
    std::vector<uint8_t> sums_bytes() const;
    static std::unique_ptr<Film> from_sums_bytes(std::span<const uint8_t> bytes, std::string* error);
    std::string add_sums(const Film& other);
    // Publishes every pixel from its sums (after they were read or added).
    void publish_everything();

private:
    void publish_pixel(size_t p, double n, const FilmSum* splats);

    PixelRegion region_;
    uint32_t frame_width_, frame_height_;
    PixelFilter filter_;
    CatcherCombined catcher_;
    FilmLayout layout_;
    uint32_t published_stride() const { return 4 + layout_.published_channels(); }

    std::vector<FilmSum> sums_;        // sums_stride() per pixel
    std::vector<uint32_t> counts_;     // camera samples summed per pixel
    std::vector<FilmSum> splat_sums_;  // RGB per pixel, when light paths splat
    // Prefix tracking: RGB sums at the last three power-of-two counts P, P/2, P/4 (9 per pixel)
    // and those counts (3 per pixel, 0 = none); the estimates made from them.
    std::vector<FilmSum> prefix_sums_;
    std::vector<uint32_t> prefix_counts_;
    std::vector<PixelErrorEstimate> estimates_;
    uint32_t sample_begin_ = 0, sample_end_ = 0;
    // Published values (published_stride() per pixel). Tiles publish disjoint pixels under a
    // shared lock; read() takes it exclusively.
    mutable std::shared_mutex published_mutex_;
    std::vector<float> published_;
};

}  // namespace stratum
