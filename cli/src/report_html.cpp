#include "report_html.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>

namespace lodopt::cli {

std::string escapeHtml(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string base64Encode(const std::vector<std::uint8_t>& bytes) {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const std::uint32_t v = (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (i < bytes.size()) {
        std::uint32_t v = std::uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= std::uint32_t(bytes[i + 1]) << 8;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

namespace {

std::vector<std::uint8_t> readBytes(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error(path + ": cannot be read");
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (bytes.empty()) throw std::runtime_error(path + ": empty file");
    return bytes;
}

// Width in pixels from a PNG header (signature, then the IHDR chunk), 0 when not a PNG.
int pngWidth(const std::vector<std::uint8_t>& bytes) {
    static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 24 || !std::equal(kSignature, kSignature + 8, bytes.begin())) return 0;
    return int((std::uint32_t(bytes[16]) << 24) | (std::uint32_t(bytes[17]) << 16) | (std::uint32_t(bytes[18]) << 8) |
               bytes[19]);
}

std::string dataUriOf(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::string type = "image/png";
    const std::size_t dot = path.rfind('.');
    const std::string extension = dot == std::string::npos ? "" : path.substr(dot + 1);
    if (extension == "svg")
        type = "image/svg+xml";
    else if (extension == "jpg" || extension == "jpeg")
        type = "image/jpeg";
    return "data:" + type + ";base64," + base64Encode(bytes);
}

}  // namespace

std::string dataUri(const std::string& path) {
    return dataUriOf(path, readBytes(path));
}

std::string formatNumber(double value, int digits) {
    if (std::isnan(value)) return "–";
    char text[64];
    std::snprintf(text, sizeof(text), "%.*g", digits, value);
    return text;
}

namespace {

// The page's look: readable tables, pictures that wrap, nothing fetched from elsewhere.
constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; margin: 0 auto; max-width: 1180px;
       padding: 16px 24px 48px; color: #1d2330; background: #fbfbfd; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.3em; margin-top: 1.8em; border-bottom: 2px solid #d6dbe6; padding-bottom: 4px; }
h3 { font-size: 1.08em; margin-top: 1.4em; }
h4 { font-size: 1em; margin-top: 1.1em; color: #39425a; }
nav { background: #eef1f7; border-radius: 6px; padding: 8px 14px; font-size: 0.92em; }
nav a { margin-right: 14px; white-space: nowrap; color: #1b4f9c; }
table { border-collapse: collapse; margin: 8px 0 14px; font-size: 0.9em; }
th, td { border: 1px solid #d3d8e3; padding: 3px 8px; text-align: right; }
th { background: #e9edf5; }
td:first-child, th:first-child { text-align: left; }
tr:nth-child(even) td { background: #f4f6fa; }
.row { display: flex; flex-wrap: wrap; gap: 14px; align-items: flex-start; margin: 8px 0 12px; }
figure { margin: 0; background: #fff; border: 1px solid #dde2ec; border-radius: 4px; padding: 6px;
         max-width: 100%; box-sizing: border-box; }
figure img { display: block; max-width: 100%; height: auto; }
figure img.pixels { image-rendering: pixelated; }
figcaption { font-size: 0.85em; color: #4a5368; margin-top: 4px; }
.note { background: #fff6db; border-left: 4px solid #e0b100; padding: 6px 10px; margin: 8px 0;
        font-size: 0.92em; }
.missing { width: 260px; min-height: 80px; display: flex; align-items: center; justify-content: center;
           background: #f3f3f3; color: #6a6a6a; font-size: 0.85em; padding: 8px; text-align: center; }
.legend { display: flex; align-items: center; gap: 6px; font-size: 0.8em; margin-top: 4px; }
.legend .bar { flex: 1; height: 12px; border: 1px solid #999; }
details { margin: 6px 0 12px; }
pre { background: #f1f3f8; padding: 8px; overflow-x: auto; font-size: 0.82em; }
.meta { color: #4a5368; font-size: 0.9em; }
)";

std::string anchorOf(const std::string& text, std::set<std::string>& used) {
    std::string anchor;
    for (char c : text) {
        if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'))
            anchor += c;
        else if (c >= 'A' && c <= 'Z')
            anchor += char(c - 'A' + 'a');
        else if (!anchor.empty() && anchor.back() != '-')
            anchor += '-';
    }
    while (!anchor.empty() && anchor.back() == '-') anchor.pop_back();
    if (anchor.empty()) anchor = "section";
    std::string unique = anchor;
    for (int k = 2; used.count(unique); ++k) unique = anchor + "-" + std::to_string(k);
    used.insert(unique);
    return unique;
}

}  // namespace

ReportImage makeImage(std::string path, std::string caption, std::string note, int displayWidth) {
    ReportImage image;
    image.path = std::move(path);
    image.caption = std::move(caption);
    image.note = std::move(note);
    image.displayWidth = displayWidth;
    return image;
}

HtmlReport::HtmlReport(std::string title) : mTitle(std::move(title)) {}

void HtmlReport::heading(int level, const std::string& text) {
    const std::string anchor = anchorOf(text, mAnchors);
    const int clamped = level < 2 ? 2 : (level > 4 ? 4 : level);
    if (clamped == 2) mContents.emplace_back(anchor, text);
    mBody += "<h" + std::to_string(clamped) + " id=\"" + anchor + "\">" + escapeHtml(text) + "</h" +
             std::to_string(clamped) + ">\n";
}

void HtmlReport::paragraph(const std::string& text) {
    mBody += "<p>" + escapeHtml(text) + "</p>\n";
}

void HtmlReport::note(const std::string& text) {
    mBody += "<div class=\"note\">" + escapeHtml(text) + "</div>\n";
}

void HtmlReport::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
    std::string html = "<table><thead><tr>";
    for (const std::string& cell : header) html += "<th>" + escapeHtml(cell) + "</th>";
    html += "</tr></thead><tbody>\n";
    for (const std::vector<std::string>& row : rows) {
        html += "<tr>";
        for (std::size_t c = 0; c < std::max(header.size(), row.size()); ++c) {
            html += "<td>" + (c < row.size() ? escapeHtml(row[c]) : std::string()) + "</td>";
        }
        html += "</tr>\n";
    }
    mBody += html + "</tbody></table>\n";
}

void HtmlReport::images(const std::vector<ReportImage>& pictures) {
    std::string html = "<div class=\"row\">\n";
    for (const ReportImage& picture : pictures) {
        std::string uri;
        std::string why = picture.note;
        int width = 0, natural = 0;
        if (!picture.path.empty()) {
            try {
                const std::vector<std::uint8_t> bytes = readBytes(picture.path);
                uri = dataUriOf(picture.path, bytes);
                natural = pngWidth(bytes);
                width = picture.displayWidth > 0 ? picture.displayWidth : natural;
            } catch (const std::exception& error) {
                why = error.what();
            }
        }
        // The figure is as wide as its picture, so a long caption wraps under it.
        html += width > 0 ? "<figure style=\"width:" + std::to_string(width + 14) + "px\">" : std::string("<figure>");
        if (!uri.empty()) {
            ++mEmbeddedImages;
            html += "<img src=\"" + uri + "\" alt=\"" + escapeHtml(picture.caption) + "\"";
            if (picture.displayWidth > natural) html += " class=\"pixels\"";
            if (width > 0) html += " width=\"" + std::to_string(width) + "\"";
            html += ">";
        } else {
            html += "<div class=\"missing\">" + escapeHtml(why.empty() ? "no picture" : why) + "</div>";
        }
        if (!picture.caption.empty()) html += "<figcaption>" + escapeHtml(picture.caption) + "</figcaption>";
        if (!picture.legendGradient.empty()) {
            html += "<div class=\"legend\"><span>" + escapeHtml(picture.legendLow) +
                    "</span><span class=\"bar\" style=\"background: linear-gradient(to right, " +
                    escapeHtml(picture.legendGradient) + ")\"></span><span>" + escapeHtml(picture.legendHigh) +
                    "</span></div>";
        }
        html += "</figure>\n";
    }
    mBody += html + "</div>\n";
}

void HtmlReport::details(const std::string& summary, const std::string& text) {
    mBody += "<details><summary>" + escapeHtml(summary) + "</summary><pre>" + escapeHtml(text) + "</pre></details>\n";
}

void HtmlReport::raw(const std::string& html) {
    mBody += html;
}

std::string HtmlReport::finish() const {
    std::string page =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
        escapeHtml(mTitle) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" + escapeHtml(mTitle) +
        "</h1>\n";
    if (mContents.size() > 1) {
        page += "<nav>";
        for (const auto& [anchor, text] : mContents)
            page += "<a href=\"#" + anchor + "\">" + escapeHtml(text) + "</a> ";
        page += "</nav>\n";
    }
    return page + mBody + "</body>\n</html>\n";
}

}  // namespace lodopt::cli
