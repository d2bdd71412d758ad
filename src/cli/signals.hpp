#pragma once
/// The signals of a run: SIGINT, SIGTERM and SIGHUP stop it gracefully (the frames in flight are
/// finished and written, summary.csv and report.json record the stop, --resume continues), a
/// second one ends it at once; SIGPIPE is ignored, so that a closed stderr or stdout (piped into
/// `head`, a terminal gone) fails those writes only and the outputs still complete.
#include <atomic>

namespace sm::cli {

/// Ignores SIGPIPE for the whole program (call first in main).
void ignore_broken_pipes();

/// Installs (or, with `on` false, removes) the handler of SIGINT, SIGTERM and SIGHUP.
void catch_stop_signals(bool on);

/// Becomes true at the first stop signal: the run's cancel flag (RunHooks::cancel).
const std::atomic<bool>& stop_requested();

/// The first stop signal received, 0 if none.
int stop_signal();

/// The exit status of a run stopped by `sig`: 128 + the signal's number (130 SIGINT, 143 SIGTERM,
/// 129 SIGHUP), as shells report it.
int stopped_exit_code(int sig);

/// "interrupted" (SIGINT), "terminated (SIGTERM)", "hung up (SIGHUP)".
const char* stopped_text(int sig);

}  // namespace sm::cli
