#include <doctest/doctest.h>

#include "libvri/experiment/experiment_reproduce.h"

namespace {

namespace fs = std::filesystem;

vri::Step step(const std::string& id, std::vector<fs::path> inputs) {
    vri::Step s;
    s.id = id;
    s.inputs = std::move(inputs);
    s.outputs = {"/r/" + id};
    return s;
}

std::vector<std::string> ids(const vri::Plan& plan) {
    std::vector<std::string> out;
    for (const vri::Step& s : plan.steps) out.push_back(s.id);
    return out;
}

}  // namespace

TEST_CASE("reproduce check: a plan shrinks to the checked steps, what they read and what other experiments read") {
    // a and b render, diff reads a, table reads diff and b, figure reads table.
    vri::Plan plan{"/r", "/w", {step("a", {}), step("b", {}), step("diff", {"/r/a"}), step("table", {"/r/diff", "/r/b"}),
                                step("figure", {"/r/table"})},
                   {{}, {}, {0}, {2, 1}, {3}}};
    vri::Experiment experiment;
    CHECK(ids(vri::checkedPart(experiment, plan, {})) == ids(plan));  // no numbers named: the plan whole

    experiment.reproduce.push_back({"diff", {"max_abs"}, "", 0});
    const vri::Plan part = vri::checkedPart(experiment, plan, {});
    CHECK(ids(part) == std::vector<std::string>{"a", "diff"});
    CHECK(part.dependencies == std::vector<std::vector<std::size_t>>{{}, {0}});  // renumbered
    CHECK(part.part == "2 of its 5 steps: those its reproduce: numbers need (vri-run --check)");  // the manifest says so

    const vri::Plan shared = vri::checkedPart(experiment, plan, {"/r/table"});
    CHECK(ids(shared) == std::vector<std::string>{"a", "b", "diff", "table"});
    CHECK(shared.dependencies == std::vector<std::vector<std::size_t>>{{}, {}, {0}, {2, 1}});
}
