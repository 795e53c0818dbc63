#include "paired.h"

#include "encounter_game.h"

#include "taebp/config/model.h"
#include "taebp/rundir/interrupt.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <tuple>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace taebp::control {
namespace {

using json = nlohmann::json;

json NumberOrNull(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double NumberOf(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNoValue;
}

json ToJson(const PairedRecord& r) {
  return {{"junction", r.junction},
          {"status", r.status},
          {"error", r.error},
          {"intent_go", r.intent_go},
          {"nudge", r.nudge},
          {"hv_dc", r.hv_dc},
          {"av_first", r.av_first},
          {"collision", r.collision},
          {"decided_at", NumberOrNull(r.decided_at)},
          {"av_clear", NumberOrNull(r.av_clear)},
          {"hv_clear", NumberOrNull(r.hv_clear)},
          {"third_collisions", r.third_collisions},
          {"pair_min_ttc", NumberOrNull(r.pair_min_ttc)},
          {"pair_min_pet", NumberOrNull(r.pair_min_pet)},
          {"hv_trust", r.hv_trust},
          {"theory_dc", r.theory_dc},
          {"theory_collision", r.theory_collision}};
}

void FromJson(const json& j, PairedRecord* r) {
  r->junction = j.value("junction", "");
  r->status = j.value("status", "failed");
  r->error = j.value("error", "");
  r->intent_go = j.value("intent_go", false);
  r->nudge = NumberOf(j, "nudge");
  r->hv_dc = j.value("hv_dc", false);
  r->av_first = j.value("av_first", false);
  r->collision = j.value("collision", false);
  r->decided_at = NumberOf(j, "decided_at");
  r->av_clear = NumberOf(j, "av_clear");
  r->hv_clear = NumberOf(j, "hv_clear");
  r->third_collisions = j.value("third_collisions", 0L);
  r->pair_min_ttc = NumberOf(j, "pair_min_ttc");
  r->pair_min_pet = NumberOf(j, "pair_min_pet");
  r->hv_trust = NumberOf(j, "hv_trust");
  r->theory_dc = NumberOf(j, "theory_dc");
  r->theory_collision = NumberOf(j, "theory_collision");
}

// Every descriptor of this process but `keep` onto /dev/null: a branch
// writes nothing into the run's files (SUMO's outputs, the captured stderr,
// a sweep's journal), whatever is still buffered for them.
void SilenceDescriptors(int keep) {
  const int null = ::open("/dev/null", O_RDWR);
  std::vector<int> fds;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    const std::string name = e.path().filename().string();
    char* end = nullptr;
    const long fd = std::strtol(name.c_str(), &end, 10);
    if (end && *end == '\0') fds.push_back(static_cast<int>(fd));
  }
  for (int fd : fds)
    if (fd != keep && fd != null) ::dup2(null, fd);
}

}  // namespace

Pairing::Pairing(RunState& s) : s_(s) {
  if (!s.sc.paired) return;
  for (const std::string& name : s.cfg.policies) {
    const PolicyInfo* info = FindPolicy(name);
    if (info && info->plays_game) policies_.push_back(ParseGamePolicy(name));
  }
}

void Pairing::GameForms(int av, int hv, EncounterGame& game_model) {
  if (branch_ || !s_.sc.paired || !s_.policy || !s_.measuring() || policies_.empty()) return;
  const std::string game = PolicyName(*s_.policy) + std::string("-") + std::to_string(++games_);
  for (persuasion::Policy q : policies_) {
    PairedRecord row;
    row.game = game;
    row.host = PolicyName(*s_.policy);
    row.policy = PolicyName(q);
    row.time = s_.now;
    row.av = s_.vehicles[av].id;
    row.hv = s_.vehicles[hv].id;
    int p[2];
    if (::pipe(p) != 0)
      throw std::runtime_error(std::string("scenario.paired: cannot open a pipe to a branch: ") +
                               std::strerror(errno));
    std::fflush(nullptr);  // nothing buffered is written twice
    std::cout.flush();
    std::cerr.flush();
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(p[0]);
      ::close(p[1]);
      throw std::runtime_error(std::string("scenario.paired: cannot fork a branch: ") +
                               std::strerror(errno));
    }
    if (pid == 0) {  // the branch: follows this game under q
      ::close(p[0]);
      av_ = av;
      hv_ = hv;
      game_ = game;
      StartBranch(q, game_model, p[1]);
      return;
    }
    ::close(p[1]);
    std::string text;
    char buf[4096];
    for (;;) {
      const ssize_t n = ::read(p[0], buf, sizeof buf);
      if (n > 0) {
        text.append(buf, static_cast<std::size_t>(n));
      } else if (n < 0 && errno == EINTR) {
        continue;
      } else {
        break;
      }
    }
    ::close(p[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    row.status = "failed";
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !text.empty()) {
      try {
        FromJson(json::parse(text), &row);
      } catch (const std::exception& e) {
        row.error = std::string("unreadable branch result: ") + e.what();
      }
    } else {
      row.error = WIFSIGNALED(status) ? "the branch ended by signal " + std::to_string(WTERMSIG(status)) +
                                            (WTERMSIG(status) == SIGABRT ? " (SUMO aborted)" : "")
                                      : "the branch exited " + std::to_string(WEXITSTATUS(status));
    }
    s_.out.paired.push_back(std::move(row));
    ThrowIfInterrupted();  // Ctrl-C while a branch ran
  }
}

void Pairing::StartBranch(persuasion::Policy policy, EncounterGame& game, int fd) {
  branch_ = true;
  fd_ = fd;
  policy_ = policy;
  InterruptGuard::ResetInChild();
  std::signal(SIGABRT, SIG_DFL);  // SUMO aborting ends the branch only (the parent says so)
  SilenceDescriptors(fd);
  // The run's time series are the host's: a branch writes none into its files.
  if (s_.population) s_.population->SampleInto(nullptr);
  // This game is played under `policy`, by the same HV with the trust it was
  // drawn (the paper's model: an HV's trust does not depend on what it met;
  // config.cc refuses the rest); every other game stays the run's own.
  population_ = MakePopulation(s_, policy);
  population_->Add(s_.vehicles[hv_].id, s_.vehicles[hv_].trust);
  game.PlayPairWith(av_, hv_, population_.get());
  formed_ = s_.now;
  av_id_ = s_.vehicles[av_].id;
  hv_id_ = s_.vehicles[hv_].id;
  av_edge_ = s_.sumo.RouteIndex(av_id_);
  hv_edge_ = s_.sumo.RouteIndex(hv_id_);
  third_before_ = s_.out.other_collisions_game_move;
  Sample();  // where the two are as the game forms
}

void Pairing::Drawn(int av, int hv, const AvDraw& draw) {
  if (!branch_ || drawn_ || av != av_ || hv != hv_) return;
  draw_ = draw;
  drawn_ = true;
}

void Pairing::Recorded(int av, int hv, const EncounterRecord& r) {
  if (!branch_ || recorded_ || av != av_ || hv != hv_) return;
  record_ = r;
  recorded_ = true;
}

void Pairing::Left(int h) {
  if (!branch_) return;
  if (h == av_ && std::isnan(av_clear_)) av_clear_ = s_.now - formed_;
  if (h == hv_ && std::isnan(hv_clear_)) hv_clear_ = s_.now - formed_;
}

void Pairing::Sample() {
  const int av = s_.vehicles.Find(av_id_), hv = s_.vehicles.Find(hv_id_);
  if (av != av_ || hv != hv_) return;
  for (const auto& [h, id, track] :
       {std::make_tuple(av, av_id_, &av_track_), std::make_tuple(hv, hv_id_, &hv_track_)}) {
    junction::BodySample b;
    b.t = s_.now;
    const XY p = s_.sumo.Position(id);
    b.x = p.x;
    b.y = p.y;
    b.heading = junction::HeadingFromSumoAngle(s_.sumo.Angle(id));
    b.speed = s_.sumo.Speed(id);
    b.length = s_.vehicles[h].length;
    b.width = s_.vehicles[h].width;
    track->push_back(b);
  }
}

void Pairing::Step() {
  if (!branch_) return;
  Sample();
  if (std::isnan(av_clear_) && s_.vehicles.Find(av_id_) == av_ && s_.sumo.RouteIndex(av_id_) > av_edge_)
    av_clear_ = s_.now - formed_;
  if (std::isnan(hv_clear_) && s_.vehicles.Find(hv_id_) == hv_ && s_.sumo.RouteIndex(hv_id_) > hv_edge_)
    hv_clear_ = s_.now - formed_;
  if (recorded_ && !std::isnan(av_clear_) && !std::isnan(hv_clear_)) EndBranch("ok");
  if (s_.now - formed_ >= kPairedWindow)
    EndBranch("ok", "the game's window (" + std::to_string(static_cast<int>(kPairedWindow)) +
                        " s) ended before both vehicles were past the junction");
}

PairedRecord Pairing::Row(const std::string& status, const std::string& error) const {
  PairedRecord r;
  r.status = status;
  r.error = error;
  if (recorded_) {
    r.junction = record_.junction;
    r.intent_go = record_.intent_go;
    r.nudge = record_.commanded;
    r.hv_dc = record_.hv_dc;
    r.av_first = record_.av_first;
    r.collision = record_.collision;
    r.decided_at = record_.decided_at;
    r.hv_trust = record_.hv_trust;
    r.theory_dc = record_.theory_dc;
    r.theory_collision = record_.theory_collision;
  } else {
    if (status != "failed") r.status = "unfinished";  // the window or the run ended first
    if (drawn_) {  // what is known of the game so far: the draw
      r.intent_go = draw_.intent_go;
      r.nudge = draw_.nudge_distance;
      r.av_first = draw_.goes_first;
    }
  }
  r.av_clear = av_clear_;
  r.hv_clear = hv_clear_;
  const junction::PairSurrogates m = junction::MeasurePair(av_track_, hv_track_);
  r.pair_min_ttc = m.min_ttc;
  r.pair_min_pet = m.min_pet;
  r.third_collisions = s_.out.other_collisions_game_move - third_before_;
  return r;
}

void Pairing::EndBranch(const std::string& status, const std::string& error) {
  const std::string text = ToJson(Row(status, error)).dump();
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::_exit(0);
}

}  // namespace taebp::control
