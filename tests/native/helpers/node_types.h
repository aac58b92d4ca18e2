// Shader node types by name, as hosts find them: the library's listing (stratum_model_entry with
// STRATUM_MODEL_SHADER_NODE), so tests, like hosts, mirror no node number.
#pragma once

#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cstdint>
#include <cstring>

namespace stratum_test {

// The value of node type `name`; a name the library does not list fails the test and gives -1
// (a type every program check refuses).
inline int32_t node_type(const char* name) {
    const int32_t count = stratum_model_count(STRATUM_MODEL_SHADER_NODE);
    for (int32_t i = 0; i < count; ++i) {
        const char* listed = nullptr;
        int32_t value = -1;
        if (stratum_model_entry(STRATUM_MODEL_SHADER_NODE, i, &listed, &value) == STRATUM_OK &&
            std::strcmp(listed, name) == 0)
            return value;
    }
    ADD_FAILURE() << "the library lists no shader node '" << name << "'";
    return -1;
}

}  // namespace stratum_test
