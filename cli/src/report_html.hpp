// A self-contained HTML page built section by section: headings (with a table of contents),
// paragraphs, notes, tables and images. Images are embedded as base64 data URIs, so the one
// file opens anywhere (a browser, a mail attachment, a CI artifact) without the files beside
// it; the files stay beside it anyway so a user can reuse or restyle them.
//
// Every text argument is plain text and escaped here; only raw() takes HTML.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace lodopt::cli {

// &, <, >, " and ' as entities.
std::string escapeHtml(std::string_view text);
// RFC 4648 base64 with padding.
std::string base64Encode(const std::vector<std::uint8_t>& bytes);
// "data:image/png;base64,..." of a file's bytes (type from the extension: png, svg, jpg);
// throws std::runtime_error naming the file when it cannot be read.
std::string dataUri(const std::string& path);

// One picture in a row of pictures.
struct ReportImage {
    std::string path;      // PNG/SVG file to embed; empty = show `note` instead
    std::string caption;   // plain text under the picture
    std::string note;      // shown in place of the picture when `path` is empty or unreadable
    int displayWidth = 0;  // CSS pixels (0 = natural size, capped at the page width); a picture
                           // shown larger than it is is scaled without smoothing (pixels stay crisp)
    // Optional colour scale under the caption: a CSS linear-gradient stop list and the values
    // at its two ends.
    std::string legendGradient;
    std::string legendLow, legendHigh;
};

ReportImage makeImage(std::string path, std::string caption, std::string note = {}, int displayWidth = 0);

class HtmlReport {
public:
    explicit HtmlReport(std::string title);

    // `level` 2..4; level 2 headings are listed in the table of contents (their anchors are
    // made from the text, unique within the page).
    void heading(int level, const std::string& text);
    void paragraph(const std::string& text);
    // A highlighted remark (a missing plot tool, a file that was not there).
    void note(const std::string& text);
    // A table; cells are plain text. Rows shorter than `header` are padded.
    void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
    // Pictures side by side (wrapping on narrow screens).
    void images(const std::vector<ReportImage>& pictures);
    // Collapsed preformatted text (a JSON document, a log).
    void details(const std::string& summary, const std::string& text);
    // Trusted HTML, inserted as is.
    void raw(const std::string& html);

    // The whole page.
    std::string finish() const;

    // Number of images embedded so far (pictures that were readable).
    int embeddedImages() const { return mEmbeddedImages; }

private:
    std::string mTitle;
    std::string mBody;
    std::vector<std::pair<std::string, std::string>> mContents;  // anchor, text
    std::set<std::string> mAnchors;                              // every id used so far
    int mEmbeddedImages = 0;
};

// Number formatting for tables: `digits` significant digits, "–" for NaN.
std::string formatNumber(double value, int digits = 4);

}  // namespace lodopt::cli
