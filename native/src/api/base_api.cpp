// The C entry points of stratum/base.h besides the listings (listings_api.cpp): the last
// error of the calling thread and the library's version.
#include "api/abi_guard.h"
#include "stratum/stratum.h"

extern "C" {

const char* stratum_last_error(void) { return stratum::abi::g_last_error.c_str(); }

// STRATUM_VERSION_STRING: blender_manifest.toml's version, set by CMakeLists.txt.
const char* stratum_version(void) { return STRATUM_VERSION_STRING; }

}  // extern "C"
