#pragma once
// Piecewise-linear transfer function: normalised scalar s -> colour (R, G, B) and extinction tau.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vri {

// What the colour means in the emission-absorption integral I = ∫ g(s) exp(-∫ tau) dt.
enum class EmissionModel {
    ColourTimesExtinction,  // g = C(s) tau(s): Max's model as paper B writes the VRI (the default)
    Colour,                 // g = C(s): paper A's analytic study, where g(s) = s and tau(s) = s / 2
};
std::string_view emissionModelName(EmissionModel m);  // "color-times-extinction", "color"
// The model of a name emissionModelName() gives; throws vri::Error "<what>: emission '<name>' is unknown (...)".
EmissionModel parseEmissionModel(std::string_view name, const std::string& what);

struct TransferFunctionPoint {
    double s;        // normalised scalar
    double r, g, b;  // colour, >= 0
    double tau;      // extinction per world unit (= per voxel for unit spacing), >= 0
};

// Throws vri::Error "<where> <what is wrong>" unless every value of `p` is finite, colour and tau are
// non-negative, and s is not below the previous point's.
void validateTransferFunctionPoint(const TransferFunctionPoint& p, const TransferFunctionPoint* previous,
                                   const std::string& where);

template <class Real>
struct TransferFunctionSample {
    Real r, g, b, tau;
};

class TransferFunction {
public:
    // The most points a transfer function may have: far more than any classification in use (lookup
    // tables hold 256 or 1024 entries), and what a YAML file of kMaxYamlNodes nodes can hold.
    static constexpr std::size_t kMaxPoints = 10000;

    // Throws vri::Error naming `source` when there are no points or more than kMaxPoints, a value is
    // negative or not finite, or the points are not sorted by s (equal s is allowed and makes a jump).
    TransferFunction(std::vector<TransferFunctionPoint> points, EmissionModel emission,
                     const std::string& source = "transfer function");

    const std::vector<TransferFunctionPoint>& points() const { return points_; }
    EmissionModel emission() const { return emission_; }

    // Linear interpolation between the bracketing points; constant beyond the first and last point.
    // At a jump (two points with equal s) the value is taken from the right.
    template <class Real>
    TransferFunctionSample<Real> operator()(Real s) const {
        std::size_t segment = 0;
        return (*this)(s, segment);
    }

    // The same value, trying the segment of the previous call first (`segment`, updated): along a ray
    // s moves a little at a time, so the last bracket usually still holds. The bracket p[i].s <= s <
    // p[i + 1].s is unique, so the result never depends on what `segment` held.
    template <class Real>
    TransferFunctionSample<Real> operator()(Real s, std::size_t& segment) const {
        const auto& p = points_;
        if (!(s >= static_cast<Real>(p.front().s))) return at<Real>(0);
        if (!(s < static_cast<Real>(p.back().s))) return at<Real>(p.size() - 1);
        std::size_t i = segment;
        if (!(i + 1 < p.size() && s >= static_cast<Real>(p[i].s) && s < static_cast<Real>(p[i + 1].s))) {
            const int bin = static_cast<int>((static_cast<double>(s) - p.front().s) * binScale_);
            i = binStart_[bin < 0 ? 0 : (bin >= kBins ? kBins - 1 : bin)];
            while (i > 0 && s < static_cast<Real>(p[i].s)) --i;  // guards the bin's rounding
            while (s >= static_cast<Real>(p[i + 1].s)) ++i;
            segment = i;
        }
        const auto& a = p[i];
        const auto& b = p[i + 1];
        const Real w = (s - static_cast<Real>(a.s)) / static_cast<Real>(b.s - a.s);
        auto lerp = [w](double x, double y) { return static_cast<Real>(x) + w * static_cast<Real>(y - x); };
        return {lerp(a.r, b.r), lerp(a.g, b.g), lerp(a.b, b.b), lerp(a.tau, b.tau)};
    }

    // Each channel's largest value over the points, which bounds it everywhere: the function
    // interpolates linearly between them and is constant beyond.
    TransferFunctionSample<double> largest() const;

    // True when neither extinction nor emission is non-zero anywhere in [s0, s1]: samples there
    // contribute exactly nothing, so a renderer may skip them without changing a single bit.
    bool isInvisible(double s0, double s1) const;
    // The same for one sample of the function (its r, g, b and tau at one s): no extinction, and no
    // emission that could show (colour x extinction shows no colour without extinction).
    bool isInvisible(const TransferFunctionSample<double>& v) const {
        return v.tau == 0.0 && (emission_ == EmissionModel::ColourTimesExtinction || (v.r == 0 && v.g == 0 && v.b == 0));
    }

private:
    template <class Real>
    TransferFunctionSample<Real> at(std::size_t i) const {
        const auto& q = points_[i];
        return {static_cast<Real>(q.r), static_cast<Real>(q.g), static_cast<Real>(q.b), static_cast<Real>(q.tau)};
    }

    static constexpr int kBins = 256;  // accelerates the bracket search; never changes the result
    std::vector<TransferFunctionPoint> points_;
    EmissionModel emission_;
    std::vector<std::uint32_t> binStart_;
    double binScale_ = 0.0;
};

}  // namespace vri
