// SUMO's outputs of one policy's run, read once SUMO has closed them: the
// files of scenario.outputs (their dated header replaced), the SSM conflicts,
// tripinfo and summary.
#include "sumo_run_outputs.h"

#include "taebp/report/ssm.h"
#include "taebp/controller/sumo_world.h"
#include "taebp/rundir/synced_file.h"

#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace taebp::control {

namespace fs = std::filesystem;

namespace {

// SUMO heads its outputs with a comment holding the date and this run's
// scratch paths: replaced (streaming: an fcd output can be large) so the
// same config and seed give the same bytes (the provenance is in
// summary.json).
constexpr const char* kOwnOutput = "<!-- SUMO's own output; provenance in summary.json -->";
void StripGeneratedComment(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const auto begin = head.find("<!-- generated on");
  const auto end = begin == std::string::npos ? begin : head.find("-->", begin);
  if (end == std::string::npos) return;
  head.replace(begin, end + 3 - begin, kOwnOutput);
  SyncedWriter writer(file.string(), /*sync=*/false);  // scratch: copied into place synced
  std::ostream& out = writer.Stream();
  out << head;
  std::vector<char> buf(1 << 20);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0)
    out.write(buf.data(), in.gcount());
  writer.Commit();
}

// SUMO's tripinfo records of the vehicles that departed after the warm-up,
// finished or not. SUMO 1.15 writes a vehicle still in the network at the
// end with arrival="-1.00" and its duration, timeLoss and waitingTime up to
// the end (vaporized="end" for some, empty for others: arrival is the
// marker); a vehicle never inserted has no record.
// AVs and HVs apart as the controller told them at their departure.
void ReadTripinfo(const std::string& path, const ScenarioConfig& sc,
                  const std::function<bool(const std::string&)>& departed_as_av,
                  NetworkRun* net) {
  pugi::xml_document doc;
  if (!doc.load_file(path.c_str())) return;
  for (pugi::xml_node t : doc.child("tripinfos").children("tripinfo")) {
    if (t.attribute("depart").as_double() < sc.warmup) continue;
    ++net->trips;
    if (t.attribute("arrival").as_double() < 0) ++net->trips_unfinished;
    net->duration_sum += t.attribute("duration").as_double();
    const double loss = t.attribute("timeLoss").as_double();
    const double waiting = t.attribute("waitingTime").as_double();
    net->time_loss_sum += loss;
    net->time_loss_max = std::max(net->time_loss_max, loss);
    net->waiting_time_sum += waiting;
    if (departed_as_av(t.attribute("id").as_string())) {
      ++net->trips_av;
      net->time_loss_sum_av += loss;
      net->waiting_time_sum_av += waiting;
    }
  }
}

// SUMO's SSM conflicts of this policy (scenario.outputs.ssm, report/ssm.h),
// placed at the controlled junctions by their internal lanes; those of a pair
// SUMO's collision check found colliding then are that collision, not a
// conflict (the collisions after the warm-up, CollisionRecord).
SsmRun ReadSsm(const fs::path& file, const ScenarioConfig& sc, const Scenario& scenario,
               const std::vector<EncounterRecord>& encounters,
               const std::vector<CollisionRecord>& collisions) {
  const SsmConfig& c = *sc.outputs.ssm;
  SsmRules rules;
  rules.on = {c.Measures("TTC"), c.Measures("DRAC"), c.Measures("PET")};
  rules.threshold = {c.thresholds.ttc, c.thresholds.drac, c.thresholds.pet};
  rules.warmup = sc.warmup;
  rules.junction_radius = c.junction_radius;
  std::vector<SsmJunctionArea> areas;
  for (const ControlledJunction& cj : scenario.junctions) {
    SsmJunctionArea a{cj.id, {}};
    if (const net::Junction* j = scenario.topology->FindJunction(cj.id)) {
      for (const std::string& id : j->int_lanes)
        if (const net::Lane* lane = scenario.topology->FindLane(id)) {
          std::vector<std::array<double, 2>> shape;
          for (const net::Point& p : lane->shape) shape.push_back({p.x, p.y});
          a.shapes.push_back(std::move(shape));
        }
      if (a.shapes.empty()) a.shapes.push_back({{j->pos.x, j->pos.y}});
    }
    areas.push_back(std::move(a));
  }
  std::vector<SsmGame> games;
  games.reserve(encounters.size());
  for (const EncounterRecord& e : encounters) games.push_back({e.av, e.hv, e.junction, e.time});
  std::vector<SsmCollision> collided;
  collided.reserve(collisions.size());
  for (const CollisionRecord& c : collisions) collided.push_back({c.collider, c.victim, c.time});
  return ReadSsmOutput(file.string(), rules, areas, games, collided);
}

}  // namespace

std::string TripinfoPath(const Scenario& scenario, const std::string& policy) {
  return (fs::path(scenario.scratch->path()) / ("tripinfo-" + policy + ".xml")).string();
}

// SUMO's outputs of one policy (scenario.outputs, and those the user's
// additional files name) are written into scratch/<policy>/ and end up in
// the run folder as <policy>/NAME.
fs::path PolicyOutputDir(const Scenario& scenario, const std::string& policy) {
  return fs::path(scenario.scratch->path()) / "outputs" / policy;
}

void ReadSumoOutputs(const ExperimentConfig& config, const Scenario& scenario,
                     const std::string& policy,
                     const std::function<bool(const std::string&)>& departed_as_av,
                     long ssm_device_warnings, PolicyRun* r) {
  if (scenario.scratch) {
    // SUMO's outputs of this policy (their files, as SUMO closed them).
    std::error_code ec;
    const fs::path dir = PolicyOutputDir(scenario, policy);
    if (config.scenario.outputs.ssm &&
        !fs::copy_file(dir / kSsmSumoFile, dir / "ssm.xml", fs::copy_options::overwrite_existing, ec))
      throw SumoError("SUMO wrote no SSM output for policy " + policy + " (" +
                      (dir / kSsmSumoFile).string() + ": " + ec.message() + ")");
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      if (!name.empty() && name[0] != '.' && e.is_regular_file(ec)) names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
      StripGeneratedComment(dir / name);
      r->sumo_output_files.emplace_back(policy + "/" + name, (dir / name).string());
    }
    if (config.scenario.outputs.ssm) {
      r->ssm = ReadSsm(dir / "ssm.xml", config.scenario, scenario, r->encounters, r->collisions);
      for (std::size_t k = 0; k < r->encounters.size() && k < r->ssm.games.size(); ++k)
        r->encounters[k].ssm = r->ssm.games[k];
      r->ssm.device_warnings = ssm_device_warnings;
    }
  }
  if (scenario.scratch && scenario.kind == ScenarioKind::kNetwork) {
    ReadTripinfo(TripinfoPath(scenario, policy), config.scenario,
                 departed_as_av,
                 &r->network);
    // SUMO's tripinfo and summary, their dated header replaced as for the
    // outputs (StripGeneratedComment).
    auto slurp = [](const fs::path& path) {
      StripGeneratedComment(path);
      std::ifstream in(path, std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    };
    if (config.scenario.tripinfo_output) r->sumo_tripinfo_xml = slurp(TripinfoPath(scenario, policy));
    if (config.scenario.summary_output)
      r->sumo_summary_xml =
          slurp(fs::path(scenario.scratch->path()) / ("summary-" + policy + ".xml"));
  }
}

}  // namespace taebp::control
