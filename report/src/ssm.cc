#include "taebp/report/ssm.h"

#include "metric_facts.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace taebp {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The measures' elements in SUMO's output, by SsmMeasure.
constexpr const char* kElement[kSsmMeasures] = {"minTTC", "maxDRAC", "PET"};

// One measure's extreme in a record (NaN: "NA", not computed or not reached).
struct Extreme {
  double value = kNaN, x = kNaN, y = kNaN;
};

struct Record {
  std::string a, b;  // the pair, a < b
  double begin = 0, end = 0;
  std::array<Extreme, kSsmMeasures> m;
};

double Number(const char* text) {
  if (!text || !*text || std::string(text) == "NA") return kNaN;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  return end && *end == '\0' ? v : kNaN;
}

Extreme ReadExtreme(const pugi::xml_node& n) {
  Extreme e;
  if (!n) return e;
  e.value = Number(n.attribute("value").value());
  const std::string pos = n.attribute("position").value();
  const auto comma = pos.find(',');
  if (comma != std::string::npos) {
    e.x = Number(pos.substr(0, comma).c_str());
    e.y = Number(pos.substr(comma + 1).c_str());
  }
  return e;
}

// The worse of two extremes of measure `k` (least TTC / PET, greatest DRAC).
const Extreme& Worse(int k, const Extreme& p, const Extreme& q) {
  if (std::isnan(p.value)) return q;
  if (std::isnan(q.value)) return p;
  const bool greater = k == static_cast<int>(SsmMeasure::kDrac);
  return (greater ? q.value > p.value : q.value < p.value) ? q : p;
}

bool Passes(const SsmRules& r, int k, double v) { return SsmPasses(r, static_cast<SsmMeasure>(k), v); }

double SegmentDistance(const std::array<double, 2>& p, const std::array<double, 2>& a,
                       const std::array<double, 2>& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

// The controlled junction at (x, y), or nullptr.
const SsmJunctionArea* JunctionAt(const std::vector<SsmJunctionArea>& areas, double radius,
                                  double x, double y) {
  if (std::isnan(x) || std::isnan(y)) return nullptr;
  const std::array<double, 2> p{x, y};
  const SsmJunctionArea* best = nullptr;
  double best_d = radius;
  for (const SsmJunctionArea& a : areas) {
    for (const auto& shape : a.shapes) {
      double d = shape.size() == 1 ? std::hypot(x - shape[0][0], y - shape[0][1]) : kNaN;
      for (std::size_t i = 1; i < shape.size(); ++i) {
        const double s = SegmentDistance(p, shape[i - 1], shape[i]);
        d = std::isnan(d) ? s : std::min(d, s);
      }
      if (!std::isnan(d) && (best ? d < best_d : d <= best_d)) {
        best = &a;
        best_d = d;
      }
    }
  }
  return best;
}

// Counts conflict `m` in `t`: for `measure`, or (-1) as a conflict.
void Add(const std::array<Extreme, kSsmMeasures>& m, int measure, SsmTally* t) {
  if (measure < 0) {
    ++t->conflicts;
    return;
  }
  ++t->by_measure[measure];
  const double v = m[measure].value;
  if (measure == static_cast<int>(SsmMeasure::kTtc))
    t->ttc_min = std::isnan(t->ttc_min) ? v : std::min(t->ttc_min, v);
  if (measure == static_cast<int>(SsmMeasure::kDrac))
    t->drac_max = std::isnan(t->drac_max) ? v : std::max(t->drac_max, v);
}

}  // namespace

bool SsmPasses(const SsmRules& r, SsmMeasure m, double v) {
  const int k = static_cast<int>(m);
  if (!r.on[k] || std::isnan(v)) return false;
  switch (m) {
    case SsmMeasure::kTtc: return v > 0 && v <= r.threshold[k];
    case SsmMeasure::kDrac: return v >= r.threshold[k];
    case SsmMeasure::kPet: return v <= r.threshold[k];
  }
  return false;
}

namespace {

// The <conflict> records of SUMO's SSM log, each pair as a < b (counted in
// run->records).
std::vector<Record> ReadRecords(const pugi::xml_node& log, SsmRun* run) {
  std::vector<Record> records;
  for (pugi::xml_node c : log.children("conflict")) {
    ++run->records;
    Record r;
    r.a = c.attribute("ego").value();
    r.b = c.attribute("foe").value();
    if (r.b < r.a) std::swap(r.a, r.b);
    r.begin = c.attribute("begin").as_double();
    r.end = c.attribute("end").as_double();
    for (int k = 0; k < kSsmMeasures; ++k) r.m[k] = ReadExtreme(c.child(kElement[k]));
    records.push_back(std::move(r));
  }
  return records;
}

// One conflict per pair and overlapping stretch of time (the records of
// both vehicles' devices merged).
std::vector<Record> MergeRecords(std::vector<Record> records) {
  std::sort(records.begin(), records.end(), [](const Record& p, const Record& q) {
    return std::tie(p.a, p.b, p.begin, p.end) < std::tie(q.a, q.b, q.begin, q.end);
  });
  std::vector<Record> conflicts;
  for (Record& r : records) {
    if (!conflicts.empty()) {
      Record& last = conflicts.back();
      if (last.a == r.a && last.b == r.b && r.begin <= last.end) {
        last.end = std::max(last.end, r.end);
        for (int k = 0; k < kSsmMeasures; ++k) last.m[k] = Worse(k, last.m[k], r.m[k]);
        continue;
      }
    }
    conflicts.push_back(std::move(r));
  }
  return conflicts;
}

// Each game's pair measures: the worst of its AV and HV's conflicts with
// each other around the game.
void GamePairs(const std::vector<Record>& conflicts, const std::vector<SsmGame>& games,
               const SsmRules& rules, SsmRun* run) {
  // The conflicts of each pair (for the games' pair measures).
  std::map<std::pair<std::string, std::string>, std::vector<const Record*>> of_pair;
  for (const Record& c : conflicts) of_pair[{c.a, c.b}].push_back(&c);
  run->games.reserve(games.size());
  for (const SsmGame& g : games) {
    SsmPair pair;
    const auto it = of_pair.find(g.av < g.hv ? std::make_pair(g.av, g.hv) : std::make_pair(g.hv, g.av));
    if (it != of_pair.end()) {
      std::array<Extreme, kSsmMeasures> worst;
      for (const Record* c : it->second) {
        if (c->end < g.time - kSsmGameBefore || c->begin > g.time + kSsmGameAfter) continue;
        for (int k = 0; k < kSsmMeasures; ++k) worst[k] = Worse(k, worst[k], c->m[k]);
      }
      auto value = [&](SsmMeasure m) {
        const int k = static_cast<int>(m);
        return rules.on[k] ? worst[k].value : kNaN;
      };
      pair.min_ttc = value(SsmMeasure::kTtc);
      pair.max_drac = value(SsmMeasure::kDrac);
      pair.min_pet = value(SsmMeasure::kPet);
    }
    run->games.push_back(pair);
  }
}

// The conflicts after the warm-up tallied for the network, the controlled
// junctions and each junction; those over a collision counted apart.
void TallyConflicts(const std::vector<Record>& conflicts, const SsmRules& rules,
                    const std::vector<SsmJunctionArea>& areas,
                    const std::vector<SsmCollision>& collisions, SsmRun* run) {
  // The collisions by pair: a conflict over one of them is that collision.
  std::map<std::pair<std::string, std::string>, std::vector<double>> collided;
  for (const SsmCollision& c : collisions)
    collided[c.a < c.b ? std::make_pair(c.a, c.b) : std::make_pair(c.b, c.a)].push_back(c.time);
  auto is_collision = [&](const Record& c) {
    const auto it = collided.find({c.a, c.b});
    if (it == collided.end()) return false;
    for (double t : it->second)
      if (t >= c.begin - kSsmCollisionSlack && t <= c.end + kSsmCollisionSlack) return true;
    return false;
  };
  for (const Record& c : conflicts) {
    if (c.begin < rules.warmup) continue;
    if (is_collision(c)) {
      bool counted = false;
      for (int k = 0; k < kSsmMeasures; ++k) counted = counted || Passes(rules, k, c.m[k].value);
      run->collided += counted;
      continue;
    }
    int first = -1;  // the measure placing the conflict itself
    for (int k = 0; k < kSsmMeasures; ++k) {
      if (!Passes(rules, k, c.m[k].value)) continue;
      if (first < 0) first = k;
      Add(c.m, k, &run->network);
      if (const SsmJunctionArea* j = JunctionAt(areas, rules.junction_radius, c.m[k].x, c.m[k].y)) {
        Add(c.m, k, &run->at_junctions);
        Add(c.m, k, &run->junction[j->junction]);
      }
    }
    if (first < 0) continue;
    Add(c.m, -1, &run->network);
    if (const SsmJunctionArea* j = JunctionAt(areas, rules.junction_radius, c.m[first].x, c.m[first].y)) {
      Add(c.m, -1, &run->at_junctions);
      Add(c.m, -1, &run->junction[j->junction]);
    }
  }
}

}  // namespace

SsmRun ReadSsmOutput(const std::string& path, const SsmRules& rules,
                     const std::vector<SsmJunctionArea>& areas,
                     const std::vector<SsmGame>& games,
                     const std::vector<SsmCollision>& collisions) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_file(path.c_str());
  if (!ok) throw std::runtime_error(path + ": cannot read SUMO's SSM output (" + ok.description() + ")");
  const pugi::xml_node log = doc.child("SSMLog");
  if (!log) throw std::runtime_error(path + ": not SUMO's SSM output (no <SSMLog>)");
  SsmRun run;
  run.on = true;
  run.rules = rules;
  for (const SsmJunctionArea& a : areas) run.junction[a.junction];  // every junction, 0 or more

  const std::vector<Record> conflicts = MergeRecords(ReadRecords(log, &run));
  GamePairs(conflicts, games, rules, &run);
  TallyConflicts(conflicts, rules, areas, collisions, &run);
  return run;
}

// ------------------------------------------------------------------ metrics

namespace {

const SsmTally kNoConflicts{};

// The conflicts a metric counts: the network's (policy) or the junction's.
const SsmTally& Tally(const MetricFacts& f) {
  const SsmRun& s = f.run->ssm;
  if (!f.junction) return s.network;
  const auto it = s.junction.find(f.junction->id);
  return it == s.junction.end() ? kNoConflicts : it->second;
}
// Those at the controlled junctions (policy) or at this one, and the
// vehicles through them.
const SsmTally& AtJunctions(const MetricFacts& f) {
  return f.junction ? Tally(f) : f.run->ssm.at_junctions;
}
long Crossings(const MetricFacts& f) {
  return f.junction ? f.junction->crossings_av + f.junction->crossings_hv
                    : f.run->crossings_av + f.run->crossings_hv;
}
// The count of `measure` (-1: any), NaN for a measure SUMO did not compute.
double Count(const SsmTally& t, const MetricFacts& f, int measure) {
  if (measure < 0) return static_cast<double>(t.conflicts);
  return f.run->ssm.rules.on[measure] ? static_cast<double>(t.by_measure[measure]) : kNaN;
}
template <int kMeasure>
double Conflicts(const MetricFacts& f) {
  return Count(Tally(f), f, kMeasure);
}
template <int kMeasure>
double ConflictsPerHour(const MetricFacts& f) {
  return PerHour(Count(Tally(f), f, kMeasure), f.run->measured_seconds);
}
template <int kMeasure>
double ConflictsPer1000(const MetricFacts& f) {
  const long n = Crossings(f);
  return n > 0 ? 1000.0 * Count(AtJunctions(f), f, kMeasure) / static_cast<double>(n) : kNaN;
}

// Games without a collision whose pair measures pass a threshold
// (`measure` -1: any), NaN for a measure SUMO did not compute.
double NearMisses(const MetricFacts& f, int measure) {
  if (measure < 0) return static_cast<double>(f.s.near_misses);
  return f.run->ssm.rules.on[measure] ? static_cast<double>(f.s.near_misses_by[measure]) : kNaN;
}
template <int kMeasure>
double NearMissCount(const MetricFacts& f) {
  return NearMisses(f, kMeasure);
}
template <int kMeasure>
double NearMissRate(const MetricFacts& f) {
  const double k = NearMisses(f, kMeasure);
  return std::isnan(k) ? kNaN : Rate(static_cast<long>(k), f.s.n - f.s.collisions);
}

constexpr int kAny = -1;
constexpr int kTtc = static_cast<int>(SsmMeasure::kTtc);
constexpr int kDrac = static_cast<int>(SsmMeasure::kDrac);
constexpr int kPet = static_cast<int>(SsmMeasure::kPet);
constexpr unsigned kPJ = kPolicyLevel | kJunctionLevel;
using T = MetricType;
using S = MetricScope;

// ssm_near_misses' sentence, its window from kSsmGameBefore / kSsmGameAfter.
const char* NearMissSentence() {
  static const std::string s =
      "games without a collision whose AV and HV had an SSM conflict with each other (any "
      "measure past its threshold, over a span from " +
      std::to_string(static_cast<int>(kSsmGameBefore)) + " s before the game formed to " +
      std::to_string(static_cast<int>(kSsmGameAfter)) +
      " s after; a collision counts in collisions, not here; docs/ssm.md)";
  return s.c_str();
}

// clang-format off
// SUMO's SSM conflicts, all and by measure: counts, per hour, per 1,000 crossings.
std::vector<Metric> SsmConflictMetrics() {
  return {
    {"ssm_conflicts", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "SUMO's SSM conflicts after the warm-up, any measure past its threshold (one per vehicle "
     "pair and stretch of time; run: the network, junction: at it; docs/ssm.md)",
     Conflicts<kAny>},
    {"ssm_conflicts_per_hour", T::kReal, "1/h", kPJ, S::kSsm, Pool::kMean, nullptr, nullptr,
     nullptr, "ssm_conflicts per measured hour", ConflictsPerHour<kAny>},
    {"ssm_conflicts_per_1000_crossings", T::kReal, "", kPJ, S::kSsm, Pool::kWeighted, nullptr,
     "crossings_all", nullptr,
     "SSM conflicts at the controlled junctions (junction: at it) per 1,000 vehicles through "
     "them", ConflictsPer1000<kAny>},
    {"ssm_ttc_conflicts", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "of ssm_conflicts, those with a time to collision in (0, threshold] (empty: TTC not "
     "measured)", Conflicts<kTtc>},
    {"ssm_ttc_conflicts_per_hour", T::kReal, "1/h", kPJ, S::kSsm, Pool::kMean, nullptr, nullptr,
     nullptr, "ssm_ttc_conflicts per measured hour", ConflictsPerHour<kTtc>},
    {"ssm_ttc_conflicts_per_1000_crossings", T::kReal, "", kPJ, S::kSsm, Pool::kWeighted,
     nullptr, "crossings_all", nullptr,
     "TTC conflicts at the controlled junctions per 1,000 vehicles through them",
     ConflictsPer1000<kTtc>},
    {"ssm_drac_conflicts", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "of ssm_conflicts, those with a deceleration rate to avoid a crash at or above the "
     "threshold (empty: DRAC not measured)", Conflicts<kDrac>},
    {"ssm_drac_conflicts_per_hour", T::kReal, "1/h", kPJ, S::kSsm, Pool::kMean, nullptr,
     nullptr, nullptr, "ssm_drac_conflicts per measured hour", ConflictsPerHour<kDrac>},
    {"ssm_drac_conflicts_per_1000_crossings", T::kReal, "", kPJ, S::kSsm, Pool::kWeighted,
     nullptr, "crossings_all", nullptr,
     "DRAC conflicts at the controlled junctions per 1,000 vehicles through them",
     ConflictsPer1000<kDrac>},
    {"ssm_pet_conflicts", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "of ssm_conflicts, those with a post-encroachment time at or below the threshold (empty: "
     "PET not measured)", Conflicts<kPet>},
    {"ssm_pet_conflicts_per_hour", T::kReal, "1/h", kPJ, S::kSsm, Pool::kMean, nullptr, nullptr,
     nullptr, "ssm_pet_conflicts per measured hour", ConflictsPerHour<kPet>},
    {"ssm_pet_conflicts_per_1000_crossings", T::kReal, "", kPJ, S::kSsm, Pool::kWeighted,
     nullptr, "crossings_all", nullptr,
     "PET conflicts at the controlled junctions per 1,000 vehicles through them",
     ConflictsPer1000<kPet>},
  };
}

// The games' near misses, all and by measure, and what their rates are per.
std::vector<Metric> SsmNearMissMetrics() {
  return {
    {"encounters_no_collision", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr,
     nullptr, "encounters in which the AV and the HV did not collide (what a near-miss rate is per)",
     [](const MetricFacts& f) { return static_cast<double>(f.s.n - f.s.collisions); }},
    {"ssm_near_misses", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     NearMissSentence(), NearMissCount<kAny>},
    {"ssm_near_miss_rate", T::kReal, "", kPJ, S::kSsm, Pool::kRate, "ssm_near_misses",
     "encounters_no_collision", nullptr, "ssm_near_misses per encounter without a collision",
     NearMissRate<kAny>},
    {"ssm_ttc_near_misses", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "of ssm_near_misses, those with a TTC conflict", NearMissCount<kTtc>},
    {"ssm_ttc_near_miss_rate", T::kReal, "", kPJ, S::kSsm, Pool::kRate, "ssm_ttc_near_misses",
     "encounters_no_collision", nullptr, "ssm_ttc_near_misses per encounter without a collision",
     NearMissRate<kTtc>},
    {"ssm_drac_near_misses", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "of ssm_near_misses, those with a DRAC conflict (a hard brake needed)", NearMissCount<kDrac>},
    {"ssm_drac_near_miss_rate", T::kReal, "", kPJ, S::kSsm, Pool::kRate, "ssm_drac_near_misses",
     "encounters_no_collision", nullptr, "ssm_drac_near_misses per encounter without a collision",
     NearMissRate<kDrac>},
    {"ssm_pet_near_misses", T::kCount, "", kPJ, S::kSsm, Pool::kSum, nullptr, nullptr, nullptr,
     "of ssm_near_misses, those with a PET conflict", NearMissCount<kPet>},
    {"ssm_pet_near_miss_rate", T::kReal, "", kPJ, S::kSsm, Pool::kRate, "ssm_pet_near_misses",
     "encounters_no_collision", nullptr, "ssm_pet_near_misses per encounter without a collision",
     NearMissRate<kPet>},
  };
}

// The device's collisions and warnings, and the worst TTC and DRAC.
std::vector<Metric> SsmDeviceMetrics() {
  return {
    {"ssm_conflicts_collided", T::kCount, "", kPolicyLevel, S::kSsm, Pool::kSum, nullptr, nullptr,
     nullptr,
     "conflicts the device logged between two vehicles SUMO's collision check found colliding "
     "then: the collision, counted once in the collisions and not among ssm_conflicts",
     [](const MetricFacts& f) { return static_cast<double>(f.run->ssm.collided); }},
    {"ssm_device_warnings", T::kCount, "", kPolicyLevel, S::kSsm, Pool::kSum, nullptr, nullptr,
     nullptr,
     "the SSM device's warnings, apart from sumo_warnings (a collision it saw; 'Cannot compute "
     "SSM ... at junction J': crossings there go unmeasured)",
     [](const MetricFacts& f) { return static_cast<double>(f.run->ssm.device_warnings); }},
    {"ssm_ttc_min", T::kReal, "s", kPJ, S::kSsm, Pool::kMean, nullptr, nullptr, nullptr,
     "least time to collision of the TTC conflicts (the worst; empty without one)",
     [](const MetricFacts& f) { return Tally(f).ttc_min; }},
    {"ssm_drac_max", T::kReal, "m/s^2", kPJ, S::kSsm, Pool::kMean, nullptr, nullptr, nullptr,
     "greatest deceleration rate to avoid a crash of the DRAC conflicts (the worst; empty "
     "without one)",
     [](const MetricFacts& f) { return Tally(f).drac_max; }},
  };
}
// clang-format on

}  // namespace

std::vector<Metric> SsmMetricRows() {
  std::vector<Metric> t;
  for (const auto& part : {SsmConflictMetrics, SsmNearMissMetrics, SsmDeviceMetrics}) {
    const std::vector<Metric> rows = part();
    t.insert(t.end(), rows.begin(), rows.end());
  }
  return t;
}

}  // namespace taebp
