// How the Slurm executor cuts steps into jobs and what the jobs ask for, and how it reads what
// Slurm's commands print.
#include <doctest/doctest.h>

#include "libvri/experiment/slurm_commands.h"
#include "libvri/experiment/slurm_jobs.h"
#include "libvri/experiment/slurm_profile.h"
#include "libvri/util/error.h"

namespace {

vri::Step planStep(const std::string& id, const std::string& kind, std::uint64_t pixels = 0, int threads = 0) {
    vri::Step step{id, kind, "vri-x", {}, {}, {}, {}};
    step.pixels = pixels;
    step.threads = threads;
    return step;
}

std::vector<std::vector<std::size_t>> stepsOf(const std::vector<vri::JobBundle>& bundles) {
    std::vector<std::vector<std::size_t>> steps;
    for (const vri::JobBundle& b : bundles) steps.push_back(b.steps);
    return steps;
}

}  // namespace

TEST_CASE("bundleSteps packs cheap steps in plan order and keeps long or unpriced renders alone") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a", "render"), planStep("b", "render"), planStep("c", "render"), planStep("d", "diff"),
                  planStep("e", "diff"),   planStep("f", "table"),  planStep("g", "render"), planStep("h", "figure")};
    const std::vector<std::optional<double>> prices{1.0, 2.0, 100.0, 0.5, 0.5, std::nullopt, std::nullopt, 0.1};
    const std::vector<std::size_t> all{0, 1, 2, 3, 4, 5, 6, 7};

    // c costs more than a bundle: alone, and it closes the bundle before it so jobs stay in plan order.
    // g is an unpriced render: alone. f is an unpriced table: 1 s in its bundle.
    CHECK(stepsOf(vri::bundleSteps(plan, all, prices, 60)) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {2}, {3, 4, 5}, {6}, {7}});
    // A bundle closes once it holds its seconds.
    CHECK(stepsOf(vri::bundleSteps(plan, {0, 1, 3, 4, 7}, prices, 2.5)) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {3, 4, 7}});
    // 0: a job per step.
    CHECK(vri::bundleSteps(plan, all, prices, 0).size() == 8);
    // Only the steps asked for.
    CHECK(stepsOf(vri::bundleSteps(plan, {6, 7}, prices, 60)) == std::vector<std::vector<std::size_t>>{{6}, {7}});
    const auto bundles = vri::bundleSteps(plan, all, prices, 60);
    CHECK(bundles[0].seconds == doctest::Approx(3.0));
    CHECK(bundles[0].priced);
    CHECK(!bundles[2].priced);
}

TEST_CASE("jobResources: threads, memory from the image size, time from the price") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a", "render", 1000 * 1000, 3), planStep("b", "render", 10 * 10),
                  planStep("c", "diff")};
    const vri::JobResources a = vri::jobResources(plan, {{0}, 90, true}, 2);
    CHECK(a.cpus == 3);
    CHECK(a.memoryMiB == 256 + 62);  // 64 bytes a pixel: 64e6 bytes, 61.04 MiB, rounded up with the 256
    REQUIRE(a.minutes);
    CHECK(*a.minutes == 15);  // (3 * 90 + 600) / 60 = 14.5, rounded up
    CHECK(vri::jobResources(plan, {{1}, 0, false}, 2).cpus == 2);
    CHECK(!vri::jobResources(plan, {{1}, 0, false}, 2).minutes);
    CHECK(vri::jobResources(plan, {{2}, 1, true}, 2).cpus == 1);
    CHECK(vri::jobResources(plan, {{1, 2, 0}, 1, true}, 2).cpus == 3);  // the bundle's largest
    CHECK(vri::jobName(plan, {{1, 2}, 1, true}) == "vri:exp:b+1");
    CHECK(vri::jobName(plan, {{0}, 1, true}) == "vri:exp:a");
    plan.steps.push_back(planStep("d", "render", 0, 0));
    CHECK(vri::jobResources(plan, {{3}, 0, false}, 4).cpus == 4);  // 0, all cores: the default
}

TEST_CASE("jobResources: a site profile's kinds replace the estimates where they set them") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a", "render", 1000 * 1000, 3), planStep("b", "diff"), planStep("c", "table"),
                  planStep("d", "render", 100)};
    const std::map<std::string, vri::StepKindResources> kinds{{"render", {8, 4096, 120}}, {"diff", {{}, 700, 5}}};
    const vri::JobResources a = vri::jobResources(plan, {{0}, 90, true}, 2, kinds);
    CHECK(a.cpus == 3);  // its own --threads: no profile changes what it runs on
    CHECK(vri::jobResources(plan, {{3}, 1, true}, 2, kinds).cpus == 8);
    CHECK(a.memoryMiB == 4096);
    CHECK(a.minutes == 120);
    const vri::JobResources b = vri::jobResources(plan, {{1}, 1, true}, 2, kinds);
    CHECK(b.cpus == 1);  // the estimate, where the kind sets none
    CHECK(b.memoryMiB == 700);
    CHECK(b.minutes == 5);
    CHECK(vri::jobResources(plan, {{0, 1}, 91, true}, 2, kinds).minutes == 125);  // every kind timed: the sum
    CHECK(vri::jobResources(plan, {{1, 2}, 2, true}, 2, kinds).minutes == 11);    // the table's: the estimate
    CHECK(vri::jobResources(plan, {{1, 2}, 2, true}, 2, kinds).memoryMiB == 700);
}

TEST_CASE("jobResources: a brick whose bytes the planner counted asks 1.5 times them, not its file's share") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a.brick-0-0-0", "render", 1920 * 1080)};
    plan.steps[0].volumeParts = 8;
    plan.steps[0].volumeBytes = std::uint64_t(1) << 30;  // a 1024^3 uint8 brick (of a 2048^3 volume)
    // 256 MiB + 1.5 GiB + 64 bytes a pixel (126.6 MiB), rounded up.
    CHECK(vri::jobResources(plan, {{0}, 1, true}, 2).memoryMiB == 256 + 1536 + 127);
}

TEST_CASE("jobResources: a whole volume whose bytes the planner counted asks twice them, not 8 times its files") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a", "render", 1920 * 1080)};
    plan.steps[0].volumeBytes = std::uint64_t(8) << 30;  // a 2048^3 uint8 volume, which peaked at 10.6 GiB
    // 256 MiB + 16 GiB + 64 bytes a pixel (126.6 MiB), rounded up.
    CHECK(vri::jobResources(plan, {{0}, 1, true}, 2).memoryMiB == 256 + 16384 + 127);
}

TEST_CASE("jobResources: a renderer of someone else's asks at least 2 GiB, unless the profile's outside kind says") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a", "command", 40 * 30), planStep("b", "command", 40 * 30)};
    plan.steps[0].tool = "vri-outside";
    plan.steps[1].tool = "vri-verify";
    for (std::size_t i : {0, 1}) {
        CHECK(vri::slurmStepKind(plan.steps[i]) == "outside");
        CHECK(vri::jobResources(plan, {{i}, 1, true}, 2).memoryMiB == 2048);
    }
    const std::map<std::string, vri::StepKindResources> kinds{{"outside", {{}, 6144, {}}}};
    CHECK(vri::jobResources(plan, {{0}, 1, true}, 2, kinds).memoryMiB == 6144);
}

TEST_CASE("parseSqueue reads squeue's fields and refuses what is not a job line") {
    const auto jobs = vri::parseSqueue(
        "12|COMPLETED by 0|node1|None|0|\n"
        "13|FAILED|node2|NonZeroExitCode|0|\n"
        "14|CANCELLED||DependencyNeverSatisfied|0|\n"
        "15_3|RUNNING|node[1-2]|None|0|\n"
        "16|PENDING||BeginTime|2     |\n"
        "\n");
    REQUIRE(jobs.size() == 5);
    CHECK(jobs.at("12").state == "COMPLETED");
    CHECK(jobs.at("12").node == "node1");
    CHECK(jobs.at("13").reason == "NonZeroExitCode");
    CHECK(jobs.at("14").state == "CANCELLED");
    CHECK(jobs.at("14").node.empty());
    CHECK(jobs.at("14").reason == "DependencyNeverSatisfied");
    CHECK(jobs.at("15_3").node == "node[1-2]");
    CHECK(jobs.at("15_3").restarts == 0);
    CHECK(jobs.at("16").restarts == 2);  // requeued twice
    CHECK_THROWS_AS(vri::parseSqueue("12|COMPLETED|n\n"), vri::Error);
    CHECK_THROWS_AS(vri::parseSqueue("12|COMPLETED|n|None|\n"), vri::Error);  // the four fields of an older format
    CHECK_THROWS_WITH_AS(vri::parseSqueue("12|PENDING||BeginTime|-1|\n"), doctest::Contains("restart count '-1'"),
                         vri::Error);
    CHECK_THROWS_AS(vri::parseSqueue("12|PENDING||BeginTime|123456|\n"), vri::Error);
    CHECK_THROWS_AS(vri::parseSqueue("squeue: warning: something\n"), vri::Error);
    CHECK_THROWS_AS(vri::parseSqueue("|RUNNING|n|None|0|\n"), vri::Error);
    // A line of 50 MB becomes a message of a few hundred bytes (issue 48, class 6).
    try {
        vri::parseSqueue(std::string(50 << 20, 'x') + "\n");
        FAIL("a 50 MB line was read as a job");
    } catch (const vri::Error& e) {
        CHECK(std::string(e.what()).size() < 400);
        CHECK(std::string(e.what()).ends_with("... (52428600 more bytes)"));
    }
    CHECK(vri::isFinalJobState("TIMEOUT"));
    CHECK(vri::isFinalJobState("PREEMPTED"));
    CHECK(!vri::isFinalJobState("COMPLETING"));
    CHECK(!vri::isFinalJobState("PENDING"));
    CHECK(vri::isFinalJobState("REVOKED"));
    CHECK(vri::isFinalJobState("SPECIAL_EXIT"));
    CHECK_THROWS_WITH_AS(vri::isFinalJobState("FLOATING"), doctest::Contains("state 'FLOATING', which vri-run does not know"),
                         vri::Error);
}

TEST_CASE("checkSiteSbatchOption passes on the allowed long options only, as sbatch would read them") {
    for (const char* ok : {"--qos=long", "--mem=0", "--exclusive", "--exclusive=user", "--partition=short",
                           "--time=10:00", "--comment=a b", "--requeue"})
        CHECK_NOTHROW(vri::checkSiteSbatchOption(ok, "--slurm-arg"));
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("--dependency=afterok:1", "--slurm-arg"),
                         doctest::Contains("--slurm-arg: '--dependency=afterok:1': vri-run sets --dependency itself"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("--depend=afterany:2", "--slurm-arg"),
                         doctest::Contains("vri-run sets --dependency itself"), vri::Error);
    // Short options, alone or bundled: sbatch reads -vo<path> as -v -o <path>.
    for (const char* bundle : {"-o/tmp/x", "-vo/tmp/x", "-pshort", "-Mother", "-v"})
        CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption(bundle, "VRI_SLURM_ARGS"),
                             doctest::Contains("short options are refused"), vri::Error);
    // A value-less option that takes one would take the next word, the job script, as its value.
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("--comment", "--slurm-arg"),
                         doctest::Contains("needs its value in the same word (--comment=VALUE)"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("--qos=", "--slurm-arg"), doctest::Contains("needs its value"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("--requeue=1", "--slurm-arg"), doctest::Contains("takes no value"),
                         vri::Error);
    // Abbreviations and anything not on the list.
    for (const char* other : {"--acc=x", "--export=ALL", "--hold", "--array=1-3", "--open-mode=append", "--wrap=true"})
        CHECK_THROWS_AS(vri::checkSiteSbatchOption(other, "--slurm-arg"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("--export=ALL", "--slurm-arg"),
                         doctest::Contains("is not among the sbatch options vri-run passes on (--account, --qos"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption("script.sh", "--slurm-arg"),
                         doctest::Contains("is not an sbatch option"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::checkSiteSbatchOption(std::string(100000, '-'), "--slurm-arg"),
                         doctest::Contains("..."), vri::Error);
}

TEST_CASE("parseSbatchJobId takes --parsable's id, with or without the cluster") {
    CHECK(vri::parseSbatchJobId("42\n") == "42");
    CHECK(vri::parseSbatchJobId("sbatch: warning: something\n43;cluster\n") == "43");
    CHECK(vri::parseSbatchJobId("4294967295\n") == "4294967295");
    CHECK_THROWS_WITH_AS(vri::parseSbatchJobId("12345678901234567890123\n"),
                         doctest::Contains("sbatch printed a job id vri-run cannot use: 12345678901234567890123"), vri::Error);
    CHECK_THROWS_AS(vri::parseSbatchJobId("4294967296\n"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::parseSbatchJobId("sbatch: error: Batch job submission failed\n"),
                         doctest::Contains("sbatch: error: Batch job submission failed"), vri::Error);
}

TEST_CASE("memoryLimitKill finds slurmstepd's line in a job's output, and nothing in a job's own words") {
    // As Slurm 22.05's jobacct_gather (OverMemoryKill) wrote it on the test cluster.
    const std::string killed =
        "vri-render: progress ...\n"
        "slurmstepd-vri-test-node: error: StepId=3.batch exceeded memory limit (77053952 > "
        "16777216), being killed\n"
        "slurmstepd-vri-test-node: error: Exceeded job memory limit\n"
        "slurmstepd-vri-test-node: error: *** JOB 3 ON vri-test-node CANCELLED AT "
        "2026-12-07T08:27:19 ***\n";
    CHECK(vri::memoryLimitKill(killed) == "StepId=3.batch exceeded memory limit (77053952 > 16777216)");
    CHECK_FALSE(vri::memoryLimitKill("vri-render: error: exceeded memory limit (a tool's own words)\n"));
    CHECK_FALSE(vri::memoryLimitKill("slurmstepd: error: StepId=3.batch exceeded memory limit (unclosed\n"));
    CHECK_FALSE(vri::memoryLimitKill(""));
}

TEST_CASE("parseUnendedIn: the jobs not ended in one working directory, whatever its name holds") {
    const std::string out = "12|RUNNING|/r/exp/.steps/slurm\n"
                            "13|COMPLETED|/r/exp/.steps/slurm\n"
                            "14|PENDING|/r/exp/.steps/slurm/deeper\n"
                            "15|COMPLETING|/r/a|b/.steps/slurm          \n"
                            "16|PENDING|/r/exp/.steps/slurm\n"
                            "not a job line\n";
    CHECK(vri::parseUnendedIn(out, "/r/exp/.steps/slurm") == std::vector<std::string>{"12", "16"});
    CHECK(vri::parseUnendedIn(out, "/r/a|b/.steps/slurm") == std::vector<std::string>{"15"});
    CHECK(vri::parseUnendedIn(out, "/elsewhere").empty());
}

TEST_CASE("bundleSteps keeps the tiles of one render in jobs of their own, priced or not") {
    vri::Plan plan{"/r/exp", "/r", {}, {}};
    plan.steps = {planStep("a.tile-1", "render"), planStep("a.tile-2", "render"), planStep("a", "render"),
                  planStep("d", "diff")};
    plan.steps[0].parameters = {{"region", "0,0,8,2"}};
    plan.steps[1].parameters = {{"region", "0,2,8,2"}};
    const std::vector<std::optional<double>> prices{1.0, 1.0, 0.5, 0.5};
    CHECK(stepsOf(vri::bundleSteps(plan, {0, 1, 2, 3}, prices, 60)) ==
          std::vector<std::vector<std::size_t>>{{0}, {1}, {2, 3}});
}
