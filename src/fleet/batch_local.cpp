#include "fleet/batch_local.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "core/atomic_file.hpp"

extern char** environ;

namespace revisit {
namespace fs = std::filesystem;
namespace {

/// Starts `executable arguments...` with stdout and stderr into `log_file`; returns the child's pid.
pid_t Spawn(const fs::path& executable, const std::vector<std::string>& arguments, const fs::path& log_file) {
    // The log grows while the run works (users follow it), so it is not written through a temporary;
    // whatever has its name is replaced, never written through (core/atomic_file.hpp).
    const int log_fd = CreateFileExclusively(log_file);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, log_fd, STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, log_fd, STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    std::vector<std::string> words = {executable.string()};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int error = posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(log_fd);
    if (error != 0) throw std::runtime_error("cannot start " + executable.string() + ": error " + std::to_string(error));
    return pid;
}

int ExitCode(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0); }

}  // namespace

LocalOutcome RunLocally(const BatchPlan& plan, const std::vector<std::size_t>& indices, int jobs, std::ostream& log) {
    fs::create_directories(plan.out / "logs");
    LocalOutcome outcome;
    std::map<pid_t, std::size_t> running;
    std::size_t next = 0, done = 0;
    while (next < indices.size() || !running.empty()) {
        while (next < indices.size() && int(running.size()) < std::max(1, jobs)) {
            const auto& task = plan.tasks[indices[next]];
            running[Spawn(plan.executable, task.arguments, task.log)] = indices[next];
            ++next;
        }
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) break;
        const auto it = running.find(pid);
        if (it == running.end()) continue;
        const auto& task = plan.tasks[it->second];
        ++done;
        const bool ok = ExitCode(status) == 0 && TaskFinished(task);
        log << "run " << done << "/" << indices.size() << ": " << task.name << (ok ? " finished" : " FAILED (exit " + std::to_string(ExitCode(status)) + ")")
            << (ok ? "" : "; log " + task.log.string()) << '\n';
        if (!ok) outcome.failed.push_back(it->second);
        running.erase(it);
    }
    std::sort(outcome.failed.begin(), outcome.failed.end());
    for (const auto& task : plan.tasks) {
        if (!TaskFinished(task)) {
            if (!std::count(outcome.failed.begin(), outcome.failed.end(), task.index)) outcome.failed.push_back(task.index);
        }
    }
    if (!outcome.failed.empty()) return outcome;
    int status = 0;
    waitpid(Spawn(plan.executable, plan.merge_arguments, plan.merge_log), &status, 0);
    outcome.merge_exit = ExitCode(status);
    log << "merge: exit " << outcome.merge_exit << "; log " << plan.merge_log.string() << '\n';
    return outcome;
}

}  // namespace revisit
