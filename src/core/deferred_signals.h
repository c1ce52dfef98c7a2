#pragma once
// Holds back the signals that end a process from the keyboard or a supervisor (SIGINT, SIGTERM,
// SIGHUP, SIGQUIT) while a short, all-or-nothing step runs, and lets them through when it ends.
//
// Why: OutputFiles::commit writes temporaries, keeps backups and renames them in turn. A Ctrl-C
// between two renames would leave some outputs new and some old, and temporaries behind. With
// the signals blocked the commit always finishes (all new) or rolls back on an error (all old),
// removes what it created, and then the pending signal is delivered with its usual effect: the
// process ends as the user asked, a moment later. SIGKILL cannot be blocked; README says what it
// can leave (a hidden .NAME.XXXXXX temporary, never a half-written output).
#include <signal.h>

namespace punctual {

class DeferredSignals {
public:
    DeferredSignals();
    ~DeferredSignals();  // restores the previous mask; a signal that arrived meanwhile is delivered now
    DeferredSignals(const DeferredSignals&) = delete;
    DeferredSignals& operator=(const DeferredSignals&) = delete;

private:
    sigset_t previous_{};
};

}  // namespace punctual
