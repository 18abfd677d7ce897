// Plots through gnuplot (Debian package gnuplot-nox), with the data and the script kept beside
// the picture: `name.gp` reads `name*.dat` from its own folder, so `cd DIR && gnuplot name.gp`
// remakes `name.png` after a user edits the style.
//
// gnuplot is found on PATH (or at $LODOPT_GNUPLOT; `LODOPT_GNUPLOT=none` disables plotting, for
// tests and for machines where it misbehaves). The terminal is pngcairo when this gnuplot has
// it (anti-aliased, UTF-8 text), else png (libgd). A missing gnuplot or a failed plot is never
// fatal: plot() returns a note saying why, the data and script are still written, and the
// report shows the note where the picture would be.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace lodopt::cli {

struct PlotSpec {
    std::string name;   // file stem in the plot folder, [A-Za-z0-9_-]: name.gp, name.png
    std::string title;  // shown above the plot (plain text)
    // gnuplot commands after the terminal and output lines; data files are named relative to
    // the plot folder (the script runs there).
    std::string script;
    std::vector<std::pair<std::string, std::string>> data;  // file name in the folder, contents
    int width = 760;                                        // pixels
    int height = 430;                                       // pixels
};

struct PlotOutput {
    bool made = false;
    std::string image;   // path of the PNG when made
    std::string script;  // path of the .gp file (written even when gnuplot is missing)
    std::string note;    // why there is no picture, when !made
};

class Plotter {
public:
    // `directory` receives the plots' files (created when needed).
    explicit Plotter(std::string directory);

    bool available() const { return !mGnuplot.empty(); }
    // "gnuplot 5.4 patchlevel 4, pngcairo terminal", or why there is none.
    const std::string& description() const { return mDescription; }
    const std::string& directory() const { return mDirectory; }

    // Writes the data files and the script, then runs gnuplot in the folder. Images are
    // written atomically (gnuplot draws into a temporary name that is renamed on success).
    PlotOutput plot(const PlotSpec& spec) const;

private:
    std::string mDirectory;
    std::string mGnuplot;   // executable path; empty when unavailable
    std::string mTerminal;  // "pngcairo" or "png"
    std::string mDescription;
};

// The n-th series colour as "#rrggbb" (colour-blind-safe palette, cycling).
std::string seriesColor(int index);
// `text` as a gnuplot single-quoted string literal (for titles and labels in scripts).
std::string gnuplotString(const std::string& text);
// `text` as one double-quoted field of a gnuplot data file (names from scenes and files may
// hold anything: quotes become ', control characters spaces).
std::string gnuplotDataField(const std::string& text);

}  // namespace lodopt::cli
