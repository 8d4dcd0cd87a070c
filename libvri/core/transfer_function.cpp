#include "libvri/core/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "libvri/util/error.h"

namespace vri {

std::string_view emissionModelName(EmissionModel m) {
    return m == EmissionModel::Colour ? "color" : "color-times-extinction";
}

EmissionModel parseEmissionModel(std::string_view name, const std::string& what) {
    if (name == "color") return EmissionModel::Colour;
    if (name == "color-times-extinction") return EmissionModel::ColourTimesExtinction;
    throw Error(what + ": emission '" + std::string(name) + "' is unknown (expected color-times-extinction or color)");
}

void validateTransferFunctionPoint(const TransferFunctionPoint& p, const TransferFunctionPoint* previous,
                                   const std::string& where) {
    for (double v : {p.s, p.r, p.g, p.b, p.tau})
        if (!std::isfinite(v)) throw Error(where + " has a value that is not finite");
    if (p.r < 0 || p.g < 0 || p.b < 0) throw Error(where + " has a negative colour (expected >= 0)");
    if (p.tau < 0) throw Error(where + " has a negative extinction tau (expected >= 0)");
    if (previous && p.s < previous->s) {
        std::ostringstream msg;
        msg << where << " has s = " << p.s << " below the previous point's s = " << previous->s
            << " (points must be sorted by s)";
        throw Error(msg.str());
    }
}

TransferFunction::TransferFunction(std::vector<TransferFunctionPoint> points, EmissionModel emission,
                                   const std::string& source)
    : points_(std::move(points)), emission_(emission) {
    if (points_.empty()) throw Error(source + ": a transfer function needs at least one point");
    if (points_.size() > kMaxPoints)
        throw Error(source + ": " + std::to_string(points_.size()) + " points, more than the limit of " +
                    std::to_string(kMaxPoints));
    for (std::size_t i = 0; i < points_.size(); ++i)
        validateTransferFunctionPoint(points_[i], i > 0 ? &points_[i - 1] : nullptr,
                                      source + ": point " + std::to_string(i));
    const double span = points_.back().s - points_.front().s;
    // Between two points a value is interpolated by (s - s0) / (s1 - s0): a span past the largest
    // double gives every s in it the first point's value.
    if (!std::isfinite(span)) {
        std::ostringstream msg;
        msg << source << ": the points' s from " << points_.front().s << " to " << points_.back().s
            << " span more than the largest double (expected a finite s1 - s0)";
        throw Error(msg.str());
    }
    // A span below kBins times the smallest double (a subnormal span) makes the scale infinite, and the bin of
    // an s inside it (s - s0) * inf, which no int holds: such a function is searched from its first point.
    binScale_ = span > 0 && std::isfinite(kBins / span) ? kBins / span : 0.0;
    binStart_.assign(kBins, 0);
    std::size_t i = 0;
    for (int bin = 0; bin < kBins; ++bin) {
        const double s = points_.front().s + bin / (binScale_ > 0 ? binScale_ : 1.0);
        while (i + 2 < points_.size() && s >= points_[i + 1].s) ++i;
        binStart_[bin] = static_cast<std::uint32_t>(i);
    }
}

TransferFunctionSample<double> TransferFunction::largest() const {
    TransferFunctionSample<double> top{0.0, 0.0, 0.0, 0.0};
    for (const TransferFunctionPoint& p : points_) {
        top.r = std::max(top.r, p.r);
        top.g = std::max(top.g, p.g);
        top.b = std::max(top.b, p.b);
        top.tau = std::max(top.tau, p.tau);
    }
    return top;
}

bool TransferFunction::isInvisible(double s0, double s1) const {
    // Piecewise linear and non-negative: zero on [s0, s1] iff zero at both ends and every point between.
    if (!isInvisible((*this)(s0)) || !isInvisible((*this)(s1))) return false;
    for (const auto& p : points_)
        if (p.s > s0 && p.s < s1 && !isInvisible({p.r, p.g, p.b, p.tau})) return false;
    return true;
}

}  // namespace vri
