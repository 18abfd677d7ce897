#include "checkpoint.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

namespace lodopt::cli {

CheckpointFile::CheckpointFile(std::string path, std::string command, std::string units)
    : mPath(std::move(path)),
      mCommand(std::move(command)),
      mUnits(std::move(units)),
      mFormat("lodopt-" + mCommand + "-checkpoint/1") {}

bool CheckpointFile::restore(bool resume, bool quiet, const nlohmann::json& identity,
                                       const std::function<void(const nlohmann::json& saved)>& read) const {
    if (!std::filesystem::exists(mPath)) {
        if (resume && !quiet) {
            std::cerr << "lodopt: " << mCommand << ": no checkpoint in "
                      << std::filesystem::path(mPath).parent_path().string() << ", starting from the first "
                      << mUnits.substr(0, mUnits.size() - 1) << "\n";
        }
        return false;
    }
    if (!resume) {
        throw UsageError(mPath + " holds the " + mUnits + " of an interrupted " + mCommand +
                         ": add --resume to continue it, or delete the file to start over");
    }
    try {
        std::ifstream in(mPath);
        const nlohmann::json saved = nlohmann::json::parse(in);
        if (saved.at("format") != mFormat) throw std::invalid_argument("unknown format");
        checkIdentity(mPath, saved.at("options"), identity);
        read(saved);
    } catch (const UsageError&) {
        throw;
    } catch (const std::exception& error) {
        throw UsageError(mPath + ": not a readable " + mCommand + " checkpoint (" + error.what() +
                         "); delete it to start over");
    }
    return true;
}

void CheckpointFile::save(const nlohmann::json& identity, const nlohmann::json& units) const {
    nlohmann::json document = {{"format", mFormat}, {"options", identity}};
    for (auto it = units.begin(); it != units.end(); ++it) document[it.key()] = it.value();
    writeJsonFile(mPath, document);
}

void CheckpointFile::remove() const { std::filesystem::remove(mPath); }

}  // namespace lodopt::cli
