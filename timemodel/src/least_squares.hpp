// Small dense least-squares tools for the time-model fits (private to the module).
//
// Lawson & Hanson 1974 ("Solving Least Squares Problems", ch. 23) non-negative least squares
// on Householder QR solves, preceded by a column check: a column that is (numerically) a
// linear combination of the columns kept before it — a constant feature when the first
// column is the intercept, an exact duplicate, a zero column — is dropped with a note, and
// the kept set's condition number must stay below a bound, so a fit never blows up silently.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace lodopt::timemodel::detail {

// Row-major rows x cols.
struct Matrix {
    std::size_t rows = 0;
    std::size_t cols = 0;
    std::vector<double> values;

    Matrix() = default;
    Matrix(std::size_t r, std::size_t c) : rows(r), cols(c), values(r * c, 0.0) {}
    double& at(std::size_t r, std::size_t c) { return values[r * cols + c]; }
    double at(std::size_t r, std::size_t c) const { return values[r * cols + c]; }
};

// min ||A x - b|| over the columns flagged in `use` (others stay 0), by Householder QR.
// Columns whose pivot falls below 1e-12 of the largest are left at 0.
std::vector<double> leastSquares(const Matrix& a, const std::vector<double>& b, const std::vector<bool>& use);

// min ||A x - b|| subject to x >= 0 (Lawson–Hanson active set). `iterations` receives the
// number of inner solves.
std::vector<double> nonNegativeLeastSquares(const Matrix& a, const std::vector<double>& b, int* iterations = nullptr);

struct ColumnCheck {
    std::vector<bool> kept;          // per column
    std::vector<std::string> notes;  // one per dropped column, naming it and why
    double conditionNumber = 0.0;    // 2-norm condition of the kept, unit-norm columns
};

// Walks the columns in `order` (indices into A's columns): each is dropped when its distance
// to the span of the kept ones, relative to its norm, is below `dependencyTolerance`; then
// while the kept set's condition number exceeds `maxConditionNumber` the kept column (other
// than order[0]) nearest to the span of the others is dropped. `names` label the notes;
// `interceptColumn` (or -1) names a column of ones, to say "constant" rather than "collinear".
ColumnCheck checkColumns(const Matrix& a, const std::vector<std::size_t>& order, const std::vector<std::string>& names,
                         int interceptColumn, double dependencyTolerance, double maxConditionNumber);

struct CheckedFit {
    std::vector<double> coefficients;  // per column of A; 0 for dropped columns
    std::vector<bool> kept;
    std::vector<std::string> notes;
    double conditionNumber = 0.0;
    int iterations = 0;
};

// The checked non-negative fit: min sum_r (w_r (A x - b)_r)^2, x >= 0, over the columns that
// pass checkColumns. Columns are scaled to unit weighted norm inside, so the tolerances do
// not depend on the features' units.
CheckedFit fitNonNegative(const Matrix& a, const std::vector<double>& b, const std::vector<double>& weights,
                          const std::vector<std::size_t>& order, const std::vector<std::string>& names,
                          int interceptColumn);

inline constexpr double kDependencyTolerance = 1e-8;
inline constexpr double kMaxConditionNumber = 1e7;

}  // namespace lodopt::timemodel::detail
