#include "vehicles.h"

#include <algorithm>
#include <utility>

namespace taebp::control {
namespace {
constexpr std::uint64_t kSaltAv = 0x6176;     // "av"
constexpr std::uint64_t kSaltTrust = 0x7472;  // "tr"
}  // namespace

int VehicleRegistry::Add(Vehicle v) {
  int h;
  if (!free_slots_.empty()) {  // the last freed first
    h = free_slots_.back();
    free_slots_.pop_back();
  } else {
    h = static_cast<int>(vehs_.size());
    vehs_.emplace_back();
  }
  index_[v.id] = h;
  vehs_[h] = std::move(v);
  return h;
}

void VehicleRegistry::Remove(int h) {
  Vehicle& v = vehs_[h];
  v.alive = false;
  v.route.clear();
  index_.erase(v.id);
  if (v.open_encounters == 0) free_slots_.push_back(h);  // else once recorded
}

void VehicleRegistry::EncounterDone(int h) {
  if (--vehs_[h].open_encounters == 0 && !vehs_[h].alive) free_slots_.push_back(h);
}

double HashUniform(std::uint64_t seed, const std::string& text, std::uint64_t salt) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ULL ^ h ^ (salt << 1);
  for (int i = 0; i < 2; ++i) {  // splitmix64 finaliser, twice
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    x ^= x >> 31;
  }
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}

bool IsAv(const ScenarioConfig& sc, const std::string& id,
          const std::function<std::string()>& type_of) {
  if (sc.av_share) return HashUniform(sc.seed, id, kSaltAv) < *sc.av_share;
  const std::string type = type_of();
  return std::find(sc.av_types.begin(), sc.av_types.end(), type) != sc.av_types.end();
}

double HvTrust(const ExperimentConfig& cfg, const std::string& id) {
  const TrustSpec& t = cfg.model.trust;
  return t.IsFixed() ? t.value : t.Draw(HashUniform(cfg.scenario.seed, id, kSaltTrust));
}

}  // namespace taebp::control
