// A compiled node graph (stratum/shader_nodes.h): straight-line nodes over float registers, the
// shape of Cycles' SVM stack machine (kernel/svm/svm.h), here with named registers instead of a
// stack. A program is checked once when it is added (shading/node_registry.h) and then only
// run: evaluate() never fails, and a node's arithmetic on bad values gives what Cycles' gives
// (NaN in, NaN out; the closure parameters that read it are limited when applied).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"
#include "shading/program_layout.h"

namespace stratum {

struct Texture;

inline constexpr uint32_t kShaderInputRegisters = shader_input::kCount;

// StratumShaderNode, checked; `table` indexes ShaderProgram::tables (a node's precomputed data,
// e.g. the Sky's), or is kNoTable.
struct ShaderNode {
    int32_t type = 0;
    std::array<int32_t, 6> modes{};
    std::array<uint32_t, 12> inputs{};
    std::array<uint32_t, 6> outputs{};
    uint32_t data_offset = 0, data_count = 0;
    uint32_t table = 0xffffffffu;
};
inline constexpr uint32_t kNoTable = 0xffffffffu;

struct ShaderProgram {
    std::vector<ShaderNode> nodes;
    std::vector<float> registers;  // initial values
    std::vector<float> data;
    std::vector<std::vector<float>> tables;  // built by nodes' prepare step (node_registry.h)
};

// What a node can see besides its registers.
struct ShaderEvalContext {
    const ShaderProgram* program = nullptr;
    const std::vector<std::shared_ptr<const Texture>>* textures = nullptr;

    const float* data(const ShaderNode& n) const { return program->data.data() + n.data_offset; }
    const std::vector<float>& table(const ShaderNode& n) const { return program->tables[n.table]; }
};

// The register file of one evaluation: the program's initial values with the inputs written over
// the first kShaderInputRegisters. Small programs stay on the stack.
class ShaderRegisters {
public:
    explicit ShaderRegisters(const ShaderProgram& program);
    float* data() { return values_; }
    const float* data() const { return values_; }
    float& operator[](uint32_t i) { return values_[i]; }
    float operator[](uint32_t i) const { return values_[i]; }
    Vec3 vec3(uint32_t i) const { return {values_[i], values_[i + 1], values_[i + 2]}; }
    Rgb rgb(uint32_t i) const { return {values_[i], values_[i + 1], values_[i + 2]}; }
    void set(uint32_t i, Vec3 v) {
        values_[i] = v.x;
        values_[i + 1] = v.y;
        values_[i + 2] = v.z;
    }
    void set(uint32_t i, Rgb c) {
        values_[i] = c.r;
        values_[i + 1] = c.g;
        values_[i + 2] = c.b;
    }

    ShaderRegisters(const ShaderRegisters&) = delete;
    ShaderRegisters& operator=(const ShaderRegisters&) = delete;

private:
    static constexpr uint32_t kStackRegisters = 512;
    std::array<float, kStackRegisters> stack_;
    std::vector<float> heap_;
    float* values_;
};

// Writes the inputs of a point on no object (the world, a lamp) into the first
// kShaderInputRegisters registers: 0, except each mesh attribute's alpha, 1 (Cycles' missing
// attribute), and the identity normal transform (Cycles leaves a vector as it is without one).
void write_objectless_inputs(float* registers);

// Runs every node of `program` in order on `registers` (whose inputs the caller has written).
void evaluate(const ShaderProgram& program, const ShaderEvalContext& context, ShaderRegisters& registers);

}  // namespace stratum
