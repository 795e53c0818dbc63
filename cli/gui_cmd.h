// The visual side of the CLI, registered on the CLI11 app by main.cc:
//   taebp run CONFIG --gui [--delay MS]   watch the run in sumo-gui
//   taebp snapshot CONFIG --out FILE.png [--at S] [--set K=V]... [--policy P]
// Both drive sumo-gui through the adapter's libtraci backend
// (sumo::SetBackend(Backend::kLibtraciGui)); the runner colours vehicles by
// state (RunOptions::colour_states) and the view is framed on the track.
#pragma once

#include "taebp/controller/policy_run.h"

#include <memory>
#include <stdexcept>

namespace CLI {
class App;
}

namespace taebp::gui {

// A missing program, no display, a bad option: the message says what to do.
class GuiError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `--gui` and `--delay MS` on the `run` subcommand.
class RunGui {
 public:
  explicit RunGui(CLI::App* run);
  ~RunGui();
  // The run options for RunPolicy. With --gui it also switches the adapter to
  // sumo-gui (throws GuiError when sumo-gui or a display is missing); without
  // it, the defaults (no extra SUMO calls).
  RunOptions Prepare() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The `snapshot` subcommand.
class Snapshot {
 public:
  explicit Snapshot(CLI::App& app);
  ~Snapshot();
  bool Parsed() const;
  // Runs it (re-executing this program under xvfb-run when DISPLAY is unset);
  // returns the exit code. `argc`/`argv` are main's, for the re-execution.
  // Throws ConfigError for a bad config, SumoError when SUMO fails.
  int Run(int argc, char** argv);
  // In the copy re-executed under xvfb-run: hands `exit_code` (the code this
  // process exits with) to the parent through a file, since xvfb-run's own
  // clean-up may replace it (exit 5 when its temporary folder cannot be
  // removed). Elsewhere it does nothing.
  static void HandBack(int exit_code);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The view framed on the track: the network's bounding box with a margin, in
// the "real world" scheme. For RunOptions::after_start with sumo-gui.
void FrameTrack();

}  // namespace taebp::gui
