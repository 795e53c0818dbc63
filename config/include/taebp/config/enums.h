// The config's options with a fixed set of values, typed: each enum's names are
// written once, in its EnumNames specialisation below, and every reader, writer
// and message goes through EnumName / ParseEnum / EnumChoices (as Ceres pairs
// StringToX with XToString, here one generic pair over one table per enum).
// The YAML loader turns a name into the enum when the config is read, so a
// value outside the set is rejected there, naming key, value, file and the
// choices; the model never compares strings.
#pragma once

#include <string>
#include <type_traits>
#include <utility>

namespace taebp {

template <typename E>
struct EnumNames;  // specialised per enum: static constexpr std::pair<E, const char*> kNames[]

// scenario.kind
enum class ScenarioKind { kFigure8, kNetwork };
// scenario.junctions.{priority, right_before_left, unregulated}: what a
// junction of that SUMO type becomes when selected.
enum class StopRule { kTwoWay, kAllWay };
// scenario.grid.junction_type (netgenerate's --default-junction-type)
enum class GridJunctionType { kAllwayStop, kPriorityStop, kPriority, kRightBeforeLeft };
// scenario.demand.routing
enum class Routing { kRandom };
// scenario.demand.origins: where generated trips start and end.
enum class DemandOrigins { kFringe, kMinorRoads };
// scenario.nudge_check: a nudge SUMO did not realise stops the run or is counted.
enum class NudgeCheck { kError, kCount };
// scenario.stall_action: a stall stops the run or is recorded.
enum class StallAction { kError, kRecord };
// scenario.encounter_pairs: which AV-HV meetings are the game.
enum class EncounterPairs { kColliding, kAll };
// model.likelihood.type
enum class LikelihoodType { kLinear, kLogistic };
// model.trust.dist
enum class TrustDist { kFixed, kUniform, kBeta, kDiscrete };
// model.trust_knowledge (unset: assumed when assumed_trust is set, else exact)
enum class TrustKnowledge { kExact, kPopulationMean, kAssumed };
// model.noise.kind
enum class NoiseKind { kNone, kGaussian, kUniform };
// model.noise.design
enum class NoiseDesign { kAware, kPaper };
// model.experience.design: what ta_ebp commits to for an HV that learns.
enum class ExperienceDesign { kGuarded, kPaper, kRobust };

#define TAEBP_ENUM_NAMES(E, ...)                                   \
  template <>                                                      \
  struct EnumNames<E> {                                            \
    static constexpr std::pair<E, const char*> kNames[] = {__VA_ARGS__}; \
  }
TAEBP_ENUM_NAMES(ScenarioKind, {ScenarioKind::kFigure8, "figure8"}, {ScenarioKind::kNetwork, "network"});
TAEBP_ENUM_NAMES(StopRule, {StopRule::kTwoWay, "two_way"}, {StopRule::kAllWay, "all_way"});
TAEBP_ENUM_NAMES(GridJunctionType, {GridJunctionType::kAllwayStop, "allway_stop"},
                 {GridJunctionType::kPriorityStop, "priority_stop"},
                 {GridJunctionType::kPriority, "priority"},
                 {GridJunctionType::kRightBeforeLeft, "right_before_left"});
TAEBP_ENUM_NAMES(Routing, {Routing::kRandom, "random"});
TAEBP_ENUM_NAMES(DemandOrigins, {DemandOrigins::kFringe, "fringe"},
                 {DemandOrigins::kMinorRoads, "minor_roads"});
TAEBP_ENUM_NAMES(NudgeCheck, {NudgeCheck::kError, "error"}, {NudgeCheck::kCount, "count"});
TAEBP_ENUM_NAMES(StallAction, {StallAction::kError, "error"}, {StallAction::kRecord, "record"});
TAEBP_ENUM_NAMES(EncounterPairs, {EncounterPairs::kColliding, "colliding"},
                 {EncounterPairs::kAll, "all"});
TAEBP_ENUM_NAMES(LikelihoodType, {LikelihoodType::kLinear, "linear"},
                 {LikelihoodType::kLogistic, "logistic"});
TAEBP_ENUM_NAMES(TrustDist, {TrustDist::kFixed, "fixed"}, {TrustDist::kUniform, "uniform"},
                 {TrustDist::kBeta, "beta"}, {TrustDist::kDiscrete, "discrete"});
TAEBP_ENUM_NAMES(TrustKnowledge, {TrustKnowledge::kExact, "exact"},
                 {TrustKnowledge::kPopulationMean, "population_mean"},
                 {TrustKnowledge::kAssumed, "assumed"});
TAEBP_ENUM_NAMES(NoiseKind, {NoiseKind::kNone, "none"}, {NoiseKind::kGaussian, "gaussian"},
                 {NoiseKind::kUniform, "uniform"});
TAEBP_ENUM_NAMES(NoiseDesign, {NoiseDesign::kAware, "aware"}, {NoiseDesign::kPaper, "paper"});
TAEBP_ENUM_NAMES(ExperienceDesign, {ExperienceDesign::kGuarded, "guarded"},
                 {ExperienceDesign::kPaper, "paper"},
                 {ExperienceDesign::kRobust, "robust"});
#undef TAEBP_ENUM_NAMES

// The name of a value, as the config writes it.
template <typename E>
const char* EnumName(E value) {
  for (const auto& [v, name] : EnumNames<E>::kNames)
    if (v == value) return name;
  return "?";
}
// The value of a name; false (value untouched) for a name outside the set.
template <typename E>
bool ParseEnum(const std::string& name, E* value) {
  for (const auto& [v, n] : EnumNames<E>::kNames) {
    if (name == n) {
      *value = v;
      return true;
    }
  }
  return false;
}
// "a, b, c": the names in declaration order, for messages.
template <typename E>
std::string EnumChoices() {
  std::string out;
  for (const auto& [v, name] : EnumNames<E>::kNames) {
    (void)v;
    out += (out.empty() ? "" : ", ") + std::string(name);
  }
  return out;
}

// Whether E is one of the enums above (the loader's dispatch).
template <typename E, typename = void>
struct HasEnumNames : std::false_type {};
template <typename E>
struct HasEnumNames<E, std::void_t<decltype(EnumNames<E>::kNames)>> : std::true_type {};

}  // namespace taebp
