#include "sumo_messages.h"

#include <iostream>
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
