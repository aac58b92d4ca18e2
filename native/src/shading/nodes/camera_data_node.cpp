// Camera Data (Blender's ShaderNodeCameraData), as Cycles' svm_node_camera (kernel/svm/camera.h,
// the same formula in 3.4 and 5.0).
//
// | node        | modes | inputs                               | outputs                          |
// |-------------|-------|--------------------------------------|----------------------------------|
// | camera_data | none  | 0 the point in camera space (3): the | 0 view vector (3), 1 view z      |
// |             |       | renderer's CAMERA input              | depth, 2 view distance           |
//
// With v the shading point in camera space (Cycles' worldtocamera, +Z forward, as the renderer
// writes CAMERA): View Vector = v / |v| (each component divided, as Cycles' normalize; a point
// at the camera's centre gives NaN, as there), View Z Depth = v.z, View Distance = |v|.
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

std::string no_modes(const ShaderNode&, const ShaderProgram&) { return ""; }

void evaluate_camera_data(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 v = r.vec3(n.inputs[0]);
    const float distance = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    r.set(n.outputs[0], Vec3(v.x / distance, v.y / distance, v.z / distance));
    r[n.outputs[1]] = v.z;
    r[n.outputs[2]] = distance;
}

}  // namespace

const NodeRegistration kCameraDataNode{{.value = 36,
                                        .name = "camera_data",
                                        .input_widths = {3},
                                        .output_widths = {3, 1, 1},
                                        .check = no_modes,
                                        .evaluate = evaluate_camera_data}};

}  // namespace stratum
