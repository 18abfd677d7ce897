// The checkpoint file of a long command (compare, bench, schedule; tune keeps one file per view):
// docs/robustness.md "Interrupts and --resume". One JSON document
//   {"format": "lodopt-<command>-checkpoint/1", "options": identity, ...the command's units}
// written atomically after every unit, read back by --resume only when it was written with the
// same result-changing options (`identity`: option name without "--" → value), and removed once
// the command's outputs are written.
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"

namespace lodopt::cli {

class CheckpointFile {
public:
    // `command` names the command in messages and the format ("compare"); `units` what a unit
    // is, plural ("runs").
    CheckpointFile(std::string path, std::string command, std::string units);

    const std::string& path() const { return mPath; }

    // When the file exists and `resume` is set, passes the saved document to `read` for the
    // command's units and returns true; false when there is no file. Throws UsageError when the file exists
    // without `resume`, was written with other options (checkIdentity), or is unreadable (any
    // exception from `read` other than UsageError). Without a file, with `resume` and not
    // `quiet`, says on stderr that the run starts from the first unit.
    bool restore(bool resume, bool quiet, const nlohmann::json& identity,
                           const std::function<void(const nlohmann::json& saved)>& read) const;

    // Writes {"format", "options": identity} and `units`' members atomically.
    void save(const nlohmann::json& identity, const nlohmann::json& units) const;

    void remove() const;

private:
    std::string mPath, mCommand, mUnits, mFormat;
};

}  // namespace lodopt::cli
