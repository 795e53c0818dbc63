// The experiment config's schema as data, for the generated reference
// (`taebp config --reference`, docs/reference/config.md): every key the
// loader knows, with its type, its default (from a default-constructed
// ExperimentConfig) and, for an option with a fixed set of values, its
// choices (enums.h), all read from the structs' Serialize() schema by a
// describing archive; and the one table of what each key means and which
// values it allows (key_docs.cc).
#pragma once

#include <string>
#include <vector>

namespace taebp {

struct ConfigKey {
  std::string key;            // full path, e.g. "scenario.demand.flow"
  std::string type;           // "number", "integer", "true or false", "section", ...
  std::string default_value;  // as a config writes it; "unset" when left out means off or derived
  std::vector<std::string> choices;  // an option with a fixed set of values, in order
  bool section = false;       // a map of keys of its own (they follow it)
  bool optional = false;      // a section or value that is off (unset) unless given
  std::string meaning;        // one line, from the key table
  std::string range;          // the values allowed, from the key table
};

// Every key of an experiment config, in schema order, each section before
// its keys; the meaning and range from ConfigKeyDocs(). Throws
// std::logic_error when a key has no line in the table.
std::vector<ConfigKey> ExperimentConfigReference();

// The key table: one line per key of ExperimentConfigReference().
struct KeyDoc {
  const char* key;
  const char* meaning;
  const char* range;  // "" when the type says it all
};
const std::vector<KeyDoc>& ConfigKeyDocs();

// The reference as a markdown page (docs/reference/config.md) and as JSON.
std::string ConfigReferenceMarkdown();
std::string ConfigReferenceJson();

}  // namespace taebp
