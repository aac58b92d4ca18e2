// The models of one kind (light types, closure models), filed by their C ABI value: the table a
// registry file fills with one line per model, and what the ABI's stratum_model_* list. The
// value → model lookup is one bounds check and one load, on the shading path.
//
// | parameter | meaning                                                                  |
// |-----------|--------------------------------------------------------------------------|
// | Model     | what a model answers (LightModel, ClosureModel)                          |
// | kSize     | values are 0 .. kSize − 1                                                |
// | name      | the ABI enumerator's name in lower case, without its prefix ("spot_v1"):  |
// |           | hosts look values up by it, so they mirror no number                     |
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>

namespace stratum {

template <class Model, int32_t kSize>
class ModelTable {
public:
    struct Entry {
        int32_t value = -1;
        const char* name = nullptr;
        const Model* model = nullptr;
    };

    // constexpr, so that a registry is filled at compile time (constinit: no static-initialisation
    // order to mind). A repeated or out-of-range value is a compile error there.
    constexpr ModelTable(std::initializer_list<Entry> entries) {
        for (const Entry& e : entries) {
            if (!add(e)) throw "ModelTable: value out of range or listed twice";
        }
    }

    // The model filed under `value`, or null.
    const Model* find(int32_t value) const {
        return value >= 0 && value < kSize ? entries_[static_cast<uint32_t>(value)].model : nullptr;
    }

    // Files `e` under a value that has none; false when the value is out of range or taken.
    constexpr bool add(const Entry& e) {
        if (e.value < 0 || e.value >= kSize || entries_[static_cast<uint32_t>(e.value)].model) return false;
        entries_[static_cast<uint32_t>(e.value)] = e;
        ++count_;
        return true;
    }

    // The models in value order: `index` runs over 0 .. count() − 1.
    int32_t count() const { return count_; }
    const Entry* entry(int32_t index) const {
        for (const Entry& e : entries_) {
            if (e.model && index-- == 0) return &e;
        }
        return nullptr;
    }

private:
    std::array<Entry, static_cast<uint32_t>(kSize)> entries_{};
    int32_t count_ = 0;
};

}  // namespace stratum
