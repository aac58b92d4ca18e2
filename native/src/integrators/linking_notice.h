// The notice of an integrator that renders without light and shadow linking (the light tracer
// and radiosity: their light leaves the emitters without a receiver or a shadow ray to filter):
// it names the linked lamps and the instances whose emission is linked.
#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace stratum {

// "<method> ignores light and shadow linking: ..." when some emitter links, else nullopt.
std::optional<std::string> unsupported_linking_notice(const Scene& scene, const std::string& method);

}  // namespace stratum
