#pragma once
// Running another program (the bench's chart scripts, play's ffmpeg): no shell, its output passed
// through, and the signals a terminal sends left to it while it runs.
#include <string>
#include <vector>

namespace punctual {

// Runs `program` with `args` (no shell), its output passed through; returns its exit status
// (127 when it could not be started).
// SIGINT and SIGQUIT are the child's while it runs (this process ignores them, as system() does).
int runProgram(const std::string& program, const std::vector<std::string>& args);

// For a child's status of 128 + N (it ended on signal N, or exited so after handling it): ends
// this process by signal N too. Returns `status` for any other.
int endAsTheChildEnded(int status);

// The first executable `name` in a folder of $PATH; empty when there is none.
std::string findOnPath(const std::string& name);

}  // namespace punctual
