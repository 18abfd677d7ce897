// Interrupts of long commands (compare, tune, bench, schedule): SIGINT or SIGTERM asks the
// command to stop at the next unit boundary instead of killing it mid-write.
//
// The contract (docs/robustness.md):
//  1. a long command holds an InterruptGuard while it works; the guard turns the first
//     SIGINT/SIGTERM into a flag and nothing else (async-signal-safe), a second one restores
//     the default action and re-raises it, so a user who presses Ctrl-C twice stops at once;
//  2. after each unit of work (one run, one configuration, one frame batch) the command writes
//     its checkpoint (atomically, scenes::writeTextAtomically), then calls pollInterrupt();
//  3. pollInterrupt() throws Interrupted when a signal arrived; its message names what was saved
//     and the command line that resumes (the same one, with --resume);
//  4. main() prints the message and exits with kExitInterrupted (130, the shell's 128 + SIGINT,
//     for SIGTERM too so that scripts test one code).
// Every file a command writes is complete at every moment (atomic rename), so even SIGKILL
// loses at most the unit in progress.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace lodopt::cli {

// Exit code of a command stopped by SIGINT or SIGTERM at a unit boundary (README, Robustness).
inline constexpr int kExitInterrupted = 130;

// Thrown by pollInterrupt(); what() is the full user message (several lines, no "error:").
class Interrupted : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// While an InterruptGuard lives, SIGINT and SIGTERM set the interrupt flag; the previous
// handlers come back when it is destroyed. Guards do not nest (asserted). Constructing one
// clears the flag.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// The signal number that asked to stop (SIGINT or SIGTERM), 0 when none did.
int interruptSignal();
bool interruptRequested();

// Called by a long command after unit `unitsDone` (of `unitsTotal`; units restored from a
// checkpoint count) has been saved to `savedPath`. Throws Interrupted when a signal arrived:
// "<command>: interrupted by SIGINT after 3 of 20 <unitName>s; the finished ones are saved in
// <savedPath>\nresume with: <resumeCommandLine()>".
//
// Testing aid: when the environment variable LODOPT_TEST_WAIT_AFTER_UNITS equals `unitsDone`,
// the call first waits (up to 60 s) for a signal, so that a test can kill the process at a
// known point and the outcome does not depend on timing.
void pollInterrupt(const std::string& command, std::size_t unitsDone, std::size_t unitsTotal,
                   const std::string& unitName, const std::string& savedPath);

// This process's command line (/proc/self/cmdline), shell-quoted, with " --resume" appended
// unless it already has it: what a user types to continue an interrupted command.
std::string resumeCommandLine();

// Quotes `word` for a POSIX shell when it has anything but [A-Za-z0-9_./=:,+@%-].
std::string shellQuote(const std::string& word);

}  // namespace lodopt::cli
