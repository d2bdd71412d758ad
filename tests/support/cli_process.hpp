#pragma once
/// Running the seqmassage executable from tests: to completion (exit code, stdout, stderr), from a
/// shell command line or an argument list (optionally under a file size limit), or in the
/// background as a child process that a test can signal and wait for.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"

namespace sm::test {

struct CliRun {
  int code = -1;    // exit status, or -1 if killed by a signal
  std::string out;  // stdout
  std::string err;  // stderr
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The run that ended with wait status `status`, its output read from (and then removed) the
// files `out` and `err`.
inline CliRun finished_run(int status, const std::filesystem::path& out,
                           const std::filesystem::path& err) {
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Runs seqmassage with `args` (a shell command line: quoted where needed) in the folder `cwd`.
inline CliRun run_cli(const std::filesystem::path& cwd, const std::string& args) {
  const std::filesystem::path out = cwd / "cli_stdout.txt", err = cwd / "cli_stderr.txt";
  const std::string command = "cd " + shell_quote(cwd.string()) + " && " +
                              shell_quote(SEQMASSAGE_BIN) + " " + args + " >" +
                              shell_quote(out.string()) + " 2>" + shell_quote(err.string());
  return finished_run(std::system(command.c_str()), out, err);
}

// Runs seqmassage with the arguments `args` in `cwd`, without a shell; with `file_size_limit`,
// under RLIMIT_FSIZE of that many bytes (writes beyond it fail with EFBIG, as a full disk fails
// with ENOSPC) and SIGXFSZ ignored.
inline CliRun run_cli_args(const std::filesystem::path& cwd, std::vector<std::string> args,
                           std::optional<rlim_t> file_size_limit = std::nullopt) {
  const std::filesystem::path out = cwd / ".stdout", err = cwd / ".stderr";
  args.insert(args.begin(), SEQMASSAGE_BIN);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);  // or the child would write the parent's buffered output again
  const pid_t pid = ::fork();
  if (pid < 0) return CliRun{};
  if (pid == 0) {  // only async-signal-safe calls until exec
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0 || ::chdir(cwd.c_str()) != 0)
      ::_exit(97);
    if (file_size_limit) {
      ::signal(SIGXFSZ, SIG_IGN);
      const struct rlimit limit = {*file_size_limit, *file_size_limit};
      if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(96);
    }
    ::execv(argv[0], argv.data());
    ::_exit(98);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return finished_run(status, out, err);
}

// Starts seqmassage with `args` in `cwd`, output discarded; returns its pid.
inline pid_t spawn_cli(const std::filesystem::path& cwd, const std::vector<std::string>& args) {
  std::fflush(nullptr);  // or the child would write the parent's buffered output again
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  if (::chdir(cwd.c_str()) != 0) ::_exit(99);
  if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr))
    ::_exit(97);
  std::vector<char*> argv = {const_cast<char*>(SEQMASSAGE_BIN)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(SEQMASSAGE_BIN, argv.data());
  ::_exit(98);
}

// Waits for `pid`; its exit status, or 128 + the signal that ended it.
inline int wait_cli(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace sm::test
