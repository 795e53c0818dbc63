// The pieces of one AV-HV encounter, free of SUMO so they can be unit-tested:
// the AV's draw of intent and signal, the HV's reading of the observed nudge,
// the encounter's sequence of releases, and the creep profile of a nudge.
// (Who meets whom at a junction, and when each is held and handed back:
// junction/interception.h.)
#pragma once

#include "taebp/persuasion/outcomes.h"

#include <cstdint>
#include <random>
#include <vector>

namespace taebp {

enum class VehicleKind { kAV, kHV };

// The two games an AV and an HV play (docs/beyond/major-road.md): both at
// stop lines (the paper's), or the AV at a minor road's line against an HV on
// the major road (the paper's game at the effective penalty r_eff).
enum class GameKind { kStopLines = 0, kMajorRoad = 1 };
constexpr int kGameKinds = 2;

// ---------------------------------------------------------------- randomness
// A portable uniform draw in [0, 1) from a 64-bit Mersenne twister (the
// standard distributions are implementation-defined; this is not).
double Uniform01(std::mt19937_64& rng);

// ---------------------------------------------------------------- AV and HV
struct AvDraw {
  bool intent_go = false;
  bool nudge = false;
  double nudge_distance = 0.0;  // commanded s (0 when not nudging)
  bool goes_first = false;      // intent Go and the scheme lets the AV go
};
// Draws intent ~ Bernoulli(lambda), then the signal from the committed scheme.
// Always consumes exactly two uniforms so policies share random streams.
AvDraw DrawAv(const persuasion::CommittedScheme& scheme, double prior_go, std::mt19937_64& rng);

struct HvReading {
  double observed = 0.0;   // displacement SUMO reported (m)
  double posterior = 0.0;  // p_theta(Go | observed)
  bool drives_if_clear = false;
};
// The HV reads the observed displacement with its intuitive likelihood model
// (clamped to [0, s_max]: a nudge past s_max reads as s_max) and its own trust,
// under the AV's committed scheme: persuasion::HvPosteriorGo(scheme, ...), so a
// still AV is the signal s = 0 under a signalling scheme and no information
// (the prior) without one (no_ebp, TA-EBP's fallback), as the theory predicts.
HvReading ReadNudge(const persuasion::CommittedScheme& scheme,
                    const persuasion::AvHvParams& params, double theta,
                    const persuasion::LikelihoodModel& model, double observed);

// Was a nudge realised? SUMO's displacement d for a commanded s > 0 must lie
// in [s, s + tolerance] (the creep aims at s + kNudgeOvershoot); a still AV
// (s = 0) must not have moved more than the tolerance.
bool NudgeRealised(double commanded, double observed, double tolerance = 1e-3);

// ---------------------------------------------------------------- encounter
// The order of releases once the HV has decided.
//   AV goes:  AV at once; HV DR at once (they collide), HV DC once the AV has
//             entered the junction.
//   AV waits: HV DR at once; HV DC after `confirm_delay`; the AV once the HV has
//             entered the junction.
// The second of two moves is handed back to SUMO's own rules once the first is
// inside the junction (interception.h): SUMO makes it yield to the first at
// their crossing point, as it does for any foe already in the junction.
class EncounterSequence {
 public:
  struct Release {
    bool av = false;       // true: the AV, false: the HV
    bool reckless = false; // HV driving recklessly (junction checks off)
  };
  EncounterSequence(bool av_goes, bool hv_drives_if_clear, double decided_at,
                    double confirm_delay);
  // Releases due at `now`, given which vehicles have entered the junction
  // (released and past their stop lines). A careful release (not a reckless
  // HV) also needs its exit to have room (`av_may_enter`, `hv_may_enter`:
  // keep clear); any release needs `av_may_go` / `hv_may_go` (the caller's
  // gate: a move of the game waits for its way to clear); until then it
  // stays due.
  std::vector<Release> Update(double now, bool av_entered, bool hv_entered,
                              bool av_may_enter = true, bool hv_may_enter = true,
                              bool av_may_go = true, bool hv_may_go = true);

 private:
  bool av_goes_, hv_dc_;
  double decided_at_, confirm_delay_;
  bool av_released_ = false, hv_released_ = false;
};

// ---------------------------------------------------------------- creep
// Speed to command for the next step of a nudge of `target` metres, having
// covered `covered` at speed `speed`: accelerate at most `accel` per second up
// to `creep_speed`, brake so as to stop at the target with at most `decel`,
// and land on it exactly (remaining / dt) on the last step. Returns 0 once
// the target is reached.
double CreepSpeed(double target, double covered, double speed, double dt, double accel,
                  double decel, double creep_speed);

}  // namespace taebp
