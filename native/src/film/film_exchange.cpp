// Film::sums_bytes / from_sums_bytes / add_sums: the exact sums of one frame's sample range,
// as bytes another process adds to its own (a frame's samples split over machines, e.g. the
// add-on's Dask client). Fixed-point sums (film/film.h) make the addition exact, so the films
// of ranges [0, k) and [k, n) added give the bits of one render of [0, n), in either order.
//
// | bytes (native byte order)                       | content                                  |
// |-------------------------------------------------|------------------------------------------|
// | 8                                               | kMagic "STRMSUMS"                        |
// | 11 × u32                                        | version, region x y w h, frame w h,      |
// |                                                 | light paths (0/1), sample begin, end,    |
// |                                                 | what Combined shows of shadow catchers,  |
// |                                                 | light groups                             |
// | u32 + u32 per pass                              | the passes besides Combined, in order    |
// | u32 per pixel                                   | camera samples summed                    |
// | 16 per sum (__int128), sums_stride() per pixel  | camera sums                              |
// | 16 × 3 per pixel, films with light paths        | splat sums                               |
//
// Merging rules: Average, Combined, Standard Error and splat sums add; the counts add (Sample
// Count); FirstSample passes keep the values of the range that holds sample index 0. The
// addition is of sums of the same frame (region, frame size, passes, light paths) over sample
// ranges that meet ([a, b) + [b, c) = [a, c)), so a merge cannot count a sample twice.
#include <algorithm>
#include <cstring>

#include "film/film.h"

namespace stratum {

namespace {

constexpr char kMagic[8] = {'S', 'T', 'R', 'M', 'S', 'U', 'M', 'S'};
constexpr uint32_t kVersion = 2;
constexpr size_t kHeaderWords = 12;

// Copies into bytes sized in advance (vector::insert of raw bytes trips GCC 12's bounds warnings).
class Writer {
public:
    explicit Writer(std::vector<uint8_t>& out) : out_(out) {}
    void put(const void* data, size_t n) {
        if (n == 0) return;
        std::memcpy(out_.data() + at_, data, n);
        at_ += n;
    }

private:
    std::vector<uint8_t>& out_;
    size_t at_ = 0;
};

// Reads sequentially from the bytes; ok() turns false at the first read past their end.
class Reader {
public:
    explicit Reader(std::span<const uint8_t> bytes) : bytes_(bytes) {}
    bool read(void* out, size_t n) {
        if (n > bytes_.size() - at_) {
            at_ = bytes_.size();
            ok_ = false;
            return false;
        }
        // An empty destination may be null (an empty vector's data()): memcpy must not see it.
        if (n == 0) return true;
        std::memcpy(out, bytes_.data() + at_, n);
        at_ += n;
        return true;
    }
    bool ok() const { return ok_; }
    size_t left() const { return bytes_.size() - at_; }

private:
    std::span<const uint8_t> bytes_;
    size_t at_ = 0;
    bool ok_ = true;
};

}  // namespace

std::vector<uint8_t> Film::sums_bytes() const {
    const auto entries = layout_.entries();
    std::vector<uint8_t> out(sizeof kMagic + kHeaderWords * sizeof(uint32_t) +
                             (1 + entries.size()) * sizeof(uint32_t) + counts_.size() * sizeof(uint32_t) +
                             (sums_.size() + splat_sums_.size()) * sizeof(FilmSum));
    Writer w(out);
    w.put(kMagic, sizeof kMagic);
    const uint32_t header[kHeaderWords] = {kVersion,
                                           region_.x,
                                           region_.y,
                                           region_.width,
                                           region_.height,
                                           frame_width_,
                                           frame_height_,
                                           has_light_paths() ? 1u : 0u,
                                           sample_begin_,
                                           sample_end_,
                                           static_cast<uint32_t>(catcher_),
                                           layout_.lightgroups()};
    w.put(header, sizeof header);
    const uint32_t passes = static_cast<uint32_t>(entries.size());
    w.put(&passes, sizeof passes);
    for (const FilmLayout::Entry& e : entries) {
        const uint32_t pass = static_cast<uint32_t>(e.pass);
        w.put(&pass, sizeof pass);
    }
    w.put(counts_.data(), counts_.size() * sizeof(uint32_t));
    w.put(sums_.data(), sums_.size() * sizeof(FilmSum));
    w.put(splat_sums_.data(), splat_sums_.size() * sizeof(FilmSum));
    return out;
}

std::unique_ptr<Film> Film::from_sums_bytes(std::span<const uint8_t> bytes, std::string* error) {
    Reader in(bytes);
    char magic[sizeof kMagic] = {};
    uint32_t h[kHeaderWords] = {};
    if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0 ||
        !in.read(h, sizeof h)) {
        *error = "not a Stratum film's sums (no STRMSUMS header)";
        return nullptr;
    }
    if (h[0] != kVersion) {
        *error = "film sums of version " + std::to_string(h[0]) + ", this library reads version " +
                 std::to_string(kVersion);
        return nullptr;
    }
    const PixelRegion region{h[1], h[2], h[3], h[4]};
    const uint32_t frame_width = h[5], frame_height = h[6];
    if (region.width == 0 || region.height == 0 || h[7] > 1 || h[8] > h[9] ||
        h[10] > static_cast<uint32_t>(CatcherCombined::MatteWithShadowOverBackground) ||
        h[11] > kMaxLightGroups || uint64_t{region.x} + region.width > frame_width ||
        uint64_t{region.y} + region.height > frame_height) {
        *error = "film sums with an inconsistent header (region, frame or sample range)";
        return nullptr;
    }
    uint32_t pass_count = 0;
    in.read(&pass_count, sizeof pass_count);
    if (pass_count >= kPasses.size()) {
        *error = "film sums naming " + std::to_string(pass_count) + " passes";
        return nullptr;
    }
    std::vector<Pass> passes(pass_count);
    for (Pass& pass : passes) {
        uint32_t value = 0;
        in.read(&value, sizeof value);
        if (value == 0 || value >= kPasses.size()) {
            *error = "film sums naming an unknown pass " + std::to_string(value);
            return nullptr;
        }
        pass = static_cast<Pass>(value);
    }
    const bool light_paths = h[7] == 1;
    // The sizes the header implies, checked before a film of that size is allocated.
    const auto catcher = static_cast<CatcherCombined>(h[10]);
    if (catcher != CatcherCombined::Off &&
        std::find(passes.begin(), passes.end(), Pass::ShadowCatcher) == passes.end()) {
        *error = "film sums of a shadow catcher's matte without the Shadow Catcher pass's sums";
        return nullptr;
    }
    const FilmLayout layout(passes, h[11]);
    const uint64_t pixels = region.pixel_count();
    const uint64_t expected = pixels * (sizeof(uint32_t) + (4 + layout.sum_channels()) * sizeof(FilmSum) +
                                        (light_paths ? 3 * sizeof(FilmSum) : 0));
    if (!in.ok() || in.left() != expected) {
        *error = "film sums of " + std::to_string(bytes.size()) + " bytes: the header's " +
                 std::to_string(region.width) + " x " + std::to_string(region.height) +
                 " pixels and passes do not match that size";
        return nullptr;
    }
    // The filter only shapes new samples and splats; a film made from sums publishes them.
    auto film = std::make_unique<Film>(region, frame_width, frame_height, PixelFilter(FilterType::Box, 1.0f),
                                       passes, light_paths, false, catcher, h[11]);
    in.read(film->counts_.data(), film->counts_.size() * sizeof(uint32_t));
    in.read(film->sums_.data(), film->sums_.size() * sizeof(FilmSum));
    in.read(film->splat_sums_.data(), film->splat_sums_.size() * sizeof(FilmSum));
    film->set_sample_range(h[8], h[9]);
    film->publish_everything();
    return film;
}

std::string Film::add_sums(const Film& other) {
    const PixelRegion& a = region_;
    const PixelRegion& b = other.region_;
    if (a.x != b.x || a.y != b.y || a.width != b.width || a.height != b.height ||
        frame_width_ != other.frame_width_ || frame_height_ != other.frame_height_)
        return "the sums are of another frame or border region";
    if (has_light_paths() != other.has_light_paths()) return "the sums are of another integrator";
    if (catcher_ != other.catcher_) return "the sums show shadow catchers otherwise (another film setting)";
    if (layout_.lightgroups() != other.layout_.lightgroups()) return "the sums are of other light groups";
    const auto ea = layout_.entries(), eb = other.layout_.entries();
    if (ea.size() != eb.size() || !std::equal(ea.begin(), ea.end(), eb.begin(),
                                              [](const auto& x, const auto& y) { return x.pass == y.pass; }))
        return "the sums are of other passes";
    if (other.sample_end_ != sample_begin_ && other.sample_begin_ != sample_end_)
        return "the sums' sample indices [" + std::to_string(other.sample_begin_) + ", " +
               std::to_string(other.sample_end_) + ") do not meet this film's [" +
               std::to_string(sample_begin_) + ", " + std::to_string(sample_end_) + ")";
    const bool other_holds_first = other.sample_begin_ == 0 && other.sample_end_ > 0;
    const uint32_t stride = sums_stride();
    for (size_t p = 0; p < region_.pixel_count(); ++p) {
        FilmSum* sum = &sums_[p * stride];
        const FilmSum* add = &other.sums_[p * stride];
        for (uint32_t c = 0; c < 4; ++c) sum[c] += add[c];
        for (const FilmLayout::Entry& e : layout_.entries()) {
            for (uint32_t c = 0; c < stored_channels(pass_info(e.pass)); ++c) {
                FilmSum& to = sum[4 + e.sum_offset + c];
                const FilmSum from = add[4 + e.sum_offset + c];
                to = e.kind == PassKind::FirstSample ? (other_holds_first ? from : to) : to + from;
            }
        }
        for (uint32_t c = 0; c < 3 * layout_.lightgroups(); ++c)
            sum[4 + layout_.lightgroup_sum_offset() + c] += add[4 + layout_.lightgroup_sum_offset() + c];
        counts_[p] += other.counts_[p];
    }
    for (size_t i = 0; i < splat_sums_.size(); ++i) splat_sums_[i] += other.splat_sums_[i];
    // Prefix sums are of one render's samples: the combined pixels have none, and their error
    // is the independent-samples estimate (film/film.h).
    prefix_sums_.clear();
    prefix_counts_.clear();
    estimates_.clear();
    set_sample_range(std::min(sample_begin_, other.sample_begin_), std::max(sample_end_, other.sample_end_));
    publish_everything();
    return {};
}

void Film::publish_everything() {
    if (has_light_paths())
        publish_all(sample_end_ - sample_begin_);
    else
        publish(region_.x, region_.x + region_.width, region_.y, region_.y + region_.height);
}

}  // namespace stratum
