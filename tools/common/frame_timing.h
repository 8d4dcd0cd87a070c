#pragma once
// What the tools that render for timing share: --threads, the frames --warm-up and --repeat ask for
// (render_option_table.h; every timed frame must equal the first, bit for bit), and the stats' timing record.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "libvri/render/render_job.h"
#include "libvri/util/cpu_load.h"
#include "libvri/util/error.h"

namespace vri {

class FrameTiming {
public:
    void addTo(CLI::App& app);  // --threads
    // Checks the count and, with --threads, limits oneTBB for as long as `control` lives.
    // A count above the cores this process may use runs on those, said on stderr ("<tool>: warning: ...").
    void limitThreads(std::optional<tbb::global_control>& control, std::string_view tool) const;
    // The untimed frames, then the timed ones (>= 1). Unless `quiet`, when there is more than one frame,
    // a line per frame on stderr ("<tool>: frame 2 of 5: 0.41 s"): progress, and each frame's time in a log.
    void setFrames(int warmUp, int repeat, std::string tool, bool quiet);

    // frame() and warmUpFrame() return a result with `image` (vri::Image) and `seconds` (its wall time).
    // Runs the warm-up frames untimed, then the timed ones; returns the first result and every wall time.
    template <class Frame, class WarmUpFrame>
    auto run(const Frame& frame, const WarmUpFrame& warmUpFrame) const {
        for (int i = 0; i < warmUp_; ++i) report("warm-up frame", i, warmUp_, warmUpFrame().seconds);
        const std::optional<CpuSample> before = sampleCpu();
        auto first = frame();
        report("frame", 0, repeat_, first.seconds);
        std::vector<double> wallSeconds{first.seconds};
        for (int i = 1; i < repeat_; ++i) {
            const auto again = frame();
            report("frame", i, repeat_, again.seconds);
            if (again.image.pixels != first.image.pixels)
                throw Error("--repeat: frame " + std::to_string(i + 1) + " differs from the first");
            wallSeconds.push_back(again.seconds);
        }
        measureLoad(before);
        return std::pair{std::move(first), std::move(wallSeconds)};
    }

    // frameTimingRecord's, with the load measured over the timed frames.
    nlohmann::json toJson(const std::vector<double>& wallSeconds) const;
    // For the tools' closing line: "0.94 s", or "0.94 s (median of 3)".
    std::string summary(const std::vector<double>& wallSeconds) const;

private:
    void report(const char* what, int index, int count, double seconds) const;
    // The other processes' load over the timed frames since `before`; said on stderr when it inflates them.
    void measureLoad(const std::optional<CpuSample>& before) const;
    mutable std::optional<TimingLoad> load_;

    int threads_ = 0, repeat_ = 1, warmUp_ = 0;
    std::string tool_;
    bool quiet_ = true;
};

}  // namespace vri
