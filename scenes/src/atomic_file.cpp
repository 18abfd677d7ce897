#include "scenes/atomic_file.hpp"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

namespace lodopt::scenes {

namespace fs = std::filesystem;

void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    static std::atomic<unsigned> counter{0};
    fs::path target(path);
    if (target.has_parent_path()) fs::create_directories(target.parent_path());
    // Keep the extension last: writers may choose the format from it (OpenEXR reads it).
    fs::path temporary = target.parent_path() /
                         (target.stem().string() + ".tmp" + std::to_string(::getpid()) + "_" +
                          std::to_string(counter++) + target.extension().string());
    try {
        write(temporary.string());
        if (!fs::exists(temporary)) throw std::runtime_error(path + ": writer produced no file");
        fs::rename(temporary, target);
    } catch (...) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw;
    }
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw std::runtime_error(path + ": cannot open for writing");
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.close();
        if (!out) throw std::runtime_error(path + ": write failed");
    });
}

}  // namespace lodopt::scenes
