#include "core/memory_budget.h"

#include <unistd.h>

#include <cstdio>

namespace stratum {

double physical_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page_size <= 0) return 8.0 * (1u << 30);
    return static_cast<double>(pages) * static_cast<double>(page_size);
}

double memory_budget_bytes() { return 0.5 * physical_memory_bytes(); }

std::string gib(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
    return text;
}

}  // namespace stratum
