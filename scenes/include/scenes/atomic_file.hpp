// The one way lodopt writes an output file: to a temporary name beside the target, then
// rename(2), so a reader (or a crash) never sees a half-written file.
#pragma once

#include <functional>
#include <string>

namespace lodopt::scenes {

// Calls write(temporaryPath); if it returns normally and the file exists, renames it onto
// `path`. On any exception the temporary file is removed and the exception propagates.
// Creates missing parent folders.
void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace lodopt::scenes
