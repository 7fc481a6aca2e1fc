// Signals that end a command: SIGINT (Ctrl-C), SIGTERM (what Slurm, most batch schedulers and
// `kill` send) and SIGHUP (the terminal went away). No command may leave half a file behind:
// on these signals every command ends at once but first removes the temporaries of the files
// it is writing (AtomicFile, atomic_file.h), then dies of the signal as before (exit status
// 128 + N). `tessera render` asks more politely (StopRequest): the first signal lets it
// finish the frame in hand and the frames being written, a second ends it at once. A SIGHUP
// that is ignored when the process starts (nohup) stays ignored.
#pragma once
#include <string>

namespace tessera::cli {

// Installs the handlers that end the process, removing unfinished temporaries (main() does,
// for every command).
void end_cleanly_on_signals();

// While it lives, the first SIGINT, SIGTERM or SIGHUP is recorded instead of ending the
// process; a second one ends it as end_cleanly_on_signals() does.
class StopRequest {
public:
    StopRequest();
    ~StopRequest();  // back to end_cleanly_on_signals()
    StopRequest(const StopRequest&) = delete;
    StopRequest& operator=(const StopRequest&) = delete;

    // The first signal received, or 0.
    int signal() const;
};

// "SIGTERM" for SIGTERM, and so on.
std::string signal_name(int signal);

}  // namespace tessera::cli
