// Lawson & Hanson 1974, ch. 23 (NNLS) and a Gram–Schmidt column check; see least_squares.hpp.
#include "least_squares.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

namespace lodopt::timemodel::detail {

std::vector<double> leastSquares(const Matrix& a, const std::vector<double>& b, const std::vector<bool>& use) {
    assert(b.size() == a.rows && use.size() == a.cols);
    std::vector<std::size_t> columns;
    for (std::size_t c = 0; c < a.cols; ++c) {
        if (use[c]) columns.push_back(c);
    }
    const std::size_t n = a.rows, k = columns.size();
    std::vector<double> x(a.cols, 0.0);
    if (k == 0 || n == 0) return x;
    // Column-major copy of the used columns, reduced in place to R (upper part) by Householder.
    std::vector<double> q(n * k);
    for (std::size_t j = 0; j < k; ++j) {
        for (std::size_t r = 0; r < n; ++r) q[j * n + r] = a.at(r, columns[j]);
    }
    std::vector<double> rhs = b;
    const std::size_t steps = std::min(n, k);
    std::vector<double> diagonal(k, 0.0);
    for (std::size_t j = 0; j < steps; ++j) {
        double* col = &q[j * n];
        double norm = 0.0;
        for (std::size_t r = j; r < n; ++r) norm += col[r] * col[r];
        norm = std::sqrt(norm);
        if (norm == 0.0) continue;
        const double alpha = col[j] > 0.0 ? -norm : norm;
        // v = col[j..] - alpha e_j, stored in col[j..]; H = I - 2 v v^T / (v^T v).
        col[j] -= alpha;
        double vNorm2 = 0.0;
        for (std::size_t r = j; r < n; ++r) vNorm2 += col[r] * col[r];
        if (vNorm2 > 0.0) {
            for (std::size_t other = j + 1; other < k; ++other) {
                double* target = &q[other * n];
                double dot = 0.0;
                for (std::size_t r = j; r < n; ++r) dot += col[r] * target[r];
                const double scale = 2.0 * dot / vNorm2;
                for (std::size_t r = j; r < n; ++r) target[r] -= scale * col[r];
            }
            double dot = 0.0;
            for (std::size_t r = j; r < n; ++r) dot += col[r] * rhs[r];
            const double scale = 2.0 * dot / vNorm2;
            for (std::size_t r = j; r < n; ++r) rhs[r] -= scale * col[r];
        }
        diagonal[j] = alpha;
    }
    double largest = 0.0;
    for (double d : diagonal) largest = std::max(largest, std::abs(d));
    // Back substitution on R; R's strict upper part sits in q above the diagonal.
    std::vector<double> solution(k, 0.0);
    for (std::size_t jj = steps; jj-- > 0;) {
        if (std::abs(diagonal[jj]) <= 1e-12 * largest) continue;  // rank-deficient: leave at 0
        double sum = rhs[jj];
        for (std::size_t other = jj + 1; other < steps; ++other) sum -= q[other * n + jj] * solution[other];
        solution[jj] = sum / diagonal[jj];
    }
    for (std::size_t j = 0; j < k; ++j) x[columns[j]] = solution[j];
    return x;
}

namespace {

std::vector<double> gradient(const Matrix& a, const std::vector<double>& b, const std::vector<double>& x) {
    std::vector<double> residual(b);
    for (std::size_t r = 0; r < a.rows; ++r) {
        for (std::size_t c = 0; c < a.cols; ++c) residual[r] -= a.at(r, c) * x[c];
    }
    std::vector<double> w(a.cols, 0.0);
    for (std::size_t r = 0; r < a.rows; ++r) {
        for (std::size_t c = 0; c < a.cols; ++c) w[c] += a.at(r, c) * residual[r];
    }
    return w;
}

}  // namespace

std::vector<double> nonNegativeLeastSquares(const Matrix& a, const std::vector<double>& b, int* iterations) {
    const std::size_t p = a.cols;
    std::vector<double> x(p, 0.0);
    std::vector<bool> passive(p, false), blocked(p, false);
    double scale = 0.0;
    for (double v : a.values) scale = std::max(scale, std::abs(v));
    double bNorm = 0.0;
    for (double v : b) bNorm = std::max(bNorm, std::abs(v));
    const double tolerance = 1e-12 * std::max(1.0, scale * bNorm) * double(std::max<std::size_t>(a.rows, 1));
    const int maxIterations = 30 * int(p) + 30;
    int count = 0;
    while (count < maxIterations) {
        std::vector<double> w = gradient(a, b, x);
        std::size_t best = p;
        for (std::size_t c = 0; c < p; ++c) {
            if (!passive[c] && !blocked[c] && w[c] > tolerance && (best == p || w[c] > w[best])) best = c;
        }
        if (best == p) break;
        passive[best] = true;
        bool first = true;
        while (count < maxIterations) {
            ++count;
            std::vector<double> z = leastSquares(a, b, passive);
            if (first && z[best] <= 0.0) {
                // Rounding at the optimum: the column would enter negative and be picked again
                // forever. Keep it out until some other column changes the solution.
                passive[best] = false;
                blocked[best] = true;
                break;
            }
            first = false;
            bool feasible = true;
            for (std::size_t c = 0; c < p; ++c) {
                if (passive[c] && z[c] <= 0.0) feasible = false;
            }
            if (feasible) {
                x = z;
                blocked.assign(p, false);
                break;
            }
            // Step from x towards z until the first passive coefficient reaches 0; that one
            // leaves the passive set exactly (rounding would otherwise leave it at 1e-17).
            double alpha = 1.0;
            std::size_t leaving = p;
            for (std::size_t c = 0; c < p; ++c) {
                if (passive[c] && z[c] <= 0.0) {
                    const double step = x[c] / (x[c] - z[c]);
                    if (leaving == p || step < alpha) {
                        alpha = step;
                        leaving = c;
                    }
                }
            }
            for (std::size_t c = 0; c < p; ++c) {
                if (passive[c]) x[c] += alpha * (z[c] - x[c]);
            }
            x[leaving] = 0.0;
            for (std::size_t c = 0; c < p; ++c) {
                if (passive[c] && x[c] <= 0.0) {
                    passive[c] = false;
                    x[c] = 0.0;
                }
            }
        }
    }
    if (iterations) *iterations = count;
    return x;
}

namespace {

std::string joinNames(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

// Symmetric eigenvalues by cyclic Jacobi rotations (the matrices here are at most 9 x 9).
std::vector<double> symmetricEigenvalues(std::vector<double> m, std::size_t n) {
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = i + 1; j < n; ++j) off += m[i * n + j] * m[i * n + j];
        }
        if (off < 1e-30) break;
        for (std::size_t p = 0; p < n; ++p) {
            for (std::size_t q = p + 1; q < n; ++q) {
                const double apq = m[p * n + q];
                if (std::abs(apq) < 1e-300) continue;
                const double theta = (m[q * n + q] - m[p * n + p]) / (2.0 * apq);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (std::size_t k = 0; k < n; ++k) {
                    const double akp = m[k * n + p], akq = m[k * n + q];
                    m[k * n + p] = c * akp - s * akq;
                    m[k * n + q] = s * akp + c * akq;
                }
                for (std::size_t k = 0; k < n; ++k) {
                    const double apk = m[p * n + k], aqk = m[q * n + k];
                    m[p * n + k] = c * apk - s * aqk;
                    m[q * n + k] = s * apk + c * aqk;
                }
            }
        }
    }
    std::vector<double> values(n);
    for (std::size_t i = 0; i < n; ++i) values[i] = m[i * n + i];
    return values;
}

double conditionNumber(const std::vector<std::vector<double>>& unitColumns, const std::vector<std::size_t>& kept) {
    const std::size_t k = kept.size();
    if (k == 0) return 0.0;
    std::vector<double> gram(k * k, 0.0);
    for (std::size_t i = 0; i < k; ++i) {
        for (std::size_t j = i; j < k; ++j) {
            double dot = 0.0;
            const auto& u = unitColumns[kept[i]];
            const auto& v = unitColumns[kept[j]];
            for (std::size_t r = 0; r < u.size(); ++r) dot += u[r] * v[r];
            gram[i * k + j] = gram[j * k + i] = dot;
        }
    }
    std::vector<double> eigen = symmetricEigenvalues(gram, k);
    const double largest = *std::max_element(eigen.begin(), eigen.end());
    const double smallest = *std::min_element(eigen.begin(), eigen.end());
    if (smallest <= 0.0) return std::numeric_limits<double>::infinity();
    return std::sqrt(largest / smallest);
}

// Distance of unit column `u` to the span of orthonormal `basis`.
double distanceToSpan(std::vector<double> u, const std::vector<std::vector<double>>& basis,
                      std::vector<double>* remainder = nullptr) {
    for (int pass = 0; pass < 2; ++pass) {  // twice: classical Gram–Schmidt loses orthogonality
        for (const auto& q : basis) {
            double dot = 0.0;
            for (std::size_t r = 0; r < u.size(); ++r) dot += q[r] * u[r];
            for (std::size_t r = 0; r < u.size(); ++r) u[r] -= dot * q[r];
        }
    }
    double norm = 0.0;
    for (double v : u) norm += v * v;
    norm = std::sqrt(norm);
    if (remainder) *remainder = std::move(u);
    return norm;
}

}  // namespace

ColumnCheck checkColumns(const Matrix& a, const std::vector<std::size_t>& order, const std::vector<std::string>& names,
                         int interceptColumn, double dependencyTolerance, double maxConditionNumber) {
    assert(names.size() == a.cols);
    ColumnCheck check;
    check.kept.assign(a.cols, false);
    std::vector<std::vector<double>> unit(a.cols, std::vector<double>(a.rows, 0.0));
    std::vector<double> norms(a.cols, 0.0);
    for (std::size_t c = 0; c < a.cols; ++c) {
        double norm = 0.0;
        for (std::size_t r = 0; r < a.rows; ++r) norm += a.at(r, c) * a.at(r, c);
        norms[c] = std::sqrt(norm);
        if (norms[c] > 0.0) {
            for (std::size_t r = 0; r < a.rows; ++r) unit[c][r] = a.at(r, c) / norms[c];
        }
    }
    std::vector<std::vector<double>> basis;
    std::vector<std::size_t> kept;
    for (std::size_t c : order) {
        if (norms[c] == 0.0) {
            check.notes.push_back("dropped '" + names[c] + "': zero in every sample");
            continue;
        }
        std::vector<double> remainder;
        const double distance = distanceToSpan(unit[c], basis, &remainder);
        if (distance < dependencyTolerance) {
            std::vector<std::string> before;
            for (std::size_t k : kept) before.push_back(names[k]);
            bool constant = false;
            if (interceptColumn >= 0 && check.kept[interceptColumn] && c != std::size_t(interceptColumn)) {
                constant = distanceToSpan(unit[c], {unit[interceptColumn]}) < dependencyTolerance;
            }
            // Name a single culprit when there is one: the usual case (matrices == drawn objects).
            std::string partner;
            for (std::size_t k : kept) {
                if (int(k) == interceptColumn || !partner.empty()) continue;
                std::vector<std::vector<double>> pair;
                std::vector<double> rem;
                if (interceptColumn >= 0 && check.kept[interceptColumn]) pair.push_back(unit[interceptColumn]);
                const double d = distanceToSpan(unit[k], pair, &rem);
                if (d <= 0.0) continue;
                for (double& v : rem) v /= d;
                pair.push_back(std::move(rem));
                if (distanceToSpan(unit[c], pair) < dependencyTolerance) partner = names[k];
            }
            std::string note = "dropped '" + names[c] + "': ";
            if (constant)
                note += "constant over the samples (absorbed by '" + names[interceptColumn] + "')";
            else if (!partner.empty())
                note += "a copy of '" + partner + "' (up to scale and offset) over the samples";
            else
                note += "a linear combination of " + joinNames(before) + " over the samples";
            check.notes.push_back(note);
            continue;
        }
        for (double& v : remainder) v /= distance;
        basis.push_back(std::move(remainder));
        kept.push_back(c);
        check.kept[c] = true;
    }
    check.conditionNumber = conditionNumber(unit, kept);
    while (check.conditionNumber > maxConditionNumber && kept.size() > 1) {
        // Drop the kept column closest to the span of the other kept columns.
        std::size_t worst = 1;
        double worstDistance = std::numeric_limits<double>::infinity();
        for (std::size_t i = 1; i < kept.size(); ++i) {
            std::vector<std::vector<double>> others;
            for (std::size_t j = 0; j < kept.size(); ++j) {
                if (j == i) continue;
                std::vector<double> rem;
                double d = distanceToSpan(unit[kept[j]], others, &rem);
                if (d > 0.0) {
                    for (double& v : rem) v /= d;
                    others.push_back(std::move(rem));
                }
            }
            const double d = distanceToSpan(unit[kept[i]], others);
            if (d < worstDistance) {
                worstDistance = d;
                worst = i;
            }
        }
        std::ostringstream note;
        note << "dropped '" << names[kept[worst]] << "': nearly collinear with the other features (condition number "
             << check.conditionNumber << " > " << maxConditionNumber << ")";
        check.notes.push_back(note.str());
        check.kept[kept[worst]] = false;
        kept.erase(kept.begin() + std::ptrdiff_t(worst));
        check.conditionNumber = conditionNumber(unit, kept);
    }
    return check;
}

CheckedFit fitNonNegative(const Matrix& a, const std::vector<double>& b, const std::vector<double>& weights,
                          const std::vector<std::size_t>& order, const std::vector<std::string>& names,
                          int interceptColumn) {
    assert(b.size() == a.rows && weights.size() == a.rows);
    CheckedFit fit;
    ColumnCheck check = checkColumns(a, order, names, interceptColumn, kDependencyTolerance, kMaxConditionNumber);
    fit.kept = check.kept;
    fit.notes = check.notes;
    fit.conditionNumber = check.conditionNumber;
    std::vector<std::size_t> columns;
    for (std::size_t c = 0; c < a.cols; ++c) {
        if (check.kept[c]) columns.push_back(c);
    }
    Matrix scaled(a.rows, columns.size());
    std::vector<double> target(a.rows);
    std::vector<double> scales(columns.size(), 0.0);
    for (std::size_t j = 0; j < columns.size(); ++j) {
        double norm = 0.0;
        for (std::size_t r = 0; r < a.rows; ++r) {
            const double v = weights[r] * a.at(r, columns[j]);
            scaled.at(r, j) = v;
            norm += v * v;
        }
        scales[j] = norm > 0.0 ? std::sqrt(norm) : 1.0;
        for (std::size_t r = 0; r < a.rows; ++r) scaled.at(r, j) /= scales[j];
    }
    for (std::size_t r = 0; r < a.rows; ++r) target[r] = weights[r] * b[r];
    std::vector<double> y = nonNegativeLeastSquares(scaled, target, &fit.iterations);
    fit.coefficients.assign(a.cols, 0.0);
    for (std::size_t j = 0; j < columns.size(); ++j) fit.coefficients[columns[j]] = y[j] / scales[j];
    return fit;
}

}  // namespace lodopt::timemodel::detail
