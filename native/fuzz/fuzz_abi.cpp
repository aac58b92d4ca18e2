// libFuzzer entry points: the input is a program over the C ABI (program.h, README.md).
#include <cstdio>
#include <cstdlib>
#include <span>

#include "byte_reader.h"
#include "checked_call.h"
#include "program.h"
#include "texture_sources.h"

namespace stratum::fuzz {

bool tracing() {
    static const bool enabled = std::getenv("STRATUM_FUZZ_TRACE") != nullptr;
    return enabled;
}

void trace_line(const std::string& line) { std::fprintf(stderr, "  %s;\n", line.c_str()); }

void trace_call_begin(const std::string& call) {
    std::fprintf(stderr, "  %s", call.c_str());
    std::fflush(stderr);
}

void trace_call_end(const std::string& result) { std::fprintf(stderr, "%s;\n", result.c_str()); }

void finding(const std::string& message) {
    std::fprintf(stderr, "\nSTRATUM FUZZ FINDING: %s\n", message.c_str());
    std::fflush(stderr);
    std::abort();
}

}  // namespace stratum::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    stratum::fuzz::init_texture_sources();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    stratum::fuzz::ByteReader in(std::span<const uint8_t>(data, size));
    stratum::fuzz::run_program(in);
    return 0;
}
