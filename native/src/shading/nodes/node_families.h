// The registry entries of each node family (one file each under shading/nodes/), gathered by
// node_registry.cpp.
#pragma once

#include "shading/node_registry.h"

namespace stratum {

NodeEntry math_node_entry();  // nodes/math_node.cpp
NodeEntry copy_node_entry();  // nodes/math_node.cpp

NodeEntry bump_node_entry();        // nodes/bump_node.cpp
NodeEntry normal_map_node_entry();  // nodes/bump_node.cpp

NodeEntry mix_node_entry();              // nodes/mix_node.cpp
NodeEntry invert_node_entry();           // nodes/color_adjust_nodes.cpp
NodeEntry gamma_node_entry();            // nodes/color_adjust_nodes.cpp
NodeEntry bright_contrast_node_entry();  // nodes/color_adjust_nodes.cpp
NodeEntry hsv_node_entry();              // nodes/color_adjust_nodes.cpp
NodeEntry rgb_to_bw_node_entry();        // nodes/color_adjust_nodes.cpp
NodeEntry separate_color_node_entry();   // nodes/color_convert_nodes.cpp
NodeEntry combine_color_node_entry();    // nodes/color_convert_nodes.cpp
NodeEntry color_ramp_node_entry();       // nodes/ramp_node.cpp
NodeEntry curves_node_entry();           // nodes/ramp_node.cpp

NodeEntry noise_node_entry();     // nodes/noise_texture.cpp
NodeEntry musgrave_node_entry();  // nodes/musgrave_texture.cpp

NodeEntry voronoi_node_entry();      // nodes/voronoi_texture.cpp
NodeEntry white_noise_node_entry();  // nodes/white_noise_texture.cpp

NodeEntry vector_math_node_entry();       // nodes/vector_math_node.cpp
NodeEntry map_range_node_entry();         // nodes/map_range_node.cpp
NodeEntry clamp_node_entry();             // nodes/map_range_node.cpp
NodeEntry mapping_node_entry();           // nodes/mapping_node.cpp
NodeEntry vector_rotate_node_entry();     // nodes/mapping_node.cpp
NodeEntry vector_transform_node_entry();  // nodes/mapping_node.cpp
NodeEntry fresnel_node_entry();           // nodes/fresnel_node.cpp
NodeEntry layer_weight_node_entry();      // nodes/fresnel_node.cpp
NodeEntry normal_node_entry();            // nodes/fresnel_node.cpp
NodeEntry blackbody_node_entry();         // nodes/blackbody_node.cpp
NodeEntry wavelength_node_entry();        // nodes/blackbody_node.cpp

// Pattern textures and the Image node: nodes/checker_texture.cpp, gradient_texture.cpp,
// brick_texture.cpp, magic_texture.cpp, image_node.cpp, wave_texture.cpp.
NodeEntry checker_node_entry();
NodeEntry gradient_node_entry();
NodeEntry brick_node_entry();
NodeEntry magic_node_entry();
NodeEntry image_node_entry();
NodeEntry wave_node_entry();
NodeEntry sky_node_entry();  // nodes/sky_texture.cpp

}  // namespace stratum
