// The invariants every ABI call must keep, checked after each call the fuzzer makes, and the
// readable trace of those calls (STRATUM_FUZZ_TRACE=1) that turns a crashing input into a
// sequence of C calls for a bug report or a GoogleTest case.
#pragma once

#include <string>

#include "stratum/stratum.h"

namespace stratum::fuzz {

// True when STRATUM_FUZZ_TRACE is set: every call is printed to stderr with its arguments.
bool tracing();

// Reports a violated invariant and aborts, so libFuzzer records the input as a crash.
[[noreturn]] void finding(const std::string& message);

// Prints one line of the trace; a call is printed in two parts, before and after it runs, so
// that the call a crash or hang happens in is the last line.
void trace_line(const std::string& line);
void trace_call_begin(const std::string& call);
void trace_call_end(const std::string& result);

// Makes one ABI call (`call` returns its status) and checks what every call must keep: a
// defined StratumStatus, and a failed call explains itself in stratum_last_error().
// `describe` builds the call's arguments as text, only when tracing.
template <typename Call, typename Describe>
StratumStatus checked(const char* name, Call&& call, Describe&& describe) {
    if (tracing()) trace_call_begin(std::string(name) + "(" + describe() + ")");
    const StratumStatus status = call();
    const int code = static_cast<int>(status);
    const char* error = stratum_last_error();
    if (tracing())
        trace_call_end(" -> " + std::to_string(code) +
                       (status == STRATUM_OK ? "" : std::string(" \"") + error + "\""));
    if (code < STRATUM_OK || code > STRATUM_ERROR_IO)
        finding(std::string(name) + " returned " + std::to_string(code) + ", not a StratumStatus");
    if (status != STRATUM_OK && error[0] == '\0')
        finding(std::string(name) + " failed with status " + std::to_string(code) +
                " and an empty stratum_last_error()");
    return status;
}

}  // namespace stratum::fuzz
