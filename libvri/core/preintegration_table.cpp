#include "libvri/core/preintegration_table.h"

#include <algorithm>
#include <limits>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "libvri/core/exact_ray.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

namespace {

// The segment's integral by the exact method: one piece of `length` world units whose scalar is the
// quadratic through front (sigma = 0), front/2 + back/2 + delta (sigma = 1/2) and back (sigma = 1).
SegmentIntegral<double> integrateSegment(ExactRay& ray, double length, double front, double back, double delta) {
    ray.begin();
    const Cubic s{{front, back - front + 4.0 * delta, -4.0 * delta, 0.0}};
    ray.addPiece(length, s, std::abs(front) + std::abs(back) + 4.0 * std::abs(delta), false);
    double value[4], bound[4];
    ray.finish(0.0, value, bound);
    return {value[0], value[1], value[2], ray.opticalDepth()};
}

}  // namespace

PreintegrationTable::PreintegrationTable(const TransferFunction& tf, double segmentLength, int size, int order)
    : size_(size), order_(order), length_(segmentLength) {
    if (size < kMinSize || size > kMaxSize)
        throw Error("pre-integration table size must be in [" + std::to_string(kMinSize) + ", " +
                    std::to_string(kMaxSize) + "], got " + std::to_string(size));
    if (order != 1 && order != 2) throw Error("pre-integration order must be 1 or 2, got " + std::to_string(order));
    if (!(segmentLength > 0.0) || !std::isfinite(segmentLength))
        throw Error("pre-integration segment length must be positive and finite, got " + exactNumber(segmentLength));
    const std::size_t entries = static_cast<std::size_t>(size) * size * 4;
    values_.resize(entries);
    if (order == 2) slopes_.resize(entries);
    const double spacing = 1.0 / (size - 1), step = kSlopeStep * spacing;
    // Rows in parallel, each entry on its own: the table does not depend on the thread count.
    tbb::parallel_for(tbb::blocked_range<int>(0, size), [&](const tbb::blocked_range<int>& rows) {
        ExactRay ray(tf, kEntryTolerance);
        for (int i = rows.begin(); i < rows.end(); ++i)
            for (int j = 0; j < size; ++j) {
                const double front = i * spacing, back = j * spacing;
                const std::size_t at = (static_cast<std::size_t>(i) * size + j) * 4;
                const SegmentIntegral<double> v = integrateSegment(ray, segmentLength, front, back, 0.0);
                values_[at] = v.r, values_[at + 1] = v.g, values_[at + 2] = v.b, values_[at + 3] = v.depth;
                if (order != 2) continue;
                const SegmentIntegral<double> up = integrateSegment(ray, segmentLength, front, back, step);
                const SegmentIntegral<double> down = integrateSegment(ray, segmentLength, front, back, -step);
                slopes_[at] = (up.r - down.r) / (2.0 * step);
                slopes_[at + 1] = (up.g - down.g) / (2.0 * step);
                slopes_[at + 2] = (up.b - down.b) / (2.0 * step);
                slopes_[at + 3] = (up.depth - down.depth) / (2.0 * step);
            }
    });
    valuesFloat_.assign(values_.begin(), values_.end());
    slopesFloat_.assign(slopes_.begin(), slopes_.end());
    const TransferFunctionSample<double> top = tf.largest();
    const double colourMax[3] = {top.r, top.g, top.b};
    const double depthMax = segmentLength * top.tau;
    const double weight = tf.emission() == EmissionModel::ColourTimesExtinction ? -std::expm1(-depthMax) : segmentLength;
    for (int c = 0; c < 3; ++c) upper_[c] = colourMax[c] * weight;
    upper_[3] = depthMax;
    for (int c = 0; c < 4; ++c) upperFloat_[c] = static_cast<float>(upper_[c]);
    findZeroRuns();
    deltaLevels_ = {0.0};
    if (order == 2) {
        const double widest = 1.0 - spacing;
        for (const double k : kCheckedSpacings) deltaLevels_.push_back(k * spacing);
        for (const double f : kCheckedFractions) deltaLevels_.push_back(f);
        std::erase_if(deltaLevels_, [&](double d) { return d >= widest; });
        deltaLevels_.push_back(widest);
        std::sort(deltaLevels_.begin(), deltaLevels_.end());
        deltaLevels_.erase(std::unique(deltaLevels_.begin(), deltaLevels_.end()), deltaLevels_.end());
    }
}

// A run [p, q] of indices whose every pair (i, j) in [p, q]^2 has all four values (and slopes) exactly 0,
// grown from the left as long as the next index keeps the square zero; the next run starts after it. The
// runs partition the indices that are in one, so two ranges of indices that share one lie in the same run.
void PreintegrationTable::findZeroRuns() {
    const auto zero = [&](int i, int j) {
        const std::size_t at = (static_cast<std::size_t>(i) * size_ + j) * 4;
        for (int c = 0; c < 4; ++c)
            if (values_[at + c] != 0.0 || (order_ == 2 && slopes_[at + c] != 0.0)) return false;
        return true;
    };
    zeroRun_.assign(static_cast<std::size_t>(size_), -1);
    int runs = 0;
    for (int p = 0; p < size_;) {
        if (!zero(p, p)) {
            ++p;
            continue;
        }
        int q = p;
        const auto extends = [&](int next) {
            for (int i = p; i <= next; ++i)
                if (!zero(i, next) || !zero(next, i)) return false;
            return true;
        };
        while (q + 1 < size_ && extends(q + 1)) ++q;
        for (int i = p; i <= q; ++i) zeroRun_[static_cast<std::size_t>(i)] = runs;
        ++runs;
        p = q + 1;
    }
}

bool PreintegrationTable::isInvisible(double s0, double s1) const {
    // The entries a lookup of a scalar reads: its cell's two ends, located as operator() locates it.
    const auto cell = [&](double s) {
        const double x = std::clamp(s, 0.0, 1.0) * (size_ - 1);
        return std::min(static_cast<int>(x), size_ - 2);
    };
    const int first = cell(s0), last = cell(s1) + 1;
    const int run = zeroRun_[static_cast<std::size_t>(first)];
    return run >= 0 && zeroRun_[static_cast<std::size_t>(last)] == run;
}

double PreintegrationTable::invisibleBelow() const {
    const int run = zeroRun_.front();
    // Scalars below 0 (a volume whose stated range is narrower than its data) are clamped to 0, onto entry 0.
    if (run < 0) return -std::numeric_limits<double>::infinity();
    int last = 0;  // the run's last entry: a lookup at s reads entries up to floor(s (size - 1)) + 1
    while (last + 1 < size_ && zeroRun_[static_cast<std::size_t>(last) + 1] == run) ++last;
    return last + 1 == size_ ? std::numeric_limits<double>::infinity() : static_cast<double>(last) / (size_ - 1);
}

SegmentIntegral<double> PreintegrationTable::direct(const TransferFunction& tf, double segmentLength, double front,
                                                    double back, double delta) {
    ExactRay ray(tf, kEntryTolerance);
    return integrateSegment(ray, segmentLength, front, back, delta);
}

std::pair<double, double> PreintegrationError::upTo(double largestDelta) const {
    if (deltas.empty()) return {colour, alpha};
    double c = 0.0, a = 0.0;
    for (std::size_t k = 0; k < deltas.size(); ++k) {
        c = std::max(c, colourByDelta[k]);
        a = std::max(a, alphaByDelta[k]);
        if (deltas[k] >= largestDelta) break;
    }
    return {c, a};
}

PreintegrationError PreintegrationTable::check(const TransferFunction& tf) const {
    constexpr int kMaxChecked = 64;  // per axis: 4096 points, a fraction of the table's own cost
    const int cells = size_ - 1;
    const double spacing = 1.0 / cells;
    // The cells checked per axis: kMaxChecked spread evenly, and those holding a transfer-function point
    // (up to kMaxChecked of them), where the integral has a kink that interpolation resolves worst.
    // The last cell too, where the largest deviations below 0 are asked.
    std::vector<int> cell{cells - 1};
    for (int a = 0; a < std::min(cells, kMaxChecked); ++a) cell.push_back(a * cells / std::min(cells, kMaxChecked));
    int points = 0;
    for (const TransferFunctionPoint& p : tf.points())
        if (p.s >= 0.0 && p.s < 1.0 && points++ < kMaxChecked) cell.push_back(static_cast<int>(p.s * cells));
    std::sort(cell.begin(), cell.end());
    cell.erase(std::unique(cell.begin(), cell.end()), cell.end());
    const int checked = static_cast<int>(cell.size());
    std::vector<double> deltas = deltaLevels_;  // each checked with both signs
    const std::size_t levels = deltas.size();
    struct Row {
        std::vector<double> colour, alpha;
        int points = 0;
    };
    std::vector<Row> rows(checked, Row{std::vector<double>(levels, 0.0), std::vector<double>(levels, 0.0), 0});
    tbb::parallel_for(tbb::blocked_range<int>(0, checked), [&](const tbb::blocked_range<int>& range) {
        ExactRay ray(tf, kEntryTolerance);
        for (int a = range.begin(); a < range.end(); ++a)
            for (int b = 0; b < checked; ++b)
                for (std::size_t level = 0; level < levels; ++level)
                    for (const double sign : {1.0, -1.0}) {
                        const double front = (cell[a] + 0.5) * spacing, back = (cell[b] + 0.5) * spacing;
                        const double delta = sign * deltas[level], middle = 0.5 * (front + back) + delta;
                        if (middle < 0.0 || middle > 1.0 || (level == 0 && sign < 0)) continue;
                        const SegmentIntegral<double> want = integrateSegment(ray, length_, front, back, delta);
                        const SegmentIntegral<double> got = (*this)(front, back, delta);
                        Row& e = rows[a];
                        e.colour[level] = std::max({e.colour[level], std::abs(got.r - want.r), std::abs(got.g - want.g),
                                                    std::abs(got.b - want.b)});
                        e.alpha[level] =
                            std::max(e.alpha[level], std::abs(std::expm1(-got.depth) - std::expm1(-want.depth)));
                        ++e.points;
                    }
    });
    PreintegrationError total;
    std::vector<double> colour(levels, 0.0), alpha(levels, 0.0);
    for (const Row& e : rows) {
        for (std::size_t level = 0; level < levels; ++level) {
            colour[level] = std::max(colour[level], e.colour[level]);
            alpha[level] = std::max(alpha[level], e.alpha[level]);
        }
        total.points += e.points;
    }
    total.colour = *std::max_element(colour.begin(), colour.end());
    total.alpha = *std::max_element(alpha.begin(), alpha.end());
    if (order_ == 2) {
        total.deltas = std::move(deltas);
        total.colourByDelta = std::move(colour);
        total.alphaByDelta = std::move(alpha);
    }
    return total;
}

}  // namespace vri
