// The ABI's descriptors drawn from the input. Each starts from a valid preset (a plausible
// scene object, so most programs build a scene that renders) and then takes a few field
// mutations, each of which may set an extreme value (ByteReader::special_floats).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "byte_reader.h"
#include "stratum/stratum.h"

namespace stratum::fuzz {

using Matrix = std::array<float, 16>;

// Enumerations and small counts: selector < 16 takes a boundary value of int32, else -2..9.
int32_t draw_small_int(ByteReader& in);
// An enumeration value: mostly 0..count-1, for selectors from 240 on -2..13 (invalid ones too).
int32_t draw_enum(ByteReader& in, int32_t count);
// A model value of `kind` (StratumModelKind): draw_enum's index into the listing
// (stratum_model_entry) gives a registered value; past the listing, the index itself.
int32_t draw_model(ByteReader& in, int32_t kind);

// A transform: `preset` (identity, translation, scale, per-axis scale, rotation, raw), then up to
// three element mutations (any of the 16, so the last row can stop being (0, 0, 0, 1)).
Matrix draw_matrix(ByteReader& in, const Matrix& preset);
Matrix translation(float x, float y, float z);

StratumMaterialDesc draw_material(ByteReader& in);
StratumLightDesc draw_light(ByteReader& in);
StratumCameraDesc draw_camera(ByteReader& in);
StratumInstanceDesc draw_instance(ByteReader& in, uint32_t mesh_count);

// A mesh's arrays, owned here; desc() points into them (NULL where the draw asked for NULL).
struct MeshArrays {
    std::vector<float> positions, corner_normals, corner_uvs, vertex_normals, corner_tangents;
    std::vector<uint32_t> triangles, material_ids;
    uint32_t vertex_count = 0, triangle_count = 0;
    bool null_positions = false, null_triangles = false, null_material_ids = false;
    bool with_corner_normals = false, with_vertex_normals = false, with_corner_uvs = false,
         with_corner_tangents = false;
    StratumMeshDesc desc() const;
};
MeshArrays draw_mesh(ByteReader& in, uint32_t material_count);

// An environment image and its rotation, owned here.
struct EnvironmentArrays {
    std::vector<float> rgb;
    uint32_t width = 0, height = 0;
    float strength = 1.0f;
    bool null_rgb = false;
    bool with_rotation = false;
    std::array<float, 9> rotation{};
};
EnvironmentArrays draw_environment(ByteReader& in);

}  // namespace stratum::fuzz
