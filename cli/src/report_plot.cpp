#include "report_plot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "interrupt.hpp"
#include "scenes/atomic_file.hpp"

namespace lodopt::cli {
namespace {

namespace fs = std::filesystem;

std::string findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "/usr/local/bin:/usr/bin:/bin");
    std::string folder;
    while (std::getline(folders, folder, ':')) {
        if (folder.empty()) continue;
        const fs::path candidate = fs::path(folder) / program;
        if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return {};
}

// Runs `command` through /bin/sh with stdout and stderr captured; returns the exit status
// (-1 when it did not exit normally).
int runCaptured(const std::string& command, std::string& output) {
    output.clear();
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return -1;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
    const int status = ::pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string firstLine(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    return line;
}

}  // namespace

std::string seriesColor(int index) {
    // Okabe & Ito's colour-blind-safe palette (black last), then darker variants.
    static const char* kColors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00",
                                    "#56B4E9", "#8C6D1F", "#5B3A8E", "#2F4F4F", "#000000"};
    constexpr int kCount = int(sizeof(kColors) / sizeof(kColors[0]));
    return kColors[((index % kCount) + kCount) % kCount];
}

std::string gnuplotString(const std::string& text) {
    std::string out = "'";
    for (char c : text) {
        if (c == '\'')
            out += "''";
        else if (c != '\n')
            out += c;
    }
    return out + "'";
}

std::string gnuplotDataField(const std::string& text) {
    std::string out = "\"";
    for (char c : text) out += c == '"' ? '\'' : (static_cast<unsigned char>(c) < 32 ? ' ' : c);
    return out + "\"";
}

Plotter::Plotter(std::string directory) : mDirectory(std::move(directory)) {
    const char* configured = std::getenv("LODOPT_GNUPLOT");
    if (configured && std::string(configured) == "none") {
        mDescription = "plotting disabled (LODOPT_GNUPLOT=none)";
        return;
    }
    std::string executable = configured && *configured ? std::string(configured) : findOnPath("gnuplot");
    if (executable.empty() || ::access(executable.c_str(), X_OK) != 0) {
        mDescription = "gnuplot not found" +
                       (configured && *configured ? " at " + std::string(configured) + " (LODOPT_GNUPLOT)"
                                                  : std::string(" on PATH")) +
                       "; install the Debian package gnuplot-nox and run the report again";
        return;
    }
    std::string output;
    if (runCaptured(shellQuote(executable) + " --version", output) != 0) {
        mDescription = executable + " --version failed: " + firstLine(output);
        return;
    }
    const std::string version = firstLine(output);
    mTerminal = runCaptured(shellQuote(executable) + " -e 'set terminal pngcairo'", output) == 0 ? "pngcairo" : "png";
    mGnuplot = executable;
    mDescription = version + ", " + mTerminal + " terminal";
}

PlotOutput Plotter::plot(const PlotSpec& spec) const {
    PlotOutput out;
    const fs::path folder(mDirectory);
    for (const auto& [file, text] : spec.data) scenes::writeTextAtomically((folder / file).string(), text);
    const std::string imageName = spec.name + ".png";
    std::ostringstream script;
    script << "# " << spec.title << "\n"
           << "# Written by `lodopt report` / `lodopt bench`. Edit the style below and run\n"
           << "#   gnuplot " << spec.name << ".gp\n"
           << "# in this folder to remake " << imageName << " from the data beside it.\n";
    const std::string terminal = mTerminal.empty() ? "pngcairo" : mTerminal;
    script << "set terminal " << terminal << " size " << spec.width << "," << spec.height;
    if (terminal == "pngcairo")
        script << " enhanced font 'DejaVu Sans,10' linewidth 1.2";
    else
        script << " font 'DejaVuSans,9'";
    script << "\n"
           << "if (!exists(\"lodopt_output\")) lodopt_output = " << gnuplotString(imageName) << "\n"
           << "set output lodopt_output\n"
           << "set encoding utf8\n"
           // Names from data (objects, algorithms) may hold '_' or '^': no enhanced-text markup
           // in titles, keys and data tic labels (axis formats like 10^{%L} keep it).
           << "set title " << gnuplotString(spec.title) << " noenhanced\n"
           << "set grid lc rgb '#d8d8d8'\n"
           << "set key box opaque noenhanced\n"
           << "set xtics noenhanced\n"
           << spec.script;
    if (!spec.script.empty() && spec.script.back() != '\n') script << "\n";
    script << "unset output\n";
    const fs::path scriptPath = folder / (spec.name + ".gp");
    scenes::writeTextAtomically(scriptPath.string(), script.str());
    out.script = scriptPath.string();
    if (mGnuplot.empty()) {
        out.note = "No plot: " + mDescription + ". The data and the script are in " + mDirectory + ".";
        return out;
    }
    const fs::path imagePath = folder / imageName;
    std::string log;
    try {
        scenes::writeFileAtomically(imagePath.string(), [&](const std::string& temporary) {
            const std::string command = "cd " + shellQuote(folder.string()) + " && " + shellQuote(mGnuplot) + " -e " +
                                        shellQuote("lodopt_output=" + gnuplotString(fs::absolute(temporary).string())) +
                                        " " + shellQuote(spec.name + ".gp");
            const int status = runCaptured(command, log);
            if (status != 0 || !fs::exists(temporary) || fs::file_size(temporary) == 0) {
                throw std::runtime_error("gnuplot exited with status " + std::to_string(status));
            }
        });
    } catch (const std::exception& error) {
        out.note = "No plot: " + std::string(error.what()) + (log.empty() ? "" : ": " + firstLine(log)) +
                   ". Script: " + scriptPath.string();
        return out;
    }
    out.made = true;
    out.image = imagePath.string();
    return out;
}

}  // namespace lodopt::cli
