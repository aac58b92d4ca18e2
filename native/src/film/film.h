// The film: what camera samples and light paths leave in the pixels of the rendered region.
// It owns the pixel filter, the per-pixel sums (radiance and alpha in double, so that samples
// near FLT_MAX do not overflow a mean that is finite), the sample counts, the light paths'
// splats and the passes (AOVs, film/passes.h) a render asked for, and publishes the averaged
// image the host reads while the render runs.
//
// Determinism: each pixel's camera samples are summed by one thread in sample-index order
// (CameraSampleSums), and splats are added in the order the renderer hands them over, so the
// image is bit-identical for any thread count.
//
// | published value        | formula                                                        |
// |------------------------|----------------------------------------------------------------|
// | without light paths    | sum of the pixel's camera samples / their count                |
// | with light paths       | (camera sample sum + splat sum) / sample indices done (all     |
// |                        | pixels at once, when a pass of light paths ends)               |
// | Average passes         | sum / count of the pixel's camera samples                      |
#pragma once

#include <array>
#include <cstdint>
#include <shared_mutex>
#include <span>
#include <vector>

#include "core/math.h"
#include "film/passes.h"
#include "film/pixel_filter.h"
#include "film/pixel_region.h"

namespace stratum {

// Where the channels of each enabled pass (other than Combined) sit in a sample's values.
class FilmLayout {
public:
    FilmLayout() { offsets_.fill(kAbsent); }
    explicit FilmLayout(std::span<const Pass> passes);
    bool has(Pass pass) const { return pass == Pass::Combined || offsets_[index(pass)] != kAbsent; }
    // Offset of the pass's first channel among the extra channels (only for has(pass)).
    uint32_t offset(Pass pass) const { return offsets_[index(pass)]; }
    // Channels of the enabled passes other than Combined.
    uint32_t extra_channels() const { return extra_channels_; }

private:
    static constexpr uint32_t kAbsent = ~0u;
    static size_t index(Pass pass) { return static_cast<size_t>(pass); }
    std::array<uint32_t, kPasses.size()> offsets_{};
    uint32_t extra_channels_ = 0;
};

// The extra pass values of one camera sample, written by the integrator. Passes the render did
// not ask for are not stored, so writing them costs nothing.
class PassValues {
public:
    PassValues() = default;
    PassValues(const FilmLayout* layout, float* values) : layout_(layout), values_(values) {}
    bool wants(Pass pass) const { return layout_ && pass != Pass::Combined && layout_->has(pass); }
    void write(Pass pass, Vec3 v) {
        if (!wants(pass)) return;
        float* out = values_ + layout_->offset(pass);
        out[0] = v.x;
        out[1] = v.y;
        out[2] = v.z;
    }

private:
    const FilmLayout* layout_ = nullptr;
    float* values_ = nullptr;
};

// One light path's contribution to one pixel of the rendered region.
struct Splat {
    uint32_t pixel;  // PixelRegion::index of the pixel
    Rgb value;
};

class Film {
public:
    // `passes`: the passes besides Combined; `light_paths`: whether splats will be added.
    Film(const PixelRegion& region, uint32_t frame_width, uint32_t frame_height, const PixelFilter& filter,
         std::span<const Pass> passes, bool light_paths);
    // The memory a film of these passes takes per pixel (for the renderer's memory budget).
    static double bytes_per_pixel(std::span<const Pass> passes, bool light_paths);

    const PixelRegion& region() const { return region_; }
    uint32_t frame_width() const { return frame_width_; }
    uint32_t frame_height() const { return frame_height_; }
    const PixelFilter& filter() const { return filter_; }
    const FilmLayout& layout() const { return layout_; }
    bool has_light_paths() const { return !splat_sums_.empty(); }

    // A copy of the pixel's sums: the thread adds a pass's samples to it and stores it back with
    // store_sums only if the pass completed (a pixel cancelled mid-pass keeps its previous sum).
    void load_sums(size_t pixel, double* out) const;
    void store_sums(size_t pixel, const double* sums, uint32_t count);
    // Doubles per pixel in load_sums / store_sums.
    uint32_t sums_stride() const { return 4 + layout_.extra_channels(); }

    // The splats of a contribution reaching film point s (full-frame pixel units): every pixel
    // of the region whose centre lies within the filter's radius, weighted by the filter
    // density at its offset (PixelFilter::pdf). Non-finite or black values give none.
    void splat(Vec2 s, Rgb value, std::vector<Splat>& out) const;
    // Adds splats in order; returns how many were dropped as not finite.
    uint64_t add_splats(std::span<const Splat> splats);

    // Publishes the pixels [x0, x1) x [y0, y1) (full-frame coordinates) that have samples:
    // concurrent calls must cover disjoint pixels. Films without light paths only.
    void publish(uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1);
    // Publishes every pixel with `sample_indices` done (films with light paths).
    void publish_all(uint32_t sample_indices);
    // The published values of `pass` (its channels per pixel, rows bottom to top); false when
    // the film does not hold the pass. out holds region().pixel_count() * channels floats.
    bool read(Pass pass, float* out) const;

private:
    void publish_pixel(size_t p, double n, const double* splats);

    PixelRegion region_;
    uint32_t frame_width_, frame_height_;
    PixelFilter filter_;
    FilmLayout layout_;
    std::vector<double> sums_;        // sums_stride() per pixel
    std::vector<uint32_t> counts_;    // camera samples summed per pixel
    std::vector<double> splat_sums_;  // RGB per pixel, when light paths splat
    // Published values (4 + extra channels per pixel). Tiles publish disjoint pixels under a
    // shared lock; read() takes it exclusively.
    mutable std::shared_mutex published_mutex_;
    std::vector<float> published_;
};

}  // namespace stratum
