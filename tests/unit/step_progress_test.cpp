// vri-run's live line: steps done of all, the running ones named, and an ETA from the last run's wall
// times shared among the jobs; steps never priced make it a lower bound, and none priced, no ETA.
#include <doctest/doctest.h>

#include "libvri/experiment/step_progress.h"

namespace {

vri::Plan planOf(std::size_t steps) {
    vri::Plan plan{"/results/exp", "/work", {}, {}};
    for (std::size_t i = 0; i < steps; ++i)
        plan.steps.push_back(vri::Step{"s" + std::to_string(i), "render", "vri-render", {}, {}, {}, {}});
    plan.dependencies.resize(steps);
    return plan;
}

}  // namespace

TEST_CASE("StepProgress's live line counts, names the running steps and prices what is left") {
    const vri::Plan plan = planOf(3);
    vri::StepProgress priced(plan, {4.0, 2.0, 6.0}, 2, vri::StepProgress::Style::Quiet);
    CHECK(priced.statusText() == "[0/3] ETA 6.0 s");  // 12 s of steps on 2 jobs
    priced.settled(0, "ran", "");
    CHECK(priced.statusText() == "[1/3] ETA 4.0 s");
    priced.settled(2, "cached", "");
    priced.started(1);
    const std::string running = priced.statusText();
    CHECK(running.starts_with("[2/3] running: s1; ETA "));  // at most its 2 s over two jobs, less its elapsed time
    CHECK(running.ends_with(" s"));

    vri::StepProgress partly(plan, {4.0, std::nullopt, std::nullopt}, 1, vri::StepProgress::Style::Quiet);
    CHECK(partly.statusText() == "[0/3] ETA at least 4.0 s (2 steps unpriced)");
    vri::StepProgress none(plan, {}, 1, vri::StepProgress::Style::Quiet);
    CHECK(none.statusText() == "[0/3] no ETA (3 steps never ran)");
}

TEST_CASE("StepProgress names at most three running steps") {
    const vri::Plan plan = planOf(5);
    vri::StepProgress progress(plan, {1.0, 1.0, 1.0, 1.0, 1.0}, 5, vri::StepProgress::Style::Quiet);
    for (std::size_t i = 0; i < 5; ++i) progress.started(i);
    CHECK(progress.statusText().starts_with("[0/5] running: s0, s1, s2 and 2 more; ETA "));
}
