#include "sumo_messages.h"

#include <pugixml.hpp>

#include <iostream>
#include <regex>
#include <sstream>

#include <unistd.h>

namespace taebp::control {

const std::vector<std::string>& DemandChangingWarnings() {
  static const std::vector<std::string> kPatterns = {
      "Route file should be sorted by departure time",  // the vehicle or flow is dropped
      "has no valid route",                              // the vehicle is dropped
  };
  return kPatterns;
}

void SortSumoOutput(const std::string& text, SumoWarnings* into, std::string* rest) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("Warning: ", 0) != 0) {
      *rest += line + "\n";
      continue;
    }
    const std::string w = line.substr(9);
    // SUMO_HOME unset: taebp runs SUMO with --xml-validation never.
    if (w.rfind("Environment variable SUMO_HOME is not set", 0) == 0) continue;
    // The SSM device's own remarks ("SSM device of vehicle 'a' detected
    // collision with vehicle 'b'", "Cannot compute SSM due to bad internal
    // lane geometry at junction 'J'. ..."): the same run without the device
    // has none of them.
    if (w.rfind("SSM device of vehicle", 0) == 0 || w.rfind("Cannot compute SSM", 0) == 0) {
      ++into->ssm;
      continue;
    }
    ++into->count;
    // "Vehicle 'a'; collision with vehicle 'b', ..." and "...; junction collision with ...".
    if (w.find("collision with vehicle") != std::string::npos) {
      ++into->collisions;
      continue;
    }
    bool demand = false;
    for (const std::string& p : DemandChangingWarnings()) demand |= w.find(p) != std::string::npos;
    if (demand) into->demand_changed.push_back(w);
    if (into->first.size() < SumoMessages::kFirst) into->first.push_back(w);
  }
}

namespace {

// The first of `files` with an element <TAG id="ID"> (any depth: a vType
// inside a vTypeDistribution), for each tag in `tags`; "" if none.
std::string DefiningFile(const std::vector<std::string>& files,
                         const std::vector<std::string>& tags, const std::string& id) {
  for (const std::string& f : files) {
    pugi::xml_document doc;
    if (!doc.load_file(f.c_str())) continue;
    for (const std::string& tag : tags) {
      const std::string xpath = "//" + tag + "[@id=$id]";
      pugi::xpath_variable_set vars;
      vars.add("id", pugi::xpath_type_string);
      vars.set("id", id.c_str());
      if (doc.select_node(pugi::xpath_query(xpath.c_str(), &vars))) return f;
    }
  }
  return "";
}

}  // namespace

std::string ExplainSumoError(const std::string& message, const std::string& policy,
                             const std::vector<std::string>& files,
                             const std::string& generated_dir) {
  auto name = [&](const std::string& f) {
    if (!generated_dir.empty() && f.rfind(generated_dir, 0) == 0)
      return std::string("the trips scenario.demand generated");
    return f;
  };
  auto all = [&] {
    std::string list;
    for (const std::string& f : files) list += (list.empty() ? "" : ", ") + name(f);
    return list.empty() ? std::string("(no route or additional file)") : list;
  };
  std::smatch m;
  std::string where, fix;
  static const std::regex kType(R"(vehicle type '([^']*)')", std::regex::icase);
  static const std::regex kVehicle(R"(\b(?:vehicle|person|container) '([^']*)')",
                                   std::regex::icase);
  static const std::regex kRoute(R"(\broute '([^']*)')", std::regex::icase);
  const bool type_unknown = std::regex_search(message, m, kType);
  const std::string type = type_unknown ? m[1].str() : "";
  // The vehicle SUMO names ("vehicle type 'T'" is not one).
  const std::string vehicle = std::regex_search(message, m, kVehicle) ? m[1].str() : "";
  if (!vehicle.empty()) {
    static const std::vector<std::string> kTags = {"vehicle", "trip", "flow", "person",
                                                   "container", "personFlow"};
    std::string file = DefiningFile(files, kTags, vehicle);
    // A flow's vehicles are FLOW.N.
    if (file.empty() && vehicle.find('.') != std::string::npos)
      file = DefiningFile(files, kTags, vehicle.substr(0, vehicle.rfind('.')));
    where = "vehicle '" + vehicle + "' is " +
            (file.empty() ? "not defined in any of " + all() : "defined in " + name(file));
  } else if (std::regex_search(message, m, kRoute)) {
    const std::string file = DefiningFile(files, {"route", "routeDistribution"}, m[1].str());
    where = "route '" + m[1].str() + "' is " +
            (file.empty() ? "not defined in any of " + all() : "defined in " + name(file));
  } else if (type_unknown) {
    const std::string file = DefiningFile(files, {"vType", "vTypeDistribution"}, type);
    where = "vehicle type '" + type + "' is " +
            (file.empty() ? "not defined in any of " + all() : "defined in " + name(file));
  }
  if (type_unknown)
    fix = "define the vehicle type '" + type + "' (a <vType> in a route file or in "
          "scenario.additional) or give the vehicle a type that is defined";
  else if (std::regex_search(message, std::regex("route|connect", std::regex::icase)))
    fix = "randomTrips.py --validate or duarouter repair such routes";
  // Before the command line SUMO's start failures end with.
  const std::size_t cmd = message.find("; the command was: ");
  std::string out = message.substr(0, cmd);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  out += " (policy " + policy;
  if (!where.empty()) out += "; " + where;
  if (!fix.empty()) out += "; " + fix;
  return out + ")" + (cmd == std::string::npos ? std::string() : message.substr(cmd));
}

SumoMessages::SumoMessages() {
  std::cerr.flush();
  std::fflush(stderr);
  file_ = std::tmpfile();
  if (!file_) return;
  saved_ = ::dup(2);
  if (saved_ < 0 || ::dup2(::fileno(file_), 2) < 0) {
    if (saved_ >= 0) ::close(saved_);
    saved_ = -1;
    std::fclose(file_);
    file_ = nullptr;
  }
}

std::string SumoMessages::Restore() {
  std::string text;
  if (!file_) return text;
  std::cerr.flush();
  std::fflush(stderr);
  ::dup2(saved_, 2);
  ::close(saved_);
  saved_ = -1;
  std::rewind(file_);
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) text.append(buf, n);
  std::fclose(file_);
  file_ = nullptr;
  return text;
}

namespace {
void WriteStderr(const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(2, text.data() + done, text.size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
}
}  // namespace

SumoWarnings SumoMessages::Finish() {
  SumoWarnings w;
  std::string rest;
  SortSumoOutput(Restore(), &w, &rest);
  WriteStderr(rest);
  return w;
}

// An exception on its way: everything as SUMO wrote it.
SumoMessages::~SumoMessages() { WriteStderr(Restore()); }

}  // namespace taebp::control
