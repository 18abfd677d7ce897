// lodopt report: pages from tiny optimize and compare runs, a calibrate profile and hand-made
// schedule files hold the expected sections, embedded images and plots (when gnuplot is
// installed); without gnuplot the page is still written; bad input exits with 2. Also the
// page's building blocks (base64, escaping, CSV reading, difference maps) in-process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_common.hpp"
#include "report_data.hpp"
#include "report_html.hpp"
#include "report_images.hpp"
#include "run_lodopt.hpp"

namespace {

namespace fs = std::filesystem;

using lodopt::cli_test::CommandResult;

// `environment` is prepended to the command line ("LODOPT_GNUPLOT=none").
CommandResult runWith(const std::string& environment, const std::string& arguments) {
    return lodopt::cli_test::runLodopt(arguments, environment);
}
CommandResult run(const std::string& arguments) {
    return lodopt::cli_test::runLodopt(arguments);
}

std::string readText(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

std::size_t countOf(const std::string& text, const std::string& needle) {
    std::size_t count = 0;
    for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size()))
        ++count;
    return count;
}

bool isPng(const fs::path& path) {
    const std::string bytes = readText(path);
    return bytes.size() > 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

// The PNG signature as it starts every embedded data URI.
const std::string kEmbeddedPng = "data:image/png;base64,iVBORw0KGgo";

// One tiny calibration, optimize and compare shared by the tests (a few seconds in all).
class ReportCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sDir = fs::temp_directory_path() / ("lodopt-cli-report-" + std::to_string(::getpid()));
        fs::remove_all(sDir);
        fs::create_directories(sDir);
        sProfile = (sDir / "device.json").string();
        sSetupOk =
            run("calibrate --scene harbor --samples 16 --jitter 1 --rounds 1 --repeats 1 --warmup 1 --size 96x96 "
                "--seed 3 --quiet --out " +
                sProfile)
                .exitCode == 0;
        // A generous budget: always feasible whatever this machine's timings were.
        const std::string common = " --size 96x96 --budget-ms 50 --profile " + sProfile + " --quiet ";
        sSetupOk = sSetupOk &&
                   run("optimize --max-evals 30" + common + "--out " + (sDir / "opt").string()).exitCode == 0 &&
                   run("compare --algos gapso,pso --seeds 2 --evals 30" + common + "--out " + (sDir / "cmp").string())
                           .exitCode == 0;
        // As the report decides: LODOPT_GNUPLOT=none turns plotting off, else gnuplot on PATH.
        const char* configured = std::getenv("LODOPT_GNUPLOT");
        sGnuplot = configured ? std::string(configured) != "none" && ::access(configured, X_OK) == 0
                              : std::system("command -v gnuplot >/dev/null 2>&1") == 0;
    }
    static void TearDownTestSuite() { fs::remove_all(sDir); }

    void SetUp() override { ASSERT_TRUE(sSetupOk) << "calibrate, optimize or compare failed in " << sDir; }

    static fs::path sDir;
    static std::string sProfile;
    static bool sSetupOk;
    static bool sGnuplot;
};

fs::path ReportCli::sDir;
std::string ReportCli::sProfile;
bool ReportCli::sSetupOk = false;
bool ReportCli::sGnuplot = false;

}  // namespace

TEST_F(ReportCli, OptimizePageHasImagesMapsLevelsAndCurve) {
    const CommandResult result = run("report " + (sDir / "opt").string() + " --json");
    ASSERT_EQ(result.exitCode, 0);
    const nlohmann::json summary = nlohmann::json::parse(result.output);
    ASSERT_EQ(summary["sections"].size(), 1u);
    EXPECT_EQ(summary["sections"][0]["kind"], "optimize");
    EXPECT_EQ(summary["plots_available"].get<bool>(), sGnuplot);
    const fs::path page = sDir / "opt" / "report.html";
    ASSERT_TRUE(fs::exists(page));
    const std::string html = readText(page);
    EXPECT_NE(html.find("optimize: harbor / overview"), std::string::npos);
    EXPECT_NE(html.find("Chosen levels per object"), std::string::npos);
    EXPECT_NE(html.find("Fitness curve"), std::string::npos);
    EXPECT_NE(html.find("SSIM map"), std::string::npos);
    EXPECT_NE(html.find("Difference heat map"), std::string::npos);
    EXPECT_NE(html.find("Baseline (pixelerror"), std::string::npos);  // the engines' rule by default
    EXPECT_NE(html.find("map, optimized vs reference: butteraugli 3-norm"), std::string::npos);
    EXPECT_NE(html.find("map, baseline pixelerror vs reference"), std::string::npos);
    EXPECT_NE(html.find("window groups"), std::string::npos);  // the fast path's cache
    // Reference, optimized, baseline, SSIM map, difference, the judge's two maps; + the levels
    // and curve plots.
    const std::size_t images = countOf(html, kEmbeddedPng);
    EXPECT_EQ(images, sGnuplot ? 9u : 7u);
    EXPECT_EQ(summary["images_embedded"].get<std::size_t>(), images);
    EXPECT_EQ(html.find("src=\"report_files"), std::string::npos) << "images must be embedded, not linked";

    const fs::path files = sDir / "opt" / "report_files";
    for (const char* name : {"levels.dat", "levels.gp", "curve.dat", "curve.gp"}) {
        EXPECT_TRUE(fs::exists(files / name)) << name;
    }
    EXPECT_TRUE(isPng(files / "ssim_map.png"));
    EXPECT_TRUE(isPng(files / "difference.png"));
    EXPECT_TRUE(isPng(files / "baseline.png"));
    EXPECT_TRUE(isPng(files / "judge_map.png"));
    EXPECT_TRUE(isPng(files / "judge_map_baseline.png"));
    if (std::getenv("LODOPT_GNUPLOT") && !sGnuplot) GTEST_SKIP() << "LODOPT_GNUPLOT turns plotting off";
    ASSERT_TRUE(sGnuplot) << "gnuplot (gnuplot-nox: the quick start installs it) is not on the PATH";
    EXPECT_TRUE(isPng(files / "levels.png"));
    EXPECT_TRUE(isPng(files / "curve.png"));
    // The kept script remakes the picture from the data beside it.
    fs::remove(files / "curve.png");
    EXPECT_EQ(std::system(("cd '" + files.string() + "' && gnuplot curve.gp 2>/dev/null").c_str()), 0);
    EXPECT_TRUE(isPng(files / "curve.png"));
}

TEST_F(ReportCli, ComparePageHasBandsPerAlgorithm) {
    const fs::path out = sDir / "compare_page.html";
    const CommandResult result = run("report " + (sDir / "cmp").string() + " --out " + out.string() + " --json");
    ASSERT_EQ(result.exitCode, 0);
    const std::string html = readText(out);
    EXPECT_NE(html.find("compare: harbor / overview"), std::string::npos);
    EXPECT_NE(html.find("median fitness"), std::string::npos);
    const std::string curves = readText(sDir / "compare_page_files" / "compare_curves.dat");
    EXPECT_NE(curves.find("# gapso (2 seeds)"), std::string::npos);
    EXPECT_NE(curves.find("# pso (2 seeds)"), std::string::npos);
    const std::string script = readText(sDir / "compare_page_files" / "compare_curves.gp");
    EXPECT_NE(script.find("filledcurves"), std::string::npos);
    EXPECT_EQ(countOf(html, kEmbeddedPng), sGnuplot ? 2u : 0u);
}

TEST_F(ReportCli, ProfilePageListsEveryModel) {
    const CommandResult result = run("report " + sProfile + " --json");
    ASSERT_EQ(result.exitCode, 0);
    const std::string html = readText(sDir / "device_report.html");
    EXPECT_NE(html.find("calibrate: harbor"), std::string::npos);
    for (const char* model : {">linear<", ">dong<", ">wimmer<"})
        EXPECT_NE(html.find(model), std::string::npos) << model;
    EXPECT_TRUE(fs::exists(sDir / "device_report_files" / "device_profile_errors.gp"));
    EXPECT_EQ(countOf(html, kEmbeddedPng), sGnuplot ? 2u : 0u);
}

TEST_F(ReportCli, SchedulePageFromHandMadeFrames) {
    // Three frames, two objects, levels 0..2: level 0 is used 3 times, 1 twice, 2 once.
    const fs::path dir = sDir / "sched";
    fs::create_directories(dir);
    std::ofstream(dir / "frames.csv") << "frame,decision_us,predicted_ms,measured_ms,finest_predicted_ms,switches,"
                                         "level_0,level_1,level_2\n"
                                         "0,12.5,4.0,4.4,9.0,0,2,0,0\n"
                                         "1,11.0,3.8,,9.1,1,1,1,0\n"
                                         "2,10.5,3.9,4.1,9.2,1,0,1,1\n";
    std::ofstream(dir / "summary.json") << R"({"scene": "forest", "path": "walk", "budget_ms": 4.0,
        "measured_vs_budget": {"binding": {"frames": 2, "within_10_percent": 0.5}},
        "measurement_ceiling": {"ceiling": 0.85}})";
    const CommandResult result = run("report " + dir.string() + " --json");
    ASSERT_EQ(result.exitCode, 0);
    const std::string html = readText(dir / "report.html");
    EXPECT_NE(html.find("schedule: forest / walk"), std::string::npos);
    // Goal 1 beside the measurement ceiling.
    EXPECT_NE(html.find("within ±10% of the budget on 50% of the 2 frames where the budget binds; measurement "
                        "ceiling 85%"),
              std::string::npos);
    // The levels table: object-frames per level and their share of 6.
    EXPECT_NE(html.find("<td>level 0</td><td>3</td><td>50%</td>"), std::string::npos);
    EXPECT_NE(html.find("<td>level 2</td><td>1</td><td>16.7%</td>"), std::string::npos);
    const std::string stacked = readText(dir / "report_files" / "schedule_levels.dat");
    EXPECT_NE(stacked.find("\n2 0 1 2\n"), std::string::npos) << stacked;  // running sums of frame 2
    const std::string times = readText(dir / "report_files" / "schedule_times.gp");
    EXPECT_NE(times.find("title 'budget'"), std::string::npos);
    EXPECT_NE(times.find("measured (scheduled)"), std::string::npos);
    EXPECT_EQ(countOf(html, kEmbeddedPng), sGnuplot ? 3u : 0u);
}

TEST_F(ReportCli, WithoutGnuplotThePageIsStillWritten) {
    const fs::path out = sDir / "no_gnuplot.html";
    const CommandResult result =
        runWith("LODOPT_GNUPLOT=none", "report " + (sDir / "opt").string() + " --out " + out.string() + " --json");
    ASSERT_EQ(result.exitCode, 0);
    const nlohmann::json summary = nlohmann::json::parse(result.output);
    EXPECT_FALSE(summary["plots_available"].get<bool>());
    const std::string html = readText(out);
    EXPECT_NE(html.find("No plot: plotting disabled"), std::string::npos);
    EXPECT_EQ(countOf(html, kEmbeddedPng), 7u);  // the renders and maps need no gnuplot
    EXPECT_TRUE(fs::exists(sDir / "no_gnuplot_files" / "curve.gp"));
    EXPECT_FALSE(fs::exists(sDir / "no_gnuplot_files" / "curve.png"));
    // A gnuplot path that does not exist is not fatal either.
    EXPECT_EQ(runWith("LODOPT_GNUPLOT=/nonexistent/gnuplot", "report " + (sDir / "cmp").string() + " --quiet").exitCode,
              0);
}

TEST_F(ReportCli, BadInputExitsWithTwo) {
    EXPECT_EQ(run("report " + (sDir / "missing").string()).exitCode, 2);
    const fs::path empty = sDir / "empty";
    fs::create_directories(empty);
    EXPECT_EQ(run("report " + empty.string()).exitCode, 2);
    const fs::path corrupt = sDir / "corrupt";
    fs::create_directories(corrupt);
    std::ofstream(corrupt / "result.json") << "{\"scene\": ";
    EXPECT_EQ(run("report " + corrupt.string()).exitCode, 2);
    const fs::path ragged = sDir / "ragged";
    fs::create_directories(ragged);
    std::ofstream(ragged / "curves.csv") << "algorithm,seed,iteration,evaluations,best_fitness,mean_fitness\n"
                                            "gapso,1,0,12,0.9\n";
    EXPECT_EQ(run("report " + ragged.string()).exitCode, 2);
    EXPECT_EQ(run("report " + (sDir / "opt").string() + " --baseline nosuch").exitCode, 2);
}

TEST(ReportHtml, Base64MatchesRfc4648) {
    using lodopt::cli::base64Encode;
    auto encode = [](const std::string& text) {
        return base64Encode(std::vector<std::uint8_t>(text.begin(), text.end()));
    };
    EXPECT_EQ(encode(""), "");
    EXPECT_EQ(encode("f"), "Zg==");
    EXPECT_EQ(encode("fo"), "Zm8=");
    EXPECT_EQ(encode("foo"), "Zm9v");
    EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64Encode({0xff, 0xfe, 0xfd}), "//79");
}

TEST(ReportHtml, TextIsEscapedAndHeadingsAreListed) {
    lodopt::cli::HtmlReport page("a <b> & 'c'");
    page.heading(2, "first");
    page.heading(2, "first");  // same text: a unique anchor
    page.paragraph("x < y");
    page.table({"h"}, {{"<script>"}});
    const std::string html = page.finish();
    EXPECT_NE(html.find("<title>a &lt;b&gt; &amp; &#39;c&#39;</title>"), std::string::npos);
    EXPECT_NE(html.find("id=\"first\""), std::string::npos);
    EXPECT_NE(html.find("id=\"first-2\""), std::string::npos);
    EXPECT_NE(html.find("href=\"#first-2\""), std::string::npos);
    EXPECT_NE(html.find("<p>x &lt; y</p>"), std::string::npos);
    EXPECT_EQ(html.find("<script>"), std::string::npos);
}

TEST(ReportData, CsvReaderNamesFileLineAndColumn) {
    const fs::path path = fs::temp_directory_path() / ("lodopt-report-csv-" + std::to_string(::getpid()) + ".csv");
    std::ofstream(path) << "name,value\n\"a,b\",1.5\nc,\nd,oops\n";
    const lodopt::cli::CsvTable table = lodopt::cli::readCsv(path.string());
    ASSERT_EQ(table.rows.size(), 3u);
    EXPECT_EQ(table.text(0, "name"), "a,b");
    EXPECT_DOUBLE_EQ(table.number(0, "value"), 1.5);
    EXPECT_TRUE(std::isnan(table.number(1, "value")));
    try {
        table.number(2, "value");
        ADD_FAILURE() << "no error for a non-number";
    } catch (const lodopt::cli::UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("row 3, column 'value': 'oops'"), std::string::npos) << error.what();
    }
    std::ofstream(path) << "a,b\n1,2,3\n";
    EXPECT_THROW(lodopt::cli::readCsv(path.string()), lodopt::cli::UsageError);
    fs::remove(path);
}

TEST(ReportImages, DifferenceMapsOfIdenticalAndOnePixelChange) {
    lodopt::renderer::Frame reference;
    reference.width = 32;
    reference.height = 24;
    reference.rgba.resize(32 * 24 * 4);
    for (std::size_t i = 0; i < reference.rgba.size(); ++i) reference.rgba[i] = std::uint8_t((i * 37) % 251);
    const lodopt::cli::DifferenceMaps same = lodopt::cli::differenceMaps(reference, reference, "same");
    EXPECT_DOUBLE_EQ(same.meanSsim, 1.0);
    EXPECT_EQ(same.largestDifference, 0);
    EXPECT_EQ(same.changedShare, 0.0);
    lodopt::renderer::Frame changed = reference;
    changed.rgba[(5 * 32 + 7) * 4 + 1] = std::uint8_t(changed.rgba[(5 * 32 + 7) * 4 + 1] ^ 0x40);
    const lodopt::cli::DifferenceMaps one = lodopt::cli::differenceMaps(changed, reference, "one");
    EXPECT_EQ(one.largestDifference, 0x40);
    EXPECT_DOUBLE_EQ(one.changedShare, 1.0 / (32 * 24));
    EXPECT_LT(one.meanSsim, 1.0);
    EXPECT_EQ(one.ssimMap.width, 32);
    EXPECT_EQ(one.difference.rgba.size(), changed.rgba.size());
    lodopt::renderer::Frame small = reference;
    small.width = 16;
    EXPECT_THROW(lodopt::cli::differenceMaps(small, reference, "small"), lodopt::cli::UsageError);
}
