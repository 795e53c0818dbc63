// Fuzz target: the sweep plan (ExpandSweep) and the journal reader
// (ParseJournal) with the tables built from it.
// Input: a sweep config, optionally a line "%%" and --set overrides, then a
// line "%%journal" and journal text, in which "@HASH@" stands for the plan's
// config hash. Errors must be ConfigError; malformed journal lines are named
// and skipped; the tables never throw; the journal merge would write back
// (the kept entries) reads back to the same entries.
#include "fuzz_support.h"
#include "taebp/sweep/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace taebp;
  using namespace taebp::sweep;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const auto [head, journal_part] = fuzz::SplitAt(input, "%%journal");
  const auto [config_text, set_text] = fuzz::SplitAt(head, "%%");
  Plan plan;
  try {
    plan = ExpandSweep(config_text, "fuzz.yaml", fuzz::Lines(set_text));
  } catch (const ConfigError&) {
    return 0;
  }
  std::string journal_text = journal_part;
  fuzz::ReplaceAll(&journal_text, "@HASH@", plan.hash);
  Journal journal;
  try {
    journal = ParseJournal(journal_text, plan, "journal.jsonl");
  } catch (const ConfigError&) {
    return 0;  // a line of another sweep
  }
  const Tally t = CountTasks(plan.tasks, journal);
  if (static_cast<std::size_t>(t.ok + t.failed + t.missing) != plan.tasks.size())
    fuzz::Finding("CountTasks does not add up");
  const std::string jsonl = ResultsJsonl(plan, journal);
  for (const std::string& line : fuzz::Lines(jsonl))
    if (Json::parse(line).is_discarded()) fuzz::Finding("results.jsonl: a line is not JSON");
  ResultsCsv(plan, journal);
  AggregateCsv(plan, journal);
  SweepHeader(plan, "", "").dump();
  std::string rewritten;
  for (const auto& [index, e] : journal.entries) rewritten += e.dump() + "\n";
  const Journal again = ParseJournal(rewritten, plan, "rewritten.jsonl");
  if (again.entries != journal.entries || !again.corrupt.empty())
    fuzz::Finding("the rewritten journal reads back differently");
  return 0;
}
