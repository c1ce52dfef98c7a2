#include "core/deferred_signals.h"

#include <pthread.h>

#include <initializer_list>

namespace punctual {

DeferredSignals::DeferredSignals() {
    sigset_t ending;
    sigemptyset(&ending);
    for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&ending, signal);
    // pthread_sigmask, not sigprocmask: only this thread commits; the mask is per thread.
    ::pthread_sigmask(SIG_BLOCK, &ending, &previous_);
}

DeferredSignals::~DeferredSignals() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

}  // namespace punctual
