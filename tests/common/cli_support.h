// Runs the built taebp program as a user would (no shell), capturing its exit
// code, stdout and stderr. For the suites that drive the CLI.
#pragma once

#include "test_support.h"

#include <filesystem>
#include <fstream>
#include <csignal>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace taebp::test {

struct CliResult {
  int exit_code = -1;
  std::string out, err;
  std::string Describe() const {
    return "exit " + std::to_string(exit_code) + "\nstdout:\n" + out + "\nstderr:\n" + err;
  }
};

inline std::string ReadText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A started program: its pid; Wait() collects it (exit code, stdout, stderr).
class Process {
 public:
  Process(const std::string& program, const std::vector<std::string>& args,
          const std::function<void()>& in_child = {})
      : capture_(std::make_unique<TempDir>("taebp_cli")) {
    const std::string out_path = (capture_->path() / "stdout").string();
    const std::string err_path = (capture_->path() / "stderr").string();
    std::vector<std::string> all = {program};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ == 0) {
      const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out < 0 || err < 0) ::_exit(126);
      ::dup2(out, 1);
      ::dup2(err, 2);
      if (in_child) in_child();
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~Process() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      Wait();
    }
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  pid_t pid() const { return pid_; }
  // What it has written to stderr so far.
  std::string Stderr() const { return ReadText(capture_->path() / "stderr"); }
  // The exit code is 128 + N when killed by signal N.
  CliResult Wait() {
    CliResult r;
    if (pid_ < 0) return r;
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0) {
    }
    waited_ = true;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = ReadText(capture_->path() / "stdout");
    r.err = ReadText(capture_->path() / "stderr");
    return r;
  }

 private:
  std::unique_ptr<TempDir> capture_;
  pid_t pid_ = -1;
  bool waited_ = false;
};

// Runs `program args...`; `in_child` (if any) runs in the child just before
// exec (e.g. setrlimit). The exit code is 128 + N when killed by signal N.
inline CliResult RunProgram(const std::string& program, const std::vector<std::string>& args,
                            const std::function<void()>& in_child = {}) {
  return Process(program, args, in_child).Wait();
}

}  // namespace taebp::test
