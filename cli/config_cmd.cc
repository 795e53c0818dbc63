#include "config_cmd.h"

#include "taebp/config/reference.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace taebp::cli {

ConfigCommand::ConfigCommand(CLI::App& app) {
  command_ = app.add_subcommand(
      "config", "The experiment config's keys: type, default, allowed values and meaning");
  command_->add_flag("--reference", reference_,
                     "print every key the loader knows (docs/reference/config.md)")
      ->required();
  command_->add_option("--format", format_, "md: the manual's page; json: the keys as data")
      ->check(CLI::IsMember({"md", "json"}))
      ->capture_default_str();
}

bool ConfigCommand::Parsed() const { return command_->parsed(); }

int ConfigCommand::Run() const {
  std::cout << (format_ == "json" ? ConfigReferenceJson() : ConfigReferenceMarkdown());
  return 0;
}

}  // namespace taebp::cli
