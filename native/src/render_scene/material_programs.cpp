#include "render_scene/material_programs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render_scene/render_scene.h"

namespace stratum {

namespace {

// Cycles lets a node-driven emission go negative (the pixel then is); NaN reads 0 and an
// infinity the largest float, so that sums stay finite.
float finite(float v) {
    if (std::isnan(v)) return 0.0f;
    return std::clamp(v, -std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
}
float at_least(float v, float lo) { return std::isnan(v) ? lo : std::max(v, lo); }
float unit(float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f); }
Rgb rgb_at_least0(const ShaderRegisters& r, uint32_t i) {
    return {at_least(r[i], 0.0f), at_least(r[i + 1], 0.0f), at_least(r[i + 2], 0.0f)};
}

Vec3 read3(const float* r, uint32_t at) { return {r[at], r[at + 1], r[at + 2]}; }

void put(float* r, uint32_t at, Vec3 v) {
    r[at] = v.x;
    r[at + 1] = v.y;
    r[at + 2] = v.z;
}

// Object-space normal and the Bump node's offsets (see the StratumShaderInput list).
void write_offsets(const SurfaceHit& hit, const ProgramInputs& in, float side, float* r) {
    const Transform& m = *in.object_to_world;
    const Transform inverse = m.inverse();
    // Normals go to object space by the transpose of the linear part (inverse of the inverse
    // transpose), up to scale.
    const Vec3 n = hit.shading_normal * side;
    const Vec3 on(m.m[0] * n.x + m.m[4] * n.y + m.m[8] * n.z, m.m[1] * n.x + m.m[5] * n.y + m.m[9] * n.z,
                  m.m[2] * n.x + m.m[6] * n.y + m.m[10] * n.z);
    const float onl = length(on);
    put(r, shader_input::kObjectNormal, onl > 0.0f ? on / onl : n);
    Vec3 t = hit.tangent_frame.dpdu - n * dot(n, hit.tangent_frame.dpdu);
    if (!(dot(t, t) > 1e-20f)) t = std::abs(n.x) < 0.9f ? cross(n, Vec3(1, 0, 0)) : cross(n, Vec3(0, 1, 0));
    t = normalize(t);
    const Vec3 b = cross(n, t);
    const float step = bump_step(hit.t, hit.position);
    const Vec3 dx = t * step, dy = b * step;
    put(r, shader_input::kDpdx, dx);
    put(r, shader_input::kDpdy, dy);
    const Vec3 ox = inverse.vector(dx), oy = inverse.vector(dy);
    put(r, shader_input::kDobjectDx, ox);
    put(r, shader_input::kDobjectDy, oy);
    const Vec3 s2 = in.texspace_size * 2.0f;
    put(r, shader_input::kDgeneratedDx, Vec3(ox.x / s2.x, ox.y / s2.y, ox.z / s2.z));
    put(r, shader_input::kDgeneratedDy, Vec3(oy.x / s2.x, oy.y / s2.y, oy.z / s2.z));
    // UV change of a step d in the triangle's plane: d = du dpdu + dv dpdv, solved in least
    // squares (the 2 x 2 normal equations); 0 without UVs.
    const Vec3 pu = hit.tangent_frame.dpdu, pv = hit.dpdv;
    const float a = dot(pu, pu), bb = dot(pu, pv), c = dot(pv, pv), det = a * c - bb * bb;
    const auto duv = [&](Vec3 d) {
        if (!(std::abs(det) > 0.0f)) return Vec3(0.0f, 0.0f, 0.0f);
        const float x = dot(pu, d), y = dot(pv, d);
        return Vec3((c * x - bb * y) / det, (a * y - bb * x) / det, 0.0f);
    };
    put(r, shader_input::kDuvDx, duv(dx));
    put(r, shader_input::kDuvDy, duv(dy));
}

// The mesh's attributes at the hit: corners interpolated with the barycentric weights; a slot the
// mesh lacks reads colour 0, alpha 1, Fac 0 (Cycles' missing attribute).
void write_attributes(const SurfaceHit& hit, const Mesh& mesh, float* r) {
    const float b1 = hit.barycentric.x, b2 = hit.barycentric.y, b0 = 1.0f - b1 - b2;
    for (uint32_t slot = 0; slot < shader_input::kAttributeSlots; ++slot) {
        float* out = r + shader_input::kAttribute0 + slot * shader_input::kAttributeWidth;
        const Mesh::CornerAttribute& a = mesh.attributes[slot];
        if (a.rgba.empty()) {
            out[3] = 1.0f;
            continue;
        }
        const float* c = &a.rgba[static_cast<size_t>(hit.triangle) * 12];
        for (int k = 0; k < 4; ++k) out[k] = c[k] * b0 + c[4 + k] * b1 + c[8 + k] * b2;
        out[4] = a.kind == 0 ? out[0] : (out[0] + out[1] + out[2]) * (1.0f / 3.0f);
    }
}

}  // namespace

MaterialPrograms::MaterialPrograms(const Scene& scene)
    : programs_(scene.programs), textures_(scene.textures), per_material_(scene.materials.size()) {
    for (const ProgramBinding& b : scene.program_bindings) per_material_[b.material_id].push_back(b);
    for (auto& list : per_material_) {
        std::stable_sort(list.begin(), list.end(), [](const ProgramBinding& a, const ProgramBinding& b) {
            return a.program_id < b.program_id;
        });
    }
}

void write_surface_inputs(const SurfaceHit& hit, const ProgramInputs& in, float* r) {
    std::fill(r, r + kShaderInputRegisters, 0.0f);
    // Cycles' sd->N and sd->Ng face the incoming ray's side (SD_BACKFACING negates both).
    const float side = in.backfacing ? -1.0f : 1.0f;
    put(r, shader_input::kPosition, hit.position);
    put(r, shader_input::kNormal, hit.shading_normal * side);
    put(r, shader_input::kTrueNormal, hit.geometric_normal * side);
    put(r, shader_input::kIncoming, in.wo);
    const Vec3 n = hit.shading_normal * side;
    put(r, shader_input::kReflection, n * (2.0f * dot(n, in.wo)) - in.wo);
    put(r, shader_input::kUv, Vec3(hit.uv.x, hit.uv.y, 0.0f));
    // Blender's texture space maps [location - size, location + size] to [0, 1] (Cycles' generated
    // attribute: (P - location) / (2 size) + 0.5).
    const Vec3 g = (hit.object_position - in.texspace_location);
    put(r, shader_input::kGenerated,
        Vec3(g.x / (2.0f * in.texspace_size.x) + 0.5f, g.y / (2.0f * in.texspace_size.y) + 0.5f,
             g.z / (2.0f * in.texspace_size.z) + 0.5f));
    put(r, shader_input::kObject, hit.object_position);
    if (in.world_to_camera) {
        // Cycles' camera space looks down +Z (Blender's camera looks down -Z).
        const Vec3 c = in.world_to_camera->point(hit.position);
        put(r, shader_input::kCamera, Vec3(c.x, c.y, -c.z));
    }
    put(r, shader_input::kObjectLocation, in.object_location);
    r[shader_input::kBackfacing] = in.backfacing ? 1.0f : 0.0f;
    r[shader_input::kObjectRandom] = in.object_random;
    r[shader_input::kRayLength] = in.reach.length;
    r[shader_input::kPixelFootprint] = in.reach.footprint;
    in.reach.path.write(r);
    r[shader_input::kObjectIndex] = static_cast<float>(hit.object_pass_index);
    r[shader_input::kMaterialIndex] = static_cast<float>(hit.material_pass_index);
    put(r, shader_input::kObjectColor, Vec3(in.object_color.r, in.object_color.g, in.object_color.b));
    r[shader_input::kObjectAlpha] = in.object_alpha;
    // Cycles' Tangent without a UV map (kernel/geom/primitive.h primitive_tangent): the radial
    // tangent about the object's Z axis in generated space, (-(g.y - 0.5), g.x - 0.5, 0), taken to
    // world space as a normal is, then projected into the shading plane.
    const Vec3 gen = read3(r, shader_input::kGenerated);
    const Vec3 radial = in.object_to_world->normal(Vec3(-(gen.y - 0.5f), gen.x - 0.5f, 0.0f));
    const Vec3 sn = hit.shading_normal * side;
    const Vec3 across = cross(radial, sn);
    const float across_length = length(across);
    put(r, shader_input::kTangent,
        across_length > 0.0f ? cross(sn, across / across_length) : Vec3(0.0f, 0.0f, 0.0f));
    const Vec3 du = hit.tangent_frame.dpdu - sn * dot(sn, hit.tangent_frame.dpdu);
    const float du_length = length(du);
    put(r, shader_input::kUvTangent, du_length > 0.0f ? du / du_length : Vec3(0.0f, 0.0f, 0.0f));
    put(r, shader_input::kParametric,
        Vec3(1.0f - hit.barycentric.x - hit.barycentric.y, hit.barycentric.x, 0.0f));
    write_offsets(hit, in, side, r);
    write_attributes(hit, *in.mesh, r);
    for (uint32_t k = 0; k < 3; ++k) put(r, shader_input::kTriangle + 3 * k, hit.vertices[k]);
    if (hit.tangent_frame.mikktspace) put(r, shader_input::kMikktspaceTangent, hit.tangent_frame.tangent);
    const Transform& m = *in.object_to_world;
    put(r, shader_input::kNormalTransform, m.normal(Vec3(1.0f, 0.0f, 0.0f)));
    put(r, shader_input::kNormalTransform + 3, m.normal(Vec3(0.0f, 1.0f, 0.0f)));
    put(r, shader_input::kNormalTransform + 6, m.normal(Vec3(0.0f, 0.0f, 1.0f)));
}

void MaterialPrograms::apply(const SurfaceHit& hit, const ProgramInputs& inputs, WeightedClosure* closures,
                             uint32_t count, Vec3* shading_normal) const {
    const std::vector<ProgramBinding>& bindings = per_material_[hit.material_id];
    size_t i = 0;
    while (i < bindings.size()) {
        const uint32_t program_id = bindings[i].program_id;
        const ShaderProgram& program = *programs_[program_id];
        ShaderRegisters r(program);
        write_surface_inputs(hit, inputs, r.data());
        evaluate(program, ShaderEvalContext{&program, &textures_}, r);
        for (; i < bindings.size() && bindings[i].program_id == program_id; ++i) {
            const ProgramBinding& b = bindings[i];
            if (b.closure_index >= count) continue;
            WeightedClosure& c = closures[b.closure_index];
            Material& m = c.params;
            const uint32_t at = b.register_index;
            switch (b.param) {
                case ProgramParam::BaseColor:
                    m.base_color = rgb_at_least0(r, at);
                    break;
                case ProgramParam::Roughness:
                    m.roughness = unit(r[at]);
                    break;
                case ProgramParam::Metallic:
                    m.metallic = unit(r[at]);
                    break;
                case ProgramParam::Transmission:
                    m.transmission = unit(r[at]);
                    break;
                case ProgramParam::CoatRoughness:
                    m.coat_roughness = unit(r[at]);
                    break;
                case ProgramParam::Specular:
                    m.specular = at_least(r[at], 0.0f);
                    break;
                case ProgramParam::Coat:
                    m.coat = at_least(r[at], 0.0f);
                    break;
                case ProgramParam::Ior:
                    m.ior = at_least(r[at], 1e-5f);
                    break;
                case ProgramParam::Emission:
                    m.emission = Rgb(finite(r[at]), finite(r[at + 1]), finite(r[at + 2]));
                    break;
                case ProgramParam::Weight:
                    c.weight = c.weight * rgb_at_least0(r, at);
                    break;
                case ProgramParam::CoatTint:
                    m.coat_tint = Rgb(unit(r[at]), unit(r[at + 1]), unit(r[at + 2]));
                    break;
                case ProgramParam::Normal: {
                    const Vec3 n = r.vec3(at);
                    const float len = length(n);
                    if (len > 0.0f && std::isfinite(len)) {
                        // The program's frame faces the viewer; the shading point's normal is
                        // winding-oriented until build_closures turns it.
                        *shading_normal = n / len * (inputs.backfacing ? -1.0f : 1.0f);
                    }
                    break;
                }
            }
        }
    }
}

}  // namespace stratum
