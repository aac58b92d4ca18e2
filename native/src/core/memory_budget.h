// What one allocation of a render may ask for: half of this machine's physical memory. The
// other half is left to the host (Blender holds its own copy of the image and the scene).
// Checking before allocating turns a request that cannot fit into a message naming what asked
// for it, instead of an allocation that Linux's overcommit grants and the OOM killer ends,
// taking the user's Blender session with it.
#pragma once

#include <string>

namespace stratum {

// Bytes of physical memory (sysconf); 8 GiB when the system does not say.
double physical_memory_bytes();

// Half of physical_memory_bytes().
double memory_budget_bytes();

// "12.3 GiB".
std::string gib(double bytes);

}  // namespace stratum
