// The error pattern every C entry point follows (stratum.h: "nothing aborts the host process"):
// the body runs inside `guarded`, which turns every exception into a status and a message;
// `require` (api/validation.h) rejects a bad value with a message that names it; `fail` records a message for
// stratum_last_error() and returns the status. Shared by every file under native/src/api, so
// there is one last-error slot per thread for the whole library.
#pragma once

#include <exception>
#include <new>
#include <string>
#include <utility>

#include "api/validation.h"
#include "stratum/stratum.h"

namespace stratum::abi {

// Entry points bring this namespace in with `using namespace stratum::abi`.
using stratum::require;

// Message of the last failed call on this thread (stratum_last_error()).
inline thread_local std::string g_last_error;

inline StratumStatus fail(StratumStatus status, std::string message) {
    g_last_error = std::move(message);
    return status;
}

// Runs `body`, turning every exception into a status and a message prefixed by `function`.
template <typename F>
StratumStatus guarded(const char* function, F&& body) {
    try {
        g_last_error.clear();
        return body();
    } catch (const ValidationError& e) {
        return fail(STRATUM_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        return fail(STRATUM_ERROR_OUT_OF_MEMORY, std::string(function) + ": out of memory");
    } catch (const std::exception& e) {
        return fail(STRATUM_ERROR_INTERNAL, std::string(function) + ": " + e.what());
    } catch (...) {
        return fail(STRATUM_ERROR_INTERNAL, std::string(function) + ": unknown internal error");
    }
}

}  // namespace stratum::abi
