// One entry of a registry of named choices (samplers, filters, integrators, hemisphere
// distributions, estimator options): the stable name used in settings and files, the label a
// menu shows, and the description its tooltip and `stratum --help` show.
#pragma once

namespace stratum {

struct RegistryEntry {
    const char* name;
    const char* label;
    const char* description;
};

}  // namespace stratum
