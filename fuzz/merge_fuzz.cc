// Fuzz target: `taebp merge` of one shard folder whose sweep.json and
// journal.jsonl are the input (sweep.json, a line "%%journal", the journal).
// Errors must be ConfigError (bad input) or OutputError; anything else, a
// crash or a leak is a finding.
#include "fuzz_support.h"
#include "taebp/config/config.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/sweep/engine.h"

#include <filesystem>
#include <fstream>

#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir =
      fs::temp_directory_path() / ("taebp_merge_fuzz." + std::to_string(::getpid()));
  const fs::path shard = dir / "shard", out = dir / "out";
  fs::remove_all(dir);
  fs::create_directories(shard);
  const std::string input(reinterpret_cast<const char*>(data), size);
  const auto [header, journal] = taebp::fuzz::SplitAt(input, "%%journal");
  std::ofstream(shard / "sweep.json", std::ios::binary) << header;
  std::ofstream(shard / "journal.jsonl", std::ios::binary) << journal;
  taebp::sweep::MergeOptions o;
  o.out = out.string();
  o.dirs = {shard.string()};
  o.quiet = true;
  try {
    taebp::sweep::RunMerge(o);
  } catch (const taebp::ConfigError&) {
  } catch (const taebp::OutputError&) {
  }
  fs::remove_all(dir);
  return 0;
}
