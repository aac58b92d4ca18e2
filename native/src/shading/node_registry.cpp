#include "shading/node_registry.h"

#include <cstring>

namespace stratum {

namespace {

// Constant-initialised: node files fill them during dynamic initialisation, in whatever order the
// objects' initialisers run, so they must hold their initial state before any of them does.
constinit NodeRegistry g_registry;
// The first registration that was not filed, or null.
constinit const NodeEntry* g_refused = nullptr;

std::string describe(const NodeEntry& e) {
    return std::string("shader node '") + (e.name ? e.name : "") + "' (value " + std::to_string(e.value) +
           ")";
}

}  // namespace

std::string NodeRegistry::conflict(const NodeEntry& entry) const {
    if (entry.value < 0 || entry.value >= kValueLimit)
        return describe(entry) + ": the value is outside [0, " + std::to_string(kValueLimit) + ")";
    if (entry.name == nullptr || entry.name[0] == '\0') return describe(entry) + ": it has no name";
    if (entry.evaluate == nullptr || entry.check == nullptr)
        return describe(entry) + ": it has no check or no evaluation";
    if (const NodeEntry* taken = find(entry.value))
        return describe(entry) + ": value " + std::to_string(entry.value) + " is filed already, by '" +
               taken->name + "'";
    for (const NodeEntry* e : by_value_) {
        if (e && std::strcmp(e->name, entry.name) == 0)
            return describe(entry) + ": the name is filed already, with value " + std::to_string(e->value);
    }
    return "";
}

std::string NodeRegistry::file(const NodeEntry& entry) {
    std::string problem = conflict(entry);
    if (problem.empty()) {
        by_value_[static_cast<uint32_t>(entry.value)] = &entry;
        ++count_;
    }
    return problem;
}

const NodeEntry* NodeRegistry::listed(int32_t index) const {
    for (const NodeEntry* e : by_value_) {
        if (e && index-- == 0) return e;
    }
    return nullptr;
}

NodeRegistration::NodeRegistration(const NodeEntry& entry) noexcept : entry_(entry) {
    // Filing allocates only the message of a refused entry; should even that fail, the entry is
    // still marked refused, and node_registry_problem() builds the message again when asked.
    try {
        if (!g_registry.file(entry_).empty() && g_refused == nullptr) g_refused = &entry_;
    } catch (...) {
        if (g_refused == nullptr) g_refused = &entry_;
    }
}

const NodeRegistry& node_registry() { return g_registry; }

std::string node_registry_problem() {
    if (g_refused == nullptr) return "";
    // The registry does not change after static initialisation: the conflict reads as it did.
    const std::string problem = g_registry.conflict(*g_refused);
    return problem.empty() ? describe(*g_refused) + ": it was not filed" : problem;
}

std::string check_mode(const ShaderNode& node, int index, const char* what, int32_t count) {
    const int32_t v = node.modes[index];
    if (v >= 0 && v < count) return "";
    return "mode " + std::to_string(index) + " (" + what + ") is " + std::to_string(v) + "; 0.." +
           std::to_string(count - 1);
}

}  // namespace stratum
