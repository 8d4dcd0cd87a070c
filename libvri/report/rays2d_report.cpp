#include "libvri/report/rays2d_report.h"

#include <algorithm>
#include <cmath>

#include "libvri/util/checked_size.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

namespace {

// A CSV file built line by line, header first.
class CsvWriter {
public:
    explicit CsvWriter(const std::vector<std::string>& header) { row(header); }
    void row(const std::vector<std::string>& cells) { text_ += csvLine(cells); }
    const std::string& text() const { return text_; }

private:
    std::string text_;
};

void segment(CsvWriter& csv, const std::string& panel, const std::string& kind, glm::dvec2 a, glm::dvec2 b) {
    csv.row({panel, kind, exactNumber(a.x), exactNumber(a.y), exactNumber(b.x), exactNumber(b.y)});
}

void square(CsvWriter& csv, const Study2D& study, const std::string& panel) {
    const double h = 0.5 * study.side;
    const glm::dvec2 corners[] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    for (int i = 0; i < 4; ++i)
        segment(csv, panel, "square", study.toWorld(corners[i]), study.toWorld(corners[(i + 1) % 4]));
}

// One ray of a placement panel: the ray, its samples, their stretches and what they miss.
void diagramRay(CsvWriter& csv, const std::string& panel, const RaySamples& r, double tickLength) {
    auto at = [&](double distance) { return r.entry + distance * r.direction; };
    const glm::dvec2 across = tickLength * glm::dvec2(-r.direction.y, r.direction.x);
    const double overhang = 0.5;  // world units of ray drawn before the entry and after the exit
    segment(csv, panel, "ray", at(-overhang), at(r.length + overhang));
    // Part [a, b] of a stretch: covered inside the square, overshot outside.
    auto stretch = [&](double a, double b) {
        const double lo = std::clamp(a, 0.0, r.length), hi = std::clamp(b, 0.0, r.length);
        if (a < lo) segment(csv, panel, "overshot", at(a), at(lo));
        if (lo < hi) segment(csv, panel, "covered", at(lo), at(hi));
        if (hi < b) segment(csv, panel, "overshot", at(hi), at(b));
    };
    for (double p : r.positions) {
        const double a = p - 0.5 * r.step, b = p + 0.5 * r.step;
        stretch(a, b);
        for (double end : {a, b}) segment(csv, panel, "tick", at(end) - across, at(end) + across);
        segment(csv, panel, "sample", at(p), at(p));
    }
    // Consecutive stretches touch, so together they cover one interval; the rest of [0, D] is missed.
    if (r.positions.empty()) {
        segment(csv, panel, "missed", at(0.0), at(r.length));
        return;
    }
    const double from = r.positions.front() - 0.5 * r.step, to = r.positions.back() + 0.5 * r.step;
    if (from > 0.0) segment(csv, panel, "missed", at(0.0), at(std::min(from, r.length)));
    if (to < r.length) segment(csv, panel, "missed", at(std::max(to, 0.0)), at(r.length));
}

int raysThatHit(const Fan& fan) {
    return static_cast<int>(std::count_if(fan.rays.begin(), fan.rays.end(), [](const Ray2D& r) { return r.length > 0.0; }));
}

struct ErrorSummary {
    double maxAbs = 0.0, meanAbs = 0.0, over = 0.0, under = 0.0;
    int empty = 0;  // rays of positive length without a sample
};

ErrorSummary summarise(const Fan& fan, std::size_t placement, std::size_t rate) {
    ErrorSummary s;
    int hits = 0;
    for (std::size_t i = 0; i < fan.rays.size(); ++i) {
        if (!(fan.rays[i].length > 0.0)) continue;
        ++hits;
        const DiscreteRay& d = fan.discrete[placement][rate][i];
        const double e = d.intensity - fan.rays[i].closedForm;
        s.maxAbs = std::max(s.maxAbs, std::abs(e));
        s.meanAbs += std::abs(e);
        s.over = std::max(s.over, e);
        s.under = std::max(s.under, -e);
        s.empty += d.samples == 0;
    }
    if (hits > 0) s.meanAbs /= hits;
    return s;
}

}  // namespace

Fan castFan(const Rays2D& study, const std::vector<Placement>& placements, const std::vector<double>& rates) {
    double rateSum = 0.0;
    for (double rate : rates) rateSum += rate;
    const Study2D& s = study.study();
    requireWithin("2D study: " + std::to_string(s.rays) + " rays x " + std::to_string(placements.size()) +
                      " placements at rates summing to " + exactNumber(rateSum) + " on a " +
                      std::to_string(s.gridSize) + "x" + std::to_string(s.gridSize) + " grid",
                  double(s.rays) * double(placements.size()) * rateSum * study.samplesPerRayAtRate1(), kMaxFanSamples,
                  "samples");
    Fan fan{placements, rates, study.closedForm(), {}};
    for (Placement p : placements) {
        auto& perRate = fan.discrete.emplace_back();
        for (double rate : rates) {
            auto& perRay = perRate.emplace_back();
            for (const Ray2D& ray : fan.rays) perRay.push_back(study.discrete(ray.index, p, rate));
        }
    }
    return fan;
}

std::string fanColumn(Placement placement, double rate) {
    return std::string(placementName(placement)) + "_r" + exactNumber(rate);
}

std::string fanCsv(const Fan& fan) {
    std::vector<std::string> header{"ray", "angle_deg", "length", "closed_form"};
    for (Placement p : fan.placements)
        for (double rate : fan.rates) header.push_back(fanColumn(p, rate));
    for (Placement p : fan.placements)
        for (double rate : fan.rates) header.push_back("n_" + fanColumn(p, rate));
    CsvWriter csv(header);
    for (std::size_t i = 0; i < fan.rays.size(); ++i) {
        const Ray2D& ray = fan.rays[i];
        std::vector<std::string> row{std::to_string(ray.index), exactNumber(ray.angleDegrees), exactNumber(ray.length),
                                     exactNumber(ray.closedForm)};
        for (const auto& perRate : fan.discrete)
            for (const auto& perRay : perRate) row.push_back(exactNumber(perRay[i].intensity));
        for (const auto& perRate : fan.discrete)
            for (const auto& perRay : perRate) row.push_back(std::to_string(perRay[i].samples));
        csv.row(row);
    }
    return csv.text();
}

Table fanErrorTable(const Fan& fan) {
    Table t;
    t.title = "Error of eq. (6) against the closed form, per placement and sampling rate";
    t.rowHeader = "Placement, rate";
    t.columns = {"max |error|", "mean |error|", "max over", "max under", "rays without samples"};
    t.precision = {6, 6, 6, 6, 0};
    for (std::size_t p = 0; p < fan.placements.size(); ++p)
        for (std::size_t r = 0; r < fan.rates.size(); ++r) {
            const ErrorSummary s = summarise(fan, p, r);
            t.rows.push_back(std::string(placementName(fan.placements[p])) + ", " + exactNumber(fan.rates[r]));
            t.cells.push_back({s.maxAbs, s.meanAbs, s.over, s.under, double(s.empty)});
        }
    t.notes = {"Over the " + std::to_string(raysThatHit(fan)) + " rays that cross the square; intensities are in "
               "[0, 2]. Over/under: the largest discrete sum above/below the closed form."};
    return t;
}

std::string convergenceCsv(const Fan& fan) {
    std::vector<std::string> header{"rate"};
    for (Placement p : fan.placements)
        for (const char* stat : {"_max", "_mean"}) header.push_back(std::string(placementName(p)) + stat);
    CsvWriter csv(header);
    for (std::size_t r = 0; r < fan.rates.size(); ++r) {
        std::vector<std::string> row{exactNumber(fan.rates[r])};
        for (std::size_t p = 0; p < fan.placements.size(); ++p) {
            const ErrorSummary s = summarise(fan, p, r);
            row.insert(row.end(), {exactNumber(s.maxAbs), exactNumber(s.meanAbs)});
        }
        csv.row(row);
    }
    return csv.text();
}

std::string diagramCsv(const Rays2D& study, const std::vector<int>& rays, const std::vector<Placement>& placements,
                       double rate) {
    const Study2D& s = study.study();
    for (int ray : rays)
        if (ray < 0 || ray >= s.rays)
            throw Error("diagram: ray " + std::to_string(ray) + " is not in 0.." + std::to_string(s.rays - 1));
    requireWithin("diagram: " + std::to_string(rays.size()) + " rays x " + std::to_string(placements.size()) +
                      " placements at rate " + exactNumber(rate),
                  double(rays.size()) * double(placements.size()) * rate * study.samplesPerRayAtRate1(),
                  kMaxDiagramSamples, "samples");
    CsvWriter csv({"panel", "kind", "x", "y", "x2", "y2"});
    square(csv, s, "setup");
    const double reach = glm::length(s.eye) + s.side;  // far enough past the square
    for (int i = 0; i < s.rays; ++i) segment(csv, "setup", "fan", s.eye, s.eye + reach * s.rayDirection(i));
    const double tick = 0.02 * s.side;
    for (Placement p : placements) {
        const std::string panel(placementName(p));
        square(csv, s, panel);
        for (int ray : rays) diagramRay(csv, panel, study.samples(ray, p, rate), tick);
    }
    return csv.text();
}

std::string fieldCsv(const Rays2D& study, int resolution) {
    if (resolution < 2) throw Error("field image: the resolution must be at least 2, got " + std::to_string(resolution));
    checkedCount("field image of " + std::to_string(resolution) + "x" + std::to_string(resolution) + " points",
                 {std::uint64_t(resolution), std::uint64_t(resolution)}, kMaxFieldPoints, "points (rows)");
    const double h = 0.5 * study.study().side;
    CsvWriter csv({"x", "y", "analytic", "reconstructed"});
    for (int j = 0; j < resolution; ++j)
        for (int i = 0; i < resolution; ++i) {
            const glm::dvec2 p(-h + 2.0 * h * i / (resolution - 1), -h + 2.0 * h * j / (resolution - 1));
            csv.row({exactNumber(p.x), exactNumber(p.y), exactNumber(study.analytic(p)), exactNumber(study.field(p))});
        }
    return csv.text();
}

}  // namespace vri
