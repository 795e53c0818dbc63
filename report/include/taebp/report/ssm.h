// SUMO's SSM output (scenario.outputs.ssm, docs/ssm.md) read into conflicts by
// measure, per policy and per controlled junction. Plain data and pugixml;
// no SUMO and no config (the caller passes the rules).
//
// A conflict is one pair of vehicles over one stretch of time: SUMO's device
// on each equipped vehicle writes its own conflict record (ego, foe), so with
// every vehicle equipped most conflicts appear twice (ego and foe swapped,
// their spans and values not always equal). Records of the same unordered
// pair whose [begin, end] overlap are one conflict, with the worst value of
// each measure (least TTC and PET, greatest DRAC).
// A conflict counts for a measure when its value passes the threshold as in
// SUMO's own test: TTC <= t (and TTC > 0: SUMO 1.15 writes minTTC 0, type 111,
// for vehicles standing nose to tail; not a conflict), DRAC >= t, PET <= t.
// It counts after the warm-up: its first record began at or after `warmup`.
// Its place is the point of the measure's extreme (TTC's, else DRAC's, else
// PET's for the conflict itself): at the controlled junction whose internal
// lanes pass nearest that point, within `junction_radius`.
// A game's conflict: a conflict between the AV and the HV of one game (an
// AV-HV encounter), over a span that overlaps the game's window (from
// kSsmGameBefore s before it formed to kSsmGameAfter s after): the game's own
// near miss, counted once per game (and per measure), at the game's junction.
#pragma once

#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace taebp {

enum class SsmMeasure { kTtc, kDrac, kPet };
inline constexpr int kSsmMeasures = 3;

struct SsmRules {
  std::array<bool, kSsmMeasures> on{};         // the measures SUMO computed
  std::array<double, kSsmMeasures> threshold{};  // TTC s, DRAC m/s^2, PET s
  double warmup = 0;                           // s
  double junction_radius = 10;                 // m
};

// A controlled junction's place: its internal lanes' shapes (or its centre
// when it has none).
struct SsmJunctionArea {
  std::string junction;
  std::vector<std::vector<std::array<double, 2>>> shapes;
};

// One game of the run: its two vehicles, its junction, when it formed (s).
struct SsmGame {
  std::string av, hv, junction;
  double time = 0;
};
inline constexpr double kSsmGameBefore = 30;  // s
inline constexpr double kSsmGameAfter = 60;   // s

// A collision SUMO's collision check reported (after the warm-up): its two
// vehicles and when it began. A conflict the device logged between the same
// two over a span that holds it (within kSsmCollisionSlack s) is that
// collision, counted once, in the collisions: not among the conflicts.
struct SsmCollision {
  std::string a, b;
  double time = 0;
};
inline constexpr double kSsmCollisionSlack = 1;  // s

// A game's pair measures: the worst value of each measure over the conflicts
// logged between its AV and HV in its window (least TTC and PET, greatest
// DRAC), whether or not it passes its threshold; NaN where none was logged
// (or the measure is not computed). encounters.csv's ssm_min_ttc,
// ssm_max_drac, ssm_min_pet.
struct SsmPair {
  double min_ttc = std::numeric_limits<double>::quiet_NaN();
  double max_drac = std::numeric_limits<double>::quiet_NaN();
  double min_pet = std::numeric_limits<double>::quiet_NaN();
  double Value(SsmMeasure m) const {
    return m == SsmMeasure::kTtc ? min_ttc : m == SsmMeasure::kDrac ? max_drac : min_pet;
  }
};

// Whether value `v` of measure `m` passes its threshold as SUMO's own test
// does (TTC in (0, t], DRAC >= t, PET <= t), for a measure computed.
bool SsmPasses(const SsmRules& rules, SsmMeasure m, double v);

// Conflicts of one policy or one junction.
struct SsmTally {
  long conflicts = 0;                           // any measure
  std::array<long, kSsmMeasures> by_measure{};  // TTC, DRAC, PET
  double ttc_min = std::numeric_limits<double>::quiet_NaN();   // over the TTC conflicts
  double drac_max = std::numeric_limits<double>::quiet_NaN();  // over the DRAC conflicts
};

struct SsmRun {
  bool on = false;
  SsmRules rules;
  SsmTally network;                         // every conflict in the network
  SsmTally at_junctions;                    // those at a controlled junction
  std::map<std::string, SsmTally> junction; // by controlled junction id
  std::vector<SsmPair> games;               // the games' pair measures, in the order given
  long collided = 0;                        // conflicts left out: their pair collided (SsmCollision)
  long records = 0;                         // conflict elements SUMO wrote (all times)
  // The device's warnings (a collision it saw; "Cannot compute SSM due to bad
  // internal lane geometry at junction J": crossings there go unmeasured).
  long device_warnings = 0;
};

// Reads SUMO's SSM output `path`. Throws std::runtime_error naming the file
// when it is missing or not an SSM log.
// `games`: the run's games (after the warm-up), for the games' conflicts.
SsmRun ReadSsmOutput(const std::string& path, const SsmRules& rules,
                     const std::vector<SsmJunctionArea>& areas,
                     const std::vector<SsmGame>& games = {},
                     const std::vector<SsmCollision>& collisions = {});

}  // namespace taebp
