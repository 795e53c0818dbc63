// A sweep's folder: which sweep and shard it holds (sweep.json), what is left
// to run, and the tables rebuilt from the journal (results.csv,
// results.jsonl, aggregate.csv, the pooled encounters.csv, sweep.json).
#pragma once

#include "taebp/sweep/plan.h"

#include <filesystem>
#include <string>
#include <vector>

namespace taebp::sweep::internal {

namespace fs = std::filesystem;

// The files a sweep writes into its folder with WriteFilesAtomically (their
// temporaries, left by a kill, are removed when the folder is next locked).
inline const std::vector<std::string> kSweepFiles = {"sweep.json", "journal.jsonl", "results.csv",
                                                     "aggregate.csv", "encounters.csv"};

// The whole file; throws "cannot read PATH".
std::string ReadText(const fs::path& path);

// "no space left on device in DIR" when a file of a task's size cannot be
// written into `dir` (a full disk or quota), else "".
std::string NoSpaceIn(const fs::path& dir);

// --shard I/N (empty: 0/1); ConfigError naming the option otherwise.
void ParseShard(const std::string& text, int* index, int* count);

// "shard I/N", or "the unsharded sweep".
std::string ShardName(const std::string& shard);

// Refuses a directory that holds another sweep or, for `sweep` (check_shard),
// another shard of this one: a folder belongs to one (sweep, shard).
void CheckHeader(const fs::path& dir, const std::string& hash, bool check_shard = false,
                 const std::string& shard = "");

// Whether a finished task left its files (summary.json) in its folder.
bool HasTaskOutputs(const fs::path& task_dir);

// One warning line per corrupt journal line; `who` is "sweep" or "merge".
void WarnCorrupt(const Journal& journal, const char* who);

// The tasks of `scope` (a shard's tasks) still to run: no ok entry yet, or
// an ok entry whose task folder lost its outputs (`lost` counts those).
std::vector<Task> Pending(const std::vector<Task>& scope, const Journal& j, const fs::path& out,
                          int* lost);

// The SUMO version the journal's tasks ran with ("" when none recorded it).
std::string SumoVersionOf(const Journal& journal);

// The sweep's tables from the journal, each written atomically, and the
// pooled encounters.csv (every ok task's rows with its point, replicate,
// seed and swept values in front).
void WriteOutputs(const fs::path& out, const Plan& plan, const Journal& journal, Json header);

}  // namespace taebp::sweep::internal
