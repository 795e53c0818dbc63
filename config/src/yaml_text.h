// The text of a YAML config, before any key is read: valid UTF-8, one
// document (a second would be ignored by yaml-cpp), aliases bounded once
// expanded, no key given twice in any map; the one config loader's first half
// (config_yaml.cc reads the keys). Private to config/src.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

namespace taebp::config_text {

// The offset of the first byte of `s` that is not part of valid UTF-8
// (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF), or npos.
std::size_t InvalidUtf8(const std::string& s);
// One YAML document of `text`, checked as above, or a ConfigError naming `origin`.
YAML::Node OneDocument(const std::string& text, const std::string& origin);
// The same after the UTF-8 check, yaml-cpp's parse errors as ConfigErrors at their line.
YAML::Node ParseYaml(const std::string& text, const std::string& origin);
// A config file's text (NotAFile's reasons, unreadable files: ConfigError).
std::string ReadFileText(const std::string& path);
// A file's document; an empty one is a ConfigError.
YAML::Node ParseFileYaml(const std::string& path);

}  // namespace taebp::config_text
