// The describing archive: visits the config structs' Serialize() schema as
// the loader does and records each key's path, type, default and choices.
#include "taebp/config/reference.h"

#include "taebp/config/config.h"
#include "taebp/base/number_text.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace taebp {
namespace {

std::string List(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out + "]";
}

std::vector<std::string> Split(const std::string& choices) {
  std::vector<std::string> out;
  std::size_t b = 0;
  while (b <= choices.size()) {
    const std::size_t e = choices.find(", ", b);
    out.push_back(choices.substr(b, e == std::string::npos ? std::string::npos : e - b));
    if (e == std::string::npos) break;
    b = e + 2;
  }
  return out;
}

class Describer {
 public:
  Describer(std::string prefix, std::vector<ConfigKey>* out) : prefix_(std::move(prefix)), out_(out) {}

  template <typename T>
  void Visit(const char* name, T* value) {
    Describe(Key(name), *value, false);
  }

 private:
  std::string Key(const char* name) const { return prefix_.empty() ? name : prefix_ + "." + name; }
  void Add(const std::string& key, std::string type, std::string def, bool optional,
           std::vector<std::string> choices = {}, bool section = false) {
    ConfigKey k;
    k.key = key;
    k.type = std::move(type);
    k.default_value = optional ? "unset" : std::move(def);
    k.choices = std::move(choices);
    k.section = section;
    k.optional = optional;
    out_->push_back(std::move(k));
  }

  void Describe(const std::string& key, int v, bool opt) { Add(key, "integer", std::to_string(v), opt); }
  void Describe(const std::string& key, std::uint64_t v, bool opt) {
    Add(key, "non-negative integer", std::to_string(v), opt);
  }
  void Describe(const std::string& key, double v, bool opt) { Add(key, "number", NumberText(v), opt); }
  void Describe(const std::string& key, bool v, bool opt) {
    Add(key, "true or false", v ? "true" : "false", opt);
  }
  void Describe(const std::string& key, const std::string& v, bool opt) {
    Add(key, "string", v.empty() ? "\"\"" : v, opt);
  }
  void Describe(const std::string& key, const std::vector<std::string>& v, bool opt) {
    Add(key, "list of strings", List(v), opt);
  }
  void Describe(const std::string& key, const std::vector<double>& v, bool opt) {
    std::vector<std::string> text;
    for (const double x : v) text.push_back(NumberText(x));
    Add(key, "list of numbers", List(text), opt);
  }
  template <typename E, std::enable_if_t<HasEnumNames<E>::value, int> = 0>
  void Describe(const std::string& key, E v, bool opt) {
    Add(key, "one of", EnumName(v), opt, Split(EnumChoices<E>()));
  }
  // A trust: a number, or a distribution map whose keys depend on `dist`.
  void Describe(const std::string& key, const TrustSpec& v, bool opt) {
    std::vector<std::string> dists;
    for (const std::string& d : Split(EnumChoices<TrustDist>()))
      if (d != EnumName(TrustDist::kFixed)) dists.push_back(d);
    Add(key, "number or distribution", v.ToString(), opt, {}, true);
    Add(key + ".dist", "one of", "", false, dists);
    std::vector<std::string> seen;
    for (const auto& [dist, name] : EnumNames<TrustDist>::kNames) {
      (void)name;
      for (const std::string& k : TrustDistKeys(dist)) {
        bool again = false;
        for (const std::string& s : seen) again = again || s == k;
        if (again) continue;
        seen.push_back(k);
        const bool list = k == "values" || k == "weights";
        Add(key + "." + k, list ? "list of numbers" : "number", "", false);
      }
    }
  }
  // A sweep's grid: config keys mapped to lists of values.
  void Describe(const std::string& key,
                const std::vector<std::pair<std::string, std::vector<std::string>>>& v, bool opt) {
    (void)v;
    Add(key, "map: config key -> list of values", "{}", opt);
  }
  template <typename T>
  void Describe(const std::string& key, const std::optional<T>& v, bool) {
    Describe(key, v ? *v : T{}, true);
  }
  // A section: its keys follow it, with the defaults of a default-constructed struct.
  template <typename T, typename = decltype(std::declval<T&>().Serialize(
                            static_cast<Describer*>(nullptr)))>
  void Describe(const std::string& key, const T& v, bool opt) {
    Add(key, "section", "", opt, {}, true);
    out_->back().default_value = opt ? "unset" : "";
    T copy = v;
    Describer sub(key, out_);
    copy.Serialize(&sub);
  }

  std::string prefix_;
  std::vector<ConfigKey>* out_;
};

}  // namespace

std::vector<ConfigKey> ExperimentConfigReference() {
  std::vector<ConfigKey> keys;
  ExperimentConfig defaults;
  Describer d("", &keys);
  defaults.Serialize(&d);
  for (ConfigKey& k : keys) {
    const KeyDoc* doc = nullptr;
    for (const KeyDoc& line : ConfigKeyDocs())
      if (k.key == line.key) doc = &line;
    if (!doc) throw std::logic_error("config key '" + k.key + "' has no line in config/src/key_docs.cc");
    k.meaning = doc->meaning;
    k.range = doc->range;
  }
  return keys;
}

std::string ConfigReferenceMarkdown() {
  std::string out =
      "# Config keys\n\n"
      "<!-- generated by `taebp config --reference` (tools/refresh-docs); do not edit by hand -->\n\n"
      "Every key of an experiment config (`taebp run`, `taebp sweep`, `--set KEY=VALUE`), "
      "in the order of the schema (`config/include/taebp/config/config.h`): what it means, "
      "its type, its default and the values it allows. A key left out takes its default; "
      "`unset` means the key (or section) is off unless given. An unknown key, a wrong type "
      "or a value out of range is an error naming the key, the value and the file or "
      "`--set` (exit 2). `taebp config --reference --format json` prints the same as data.\n";
  for (const ConfigKey& k : ExperimentConfigReference()) {
    std::string facts = k.type;
    if (!k.choices.empty()) {
      std::string c;
      for (const std::string& x : k.choices) c += (c.empty() ? "" : ", ") + ("`" + x + "`");
      facts += " " + c;
    }
    if (!k.default_value.empty()) facts += " · default `" + k.default_value + "`";
    if (!k.range.empty()) facts += " · allowed: " + k.range;
    if (k.section && k.type == "section") {
      // A section: a heading (## for the top level, ### below), its meaning, its keys.
      const int depth = static_cast<int>(std::count(k.key.begin(), k.key.end(), '.'));
      out += "\n" + std::string(std::min(depth + 2, 4), '#') + " `" + k.key + "`\n\n" + k.meaning +
             (k.optional ? " (a section that is off unless given)" : "") + ".\n\n";
      continue;
    }
    if (k.key.find('.') == std::string::npos) {  // a top-level key: a heading of its own
      out += "\n## `" + k.key + "`\n\n" + k.meaning + ".<br>\n*" + facts + "*\n";
      continue;
    }
    out += "\n`" + k.key + "`\n:   " + k.meaning + "<br>\n    *" + facts + "*\n";
  }
  return out;
}

std::string ConfigReferenceJson() {
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const ConfigKey& k : ExperimentConfigReference()) {
    nlohmann::ordered_json j;
    j["key"] = k.key;
    j["type"] = k.type;
    j["default"] = k.default_value;
    j["choices"] = k.choices;
    j["section"] = k.section;
    j["optional"] = k.optional;
    j["allowed"] = k.range;
    j["meaning"] = k.meaning;
    keys.push_back(j);
  }
  nlohmann::ordered_json out;
  out["keys"] = keys;
  return out.dump(2) + "\n";
}

}  // namespace taebp
