#include "core/run_program.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <sstream>

extern char** environ;

namespace punctual {

int runProgram(const std::string& program, const std::vector<std::string>& args) {
    std::vector<std::string> owned = {program};
    owned.insert(owned.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : owned) argv.push_back(arg.data());
    argv.push_back(nullptr);
    // As system() does: while the child runs, a Ctrl-C (sent to the whole process group) is the
    // child's to handle: the chart scripts finish or roll back their files and print one line,
    // and this process must not die first and leave that line after the shell's prompt. The
    // child starts with the default dispositions and no blocked signal, whatever ours are.
    struct sigaction ignore {}, previousInt {}, previousQuit {};
    ignore.sa_handler = SIG_IGN;
    ::sigaction(SIGINT, &ignore, &previousInt);
    ::sigaction(SIGQUIT, &ignore, &previousQuit);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults, none;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGQUIT);
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    pid_t child = 0;
    int status = 0;
    int result = 127;
    if (posix_spawn(&child, program.c_str(), nullptr, &attributes, argv.data(), environ) == 0) {
        while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
        }
        if (WIFEXITED(status)) result = WEXITSTATUS(status);
        else if (WIFSIGNALED(status)) result = 128 + WTERMSIG(status);
    }
    posix_spawnattr_destroy(&attributes);
    ::sigaction(SIGINT, &previousInt, nullptr);
    ::sigaction(SIGQUIT, &previousQuit, nullptr);
    return result;
}

int endAsTheChildEnded(int status) {
    // 128 + N: the child ended on signal N (its own exit status or its death): end the same way.
    if (status > 128 && status < 128 + 32) {
        const int signal = status - 128;
        ::signal(signal, SIG_DFL);
        ::raise(signal);
    }
    return status;
}

std::string findOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::istringstream folders(path ? path : "");
    std::string folder;
    while (std::getline(folders, folder, ':')) {
        if (folder.empty()) continue;
        const std::string candidate = folder + "/" + name;
        if (access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return "";
}

}  // namespace punctual
