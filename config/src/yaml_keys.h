// What the parts of the one config loader share (config_yaml.cc reads keys,
// config_overrides.cc applies --set, config_json.cc writes JSON and YAML): where
// a key came from, how a value is shown in a message, and the schema's type
// traits. Private to config/src; the text checks are yaml_text.h's.
#pragma once

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace taebp::config_text {

// Where a key came from, for error messages: the file, or the --set that wrote it.
// A value as an error message shows it: at most 200 characters (a 10 MB
// value gives a short message, not a 20 MB one).
// A value as an error message shows it: control characters (a NUL, which
// would cut the message, a tab, an escape) as \xNN so that they can be seen;
// clipped past 200 characters.
inline std::string Clip(const std::string& raw) {
  std::string text;
  for (const char ch : raw) {
    const unsigned char u = static_cast<unsigned char>(ch);
    if (u < 0x20 || u == 0x7F) {
      static const char kHex[] = "0123456789abcdef";
      text += "\\x";
      text += kHex[u >> 4];
      text += kHex[u & 15];
    } else {
      text += ch;
    }
  }
  constexpr std::size_t kMax = 200;
  if (text.size() <= kMax) return text;
  std::size_t cut = kMax;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
  return text.substr(0, cut) + "... (" + std::to_string(raw.size()) + " characters)";
}

class Origins {
 public:
  Origins(std::string file) : file_(std::move(file)) {}
  void AddOverride(const std::string& key, const std::string& text) { overrides_[key] = text; }
  // Forgets the overrides of `key` and below (a key removed from the config).
  void Forget(const std::string& key) {
    for (auto it = overrides_.begin(); it != overrides_.end();)
      it = it->first == key || it->first.rfind(key + ".", 0) == 0 ? overrides_.erase(it) : ++it;
  }
  // "--set a.b=1" if `key` or one of its parents was overridden, else the file.
  std::string For(const std::string& key) const {
    for (const auto& [k, text] : overrides_) {
      if (key == k || key.rfind(k + ".", 0) == 0 || k.rfind(key + ".", 0) == 0)
        return "--set " + Clip(text);
    }
    return file_;
  }
  std::string Locate(const std::string& key, const YAML::Node& node) const {
    std::string where = For(key);
    if (where == file_ && node.IsDefined() && node.Mark().line >= 0)
      where += ":" + std::to_string(node.Mark().line + 1);
    return where;
  }

 private:
  std::string file_;
  std::map<std::string, std::string> overrides_;
};

inline std::string Join(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "." + name;
}

inline std::string Show(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + Clip(node.Scalar()) + "'";
  if (node.IsNull()) return "null";
  YAML::Emitter out;
  out << YAML::Flow << node;
  return Clip(out.c_str());
}

template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};
template <typename T>
struct IsOptional : std::false_type {};
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};

// Applies one --set KEY=VALUE to `root` (a map VALUE merges into a config
// section key by key); the keys it writes are recorded in `origins`.
void ApplyOverride(YAML::Node& root, const std::string& text, Origins* origins);

// A YAML node as JSON (scalars typed as YAML reads them).
nlohmann::ordered_json YamlToJson(const YAML::Node& node);

}  // namespace taebp::config_text
