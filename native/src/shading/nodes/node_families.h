// The registry entries of each node family (one file each under shading/nodes/), gathered by
// node_registry.cpp.
#pragma once

#include "shading/node_registry.h"

namespace stratum {

NodeEntry math_node_entry();  // nodes/math_node.cpp
NodeEntry copy_node_entry();  // nodes/math_node.cpp
NodeEntry bump_node_entry();        // nodes/bump_node.cpp
NodeEntry normal_map_node_entry();  // nodes/bump_node.cpp

}  // namespace stratum
