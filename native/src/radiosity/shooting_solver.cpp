// Progressive shooting (textbook §3: shooting, brightest unshot patch first; Cohen, Chen,
// Wallace & Greenberg 1988, "A Progressive Refinement Approach to Fast Radiosity Image
// Generation").
//
// | parameter | meaning |
// |-----------|---------|
// | state     | M = b and the unshot exitance U = b |
// | shot      | i = the patch of most unshot power A_i (U_i.r + U_i.g + U_i.b) (ties: lowest index); |
// |           | for every j that i's light reaches: ΔM = κ_j G_ji U_i, M_j += ΔM, U_j += ΔM; U_i = 0 |
// | iteration | K shots (K patches): the work of about one gathering sweep, so iterations compare |
// | converges | each shot removes A_i U_i of unshot power and adds at most κ_max of it back; M is the sum |
// |           | of the Neumann series' terms shot so far, M → (I − κG)⁻¹ b |
//
// G_ji for shooter i is column i of G: the solver reads the transpose's row i (system.shoot),
// the very Ĝ the gathering solvers use, so all three converge to one solution. (The book's
// reciprocity shortcut G_ji = A_i G_ij / A_j would solve a slightly different system: Ĝ is
// reciprocal in expectation only.)
//
// The brightest patch is kept per block of B = ⌈√K⌉ patches (the index of each block's
// brightest): a receiver's power only grows, so it replaces its block's brightest when it
// passes it (O(1) per receiver); the shooter's power drops to 0, so its block is scanned anew
// (O(B)); the choice scans the blocks' brightest (O(K/B)). A shot costs its row plus O(√K),
// where a binary heap or tournament tree costs log K per receiver, the receivers of a shot
// being spread over the whole scene. One thread, ties to the lowest index: the same shots for
// any thread count.
#include <algorithm>
#include <chrono>
#include <vector>

#include "radiosity/radiosity_solvers.h"

namespace stratum {

namespace {

// What a shot reads and writes of one receiver, together: a receiver is a random index, and
// one or two cache lines per receiver instead of five arrays' (measured: 2x faster shots).
struct ShootingState {
    DoubleRgb exitance, unshot;
    double power = 0.0;  // A (U.r + U.g + U.b)
    Rgb albedo;
    float area = 0.0f;
    void set_power() { power = area * (unshot.r + unshot.g + unshot.b); }
};

class BrightestPatch {
public:
    explicit BrightestPatch(const std::vector<ShootingState>& state) : state_(state) {
        block_ = 1;
        while (block_ * block_ < state.size()) ++block_;
        best_.resize((state.size() + block_ - 1) / block_);
        for (size_t b = 0; b < best_.size(); ++b) rescan(b);
    }
    // The patch of most power (ties: the lowest index), or kNone when every power is 0.
    uint32_t brightest() const {
        uint32_t best = kNone;
        for (const uint32_t i : best_)
            if (best == kNone || brighter(i, best)) best = i;
        return best != kNone && state_[best].power > 0.0 ? best : kNone;
    }
    // Patch i's power grew.
    void grew(uint32_t i) {
        uint32_t& best = best_[i / block_];
        if (brighter(i, best)) best = i;
    }
    // Patch i's power fell (to 0, shot).
    void fell(uint32_t i) {
        if (best_[i / block_] == i) rescan(i / block_);
    }
    static constexpr uint32_t kNone = 0xffffffffu;

private:
    bool brighter(uint32_t a, uint32_t b) const {
        const double pa = state_[a].power, pb = state_[b].power;
        return pa > pb || (pa == pb && a < b);
    }
    void rescan(size_t b) {
        const uint32_t first = static_cast<uint32_t>(b * block_);
        const uint32_t end = static_cast<uint32_t>(std::min(state_.size(), (b + 1) * block_));
        uint32_t best = first;
        for (uint32_t i = first + 1; i < end; ++i)
            if (brighter(i, best)) best = i;
        best_[b] = best;
    }
    const std::vector<ShootingState>& state_;
    size_t block_ = 1;
    std::vector<uint32_t> best_;  // per block
};

}  // namespace

RadiositySolve solve_shooting(const RadiositySystem& system, const SolveOptions& options) {
    const uint32_t n = system.size();
    const IterationMeasures measures(system);
    RadiositySolve solve;
    std::vector<ShootingState> state(n);
    for (uint32_t i = 0; i < n; ++i) {
        state[i].exitance = state[i].unshot = system.source[i];
        state[i].albedo = system.albedo[i];
        state[i].area = system.area[i];
        state[i].set_power();
    }
    BrightestPatch brightest(state);
    std::vector<DoubleRgb> before = system.source, after(n);
    double seconds = 0.0;
    bool exhausted = false;
    for (uint32_t iteration = 1;; ++iteration) {
        const auto t0 = std::chrono::steady_clock::now();
        for (uint32_t shot = 0; shot < n; ++shot) {
            if (shot % kCancelCheckRows == 0) stop_if_cancelled(options);
            const uint32_t i = brightest.brightest();
            if (i == BrightestPatch::kNone) {
                exhausted = true;
                break;
            }
            const DoubleRgb shooting = state[i].unshot;
            state[i].unshot = DoubleRgb();
            state[i].power = 0.0;
            brightest.fell(i);
            for (const SparseEntry& e : system.shoot.row(i)) {
                ShootingState& receiver = state[e.column];
                const DoubleRgb received = receiver.albedo * (shooting * e.value);
                receiver.exitance += received;
                receiver.unshot += received;
                receiver.set_power();
                brightest.grew(e.column);
            }
        }
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (uint32_t i = 0; i < n; ++i) after[i] = state[i].exitance;
        IterationReport report = measures.measure(before, after);
        report.iteration = iteration;
        report.seconds = seconds;
        before.swap(after);
        // Nothing left to shoot: M is the series' sum, converged whatever the measure says.
        if (exhausted) {
            solve.iterations.push_back(report);
            solve.converged = true;
            break;
        }
        if (record_iteration(options, report, solve)) break;
    }
    solve.exitance = std::move(before);
    return solve;
}

}  // namespace stratum
