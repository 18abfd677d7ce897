#include "metrics/reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace lodopt::metrics::reference {

namespace {

cv::Mat grayOf(const ImageView& image) {
    if (image.channels != 1 && image.channels != 3 && image.channels != 4) {
        throw std::invalid_argument("metrics::reference: " + std::to_string(image.channels) + " channels, expected 1, 3 or 4");
    }
    cv::Mat gray(image.height, image.width, CV_64F);
    for (int row = 0; row < image.height; ++row) {
        const std::uint8_t* pixel = image.pixels + std::size_t(row) * image.rowStride;
        double* out = gray.ptr<double>(row);
        for (int col = 0; col < image.width; ++col, pixel += image.channels) {
            out[col] = image.channels == 1 ? double(pixel[0]) : 0.30 * pixel[0] + 0.59 * pixel[1] + 0.11 * pixel[2];
        }
    }
    return gray;
}

double entropyOf(const std::vector<double>& histogram) {
    double total = 0.0, entropy = 0.0;
    for (double count : histogram) total += count;
    for (double count : histogram) {
        if (count > 0) entropy -= count / total * std::log2(count / total);
    }
    return entropy;
}

}  // namespace

double ssim(const ImageView& candidate, const ImageView& reference) {
    if (candidate.width != reference.width || candidate.height != reference.height) {
        throw std::invalid_argument("metrics::reference::ssim: the images differ in size");
    }
    if (candidate.width < 11 || candidate.height < 11) {
        throw std::invalid_argument("metrics::reference::ssim: the images are smaller than the 11x11 window");
    }
    const cv::Mat x = grayOf(candidate), y = grayOf(reference);
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    const cv::Size window(11, 11);
    cv::Mat mx, my, xx, yy, xy;
    cv::GaussianBlur(x, mx, window, 1.5, 1.5, cv::BORDER_REFLECT);
    cv::GaussianBlur(y, my, window, 1.5, 1.5, cv::BORDER_REFLECT);
    cv::GaussianBlur(x.mul(x), xx, window, 1.5, 1.5, cv::BORDER_REFLECT);
    cv::GaussianBlur(y.mul(y), yy, window, 1.5, 1.5, cv::BORDER_REFLECT);
    cv::GaussianBlur(x.mul(y), xy, window, 1.5, 1.5, cv::BORDER_REFLECT);
    const cv::Mat mxy = mx.mul(my), mx2 = mx.mul(mx), my2 = my.mul(my);
    const cv::Mat numerator = (2 * mxy + c1).mul(2 * (xy - mxy) + c2);
    const cv::Mat denominator = (mx2 + my2 + c1).mul((xx - mx2) + (yy - my2) + c2);
    const cv::Mat map = numerator / denominator;
    return cv::mean(map(cv::Rect(5, 5, x.cols - 10, x.rows - 10)))[0];
}

double boundaryEntropy(const ImageView& image) {
    if (image.width < 3 || image.height < 3) {
        throw std::invalid_argument("metrics::reference::boundaryEntropy: the image is smaller than 3x3");
    }
    const cv::Mat gray = grayOf(image);
    cv::Mat gx, gy;
    cv::Sobel(gray, gx, CV_64F, 1, 0, 3);
    cv::Sobel(gray, gy, CV_64F, 0, 1, 3);
    std::vector<double> histogram(256, 0.0);
    const double top = 255.0 * std::sqrt(20.0);
    for (int row = 1; row + 1 < gray.rows; ++row) {
        for (int col = 1; col + 1 < gray.cols; ++col) {
            const double g = std::hypot(gx.at<double>(row, col), gy.at<double>(row, col));
            histogram[std::size_t(std::min(255, int(g * 256.0 / top)))] += 1.0;
        }
    }
    return entropyOf(histogram);
}

double informationEntropy(const ImageView& image) {
    grayOf(image);  // checks the channel count
    // The gray level rounded half up, in integers: 0.30 R + 0.59 G + 0.11 B in binary floating
    // point can land just below a tie the exact value sits on, and round down (measured: the
    // test images' entropies off by 1e-4 against the script's).
    std::vector<double> histogram(256, 0.0);
    for (int row = 0; row < image.height; ++row) {
        const std::uint8_t* pixel = image.pixels + std::size_t(row) * image.rowStride;
        for (int col = 0; col < image.width; ++col, pixel += image.channels) {
            const int level = image.channels == 1 ? int(pixel[0]) : (30 * pixel[0] + 59 * pixel[1] + 11 * pixel[2] + 50) / 100;
            histogram[std::size_t(level)] += 1.0;
        }
    }
    return entropyOf(histogram);
}

double fitness(const ImageView& candidate, const ImageView& reference) {
    auto fidelity = [](double value, double truth) {
        return std::clamp(1.0 - std::abs(value - truth) / std::max(std::abs(truth), 1e-6), 0.0, 1.0);
    };
    return (std::clamp(ssim(candidate, reference), 0.0, 1.0) +
            fidelity(boundaryEntropy(candidate), boundaryEntropy(reference)) +
            fidelity(informationEntropy(candidate), informationEntropy(reference))) /
           3.0;
}

void useOneThread() { cv::setNumThreads(1); }

}  // namespace lodopt::metrics::reference
