#pragma once
/// Runs the built `revisit` binary as a user would and captures what it prints.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace revisit::test {

struct CliResult {
    int exit_code = -1;
    std::string output;  ///< stdout and stderr together
};

/// `arguments` is appended to the binary path as is (quote paths yourself).
inline CliResult RunCli(const std::string& arguments) {
    CliResult result;
    const std::string command = std::string("\"") + REVISIT_CLI + "\" " + arguments + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

inline std::string Quote(const std::string& text) { return "'" + text + "'"; }

}  // namespace revisit::test
