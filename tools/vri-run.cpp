// vri-run: runs experiment files as graphs of small tool invocations, with caching and provenance.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/cli.h"
#include "libvri/core/voxel_loads.h"
#include "libvri/experiment/datasets.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_reproduce.h"
#include "libvri/experiment/experiment_run.h"
#include "libvri/experiment/experiment_spec.h"
#include "libvri/experiment/gallery.h"
#include "libvri/experiment/results_viewer.h"
#include "libvri/experiment/manifest.h"
#include "libvri/experiment/new_study.h"
#include "libvri/experiment/plan_waves.h"
#include "libvri/experiment/slurm_commands.h"
#include "libvri/experiment/slurm_executor.h"
#include "libvri/experiment/slurm_profile.h"
#include "libvri/experiment/slurm_node.h"
#include "libvri/experiment/step_cache.h"
#include "libvri/experiment/step_costs.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/process.h"
#include "libvri/util/folder_lock.h"
#include "libvri/util/json_file.h"
#include "libvri/util/stale_temp_files.h"

namespace fs = std::filesystem;

namespace {

constexpr const char* kTool = "vri-run";

struct Options {
    std::vector<std::string> experiments;
    bool quick = false, quiet = false, dryRun = false, estimate = false, force = false, record = false, check = false, allowDirty = false;
    std::string results, committed = "results", gallery;
    int jobs = 1;
    std::string executor = "local";
    std::string slurmPartition, slurmAccount;
    std::vector<std::string> slurmArguments;
    double slurmBundle = 60, slurmPoll = 1, slurmMaxPending = 0, slurmMaxOutage = 120;
    int slurmRetries = 0;
    int slurmMaxJobs = 0;
    int slurmCpus = 2;
    bool slurmCpusGiven = false;       // on the command line, over a site profile's
    std::string nodeSteps, nodeCheck;  // inside a Slurm job (hidden)
    std::string newStudy;
};

// The environment variable a site sets its sbatch options in (README "On a cluster").
constexpr const char* kSiteSlurmArguments = "VRI_SLURM_ARGS";

// sbatch's options for the steps' jobs: the site profile's (slurm_profile.h), the site's (VRI_SLURM_ARGS,
// words separated by blanks), then the command line's, so that the command line wins.
vri::SlurmOptions slurmOptions(const Options& options) {
    vri::SlurmOptions slurm;
    std::optional<int> profileCpus;
    if (const std::optional<fs::path> path = vri::slurmProfilePath()) {
        vri::SlurmProfile profile = vri::readSlurmProfile(*path);
        slurm.sbatchArguments = std::move(profile.sbatchArguments);
        slurm.kinds = std::move(profile.kinds);
        profileCpus = profile.cpus;
    }
    if (const char* site = std::getenv(kSiteSlurmArguments)) {
        std::istringstream words(site);
        for (std::string word; words >> word;) {
            vri::checkSiteSbatchOption(word, kSiteSlurmArguments);
            slurm.sbatchArguments.push_back(word);
        }
    }
    if (!options.slurmPartition.empty()) slurm.sbatchArguments.push_back("--partition=" + options.slurmPartition);
    if (!options.slurmAccount.empty()) slurm.sbatchArguments.push_back("--account=" + options.slurmAccount);
    for (const std::string& word : options.slurmArguments) {
        vri::checkSiteSbatchOption(word, "--slurm-arg");
        slurm.sbatchArguments.push_back(word);
    }
    slurm.bundleSeconds = options.slurmBundle;
    slurm.cpus = options.slurmCpusGiven || !profileCpus ? options.slurmCpus : *profileCpus;
    slurm.pollSeconds = options.slurmPoll;
    slurm.maxPendingSeconds = options.slurmMaxPending;
    slurm.maxOutageSeconds = options.slurmMaxOutage;
    slurm.retries = options.slurmRetries;
    slurm.maxJobs = static_cast<std::size_t>(options.slurmMaxJobs);
    return slurm;
}

// Compares (--check) or records (--record) the reproduce: numbers of a quick run; false on a mismatch.
bool reproduce(const Options& options, const vri::Experiment& experiment, const vri::Plan& plan) {
    if (experiment.reproduce.empty()) return true;
    const nlohmann::json measured = vri::measureReproduceMetrics(experiment, plan);
    const fs::path committed = fs::path(options.committed) / experiment.name / "reproduce.json";
    if (options.record) {
        vri::writeTextFile(committed, measured.dump(2) + "\n");
        std::cerr << kTool << ": recorded " << committed.string() << '\n';
        return true;
    }
    if (!fs::is_regular_file(committed))
        throw vri::Error(committed.string() + ": no such file (record it with vri-run --quick --record)");
    const std::vector<std::string> problems = vri::readingJsonOf(
        committed, [&] { return vri::reproduceMismatches(experiment, measured, vri::readJsonFile(committed)); });
    for (const std::string& p : problems) std::cerr << kTool << ": " << experiment.name << ": " << p << '\n';
    if (problems.empty()) std::cerr << kTool << ": " << experiment.name << ": reproduced (" << committed.string() << ")\n";
    return problems.empty();
}

// Committed results come from a commit: writing into a work tree's results/ while its tracked files
// differ from HEAD is refused unless --allow-dirty (the manifest then says modified_files: true).
void requireCleanTree(const Options& options, const vri::Experiment& experiment, const fs::path& resultsRoot) {
    if (options.allowDirty) return;
    const std::optional<vri::WorkTree> tree = vri::workTreeOf(experiment.source);
    if (!tree || !tree->modified) return;
    const auto resolved = [](const fs::path& p) {  // absolute, links resolved, without a trailing '/'
        const fs::path q = fs::weakly_canonical(fs::absolute(p));
        return q.has_filename() ? q : q.parent_path();
    };
    if (resolved(resultsRoot) != resolved(tree->top / "results")) return;
    throw vri::Error(resultsRoot.string() + ": tracked files of " + tree->top.string() + " differ from commit " +
                     tree->commit.substr(0, 12) + "; commit them, or pass --allow-dirty");
}

// --estimate: what each experiment costs from nothing, priced from the last manifest in the results root,
// as a Markdown table on stdout (experiments/README.md, "What an experiment costs").
void printEstimate(const std::vector<std::pair<std::string, vri::CostEstimate>>& estimates) {
    double total = 0;
    std::size_t unpriced = 0;
    for (const auto& [name, e] : estimates) {
        total += e.seconds;
        unpriced += e.unpriced;
    }
    const auto number = [](double value) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f", value);
        return std::string(text);
    };
    std::cout << "| experiment | steps | unpriced | seconds | share | render | diff | other |\n"
                 "|---|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const auto& [name, e] : estimates) {
        const auto kind = [&](const std::string& k) { return e.byKind.contains(k) ? e.byKind.at(k) : 0.0; };
        std::cout << "| " << name << (e.hasManifest ? "" : " (no manifest)") << " | " << e.priced + e.unpriced << " | "
                  << e.unpriced << " | " << number(e.seconds) << " | " << number(total > 0 ? 100 * e.seconds / total : 0)
                  << " % | " << number(kind("render")) << " | " << number(kind("diff")) << " | "
                  << number(e.seconds - kind("render") - kind("diff")) << " |\n";
    }
    std::cout << "\nFrom nothing, one step at a time: " << (unpriced ? "at least " : "") << vri::secondsText(total)
              << ".\n";
    if (unpriced)
        std::cout << unpriced << " steps are new or changed since their experiment's last manifest and have no price.\n";
}

// Left by a vri-run or a step killed with kill -9 mid-write (a cached step is not rewritten, so its
// writer never cleans up); only the temporary names of the files this plan writes, so that a user's
// look-alike file stays, and a step of a killed vri-run that still runs keeps its own.
void removeStaleTempFiles(const vri::Plan& plan) {
    std::vector<fs::path> targets{plan.resultsDir / "manifest.json"};
    for (const vri::Step& step : plan.steps) {
        targets.insert(targets.end(), step.outputs.begin(), step.outputs.end());
        targets.push_back(vri::recordPath(plan, step));
        // A figure's gnuplot log, the temporary file of a NAME.log never kept (plot_draw.cpp).
        for (const fs::path& out : step.outputs)
            if (step.kind == "figure" && out.extension() == ".png") targets.push_back(fs::path(out).replace_extension(".log"));
    }
    for (const fs::path& target : targets)
        for (const fs::path& stale : vri::removeStaleTempFiles(target))
            std::cerr << kTool << ": removed " << plan.commandPath(stale) << ", a temporary file of a process that is gone\n";
}

// Before a plan's steps, on either executor: the clean tree --record asks for, the results folder locked until
// its manifest is written, stale temporary files gone, and the last run's wall times (which price the Slurm
// jobs and give the progress line its ETA) read while its manifest is still there. The caller removes the
// manifest once nothing can fail before the steps run; it is written again only once every step has succeeded.
struct StartedPlan {
    std::unique_ptr<vri::FolderLock> lock;
    std::vector<std::optional<double>> prices;
};
StartedPlan startPlan(const Options& options, const vri::Experiment& experiment, const vri::Plan& plan,
                      const fs::path& resultsRoot) {
    requireCleanTree(options, experiment, resultsRoot);
    StartedPlan started{std::make_unique<vri::FolderLock>(plan.commandPath(plan.resultsDir)), {}};
    removeStaleTempFiles(plan);
    started.prices = vri::stepPrices(plan, plan.resultsDir / "manifest.json");
    return started;
}

// After a plan's steps: its manifest, the summary line and, for --record or --check, the reproduce:
// numbers; false on a reproduce mismatch.
bool finish(const Options& options, const vri::Experiment& experiment, const vri::Plan& plan,
            const std::vector<vri::StepOutcome>& outcomes, const fs::path& toolDir, vri::FileHasher& hasher,
            std::chrono::steady_clock::time_point start) {
    vri::writeManifest(experiment, plan, outcomes, toolDir, hasher);
    std::size_t ran = 0, cached = 0;
    for (const vri::StepOutcome& o : outcomes) {
        ran += o.state == vri::StepOutcome::State::Ran;
        cached += o.state == vri::StepOutcome::State::Cached;
    }
    if (!options.quiet)
        std::cerr << kTool << ": " << experiment.name << ": " << plan.steps.size() << " steps, " << ran << " ran, " << cached
              << " cached, in " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s -> " << plan.commandPath(plan.resultsDir) << '\n';
    return !(options.record || options.check) || reproduce(options, experiment, plan);
}

// --executor slurm: every experiment's jobs are submitted before any is waited for, so that the cluster
// runs the files side by side. A manifest goes only once the node check has passed, and is written
// again for every experiment whose steps all succeeded; the first failure is the error, with how many
// experiments failed. False on a reproduce mismatch.
bool runOnSlurm(const Options& options, const std::vector<vri::Experiment>& experiments,
                const std::vector<vri::Plan>& plans, const vri::RunOptions& runOptions, vri::FileHasher& hasher,
                const fs::path& resultsRoot) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<StartedPlan> started;  // their locks held until the manifests are written
    vri::SlurmBatch batch(runOptions, hasher);
    std::size_t toRun = 0;
    for (std::size_t e = 0; e < plans.size(); ++e) {
        started.push_back(startPlan(options, experiments[e], plans[e], resultsRoot));
        toRun += batch.add(plans[e], started.back().prices);
    }
    if (toRun > 0) batch.checkNodes();
    for (const vri::Plan& plan : plans) fs::remove(plan.resultsDir / "manifest.json");
    if (toRun > 0) batch.run();
    bool reproduced = true;
    std::optional<std::string> firstFailure;
    bool firstFailureDetailed = false;  // a failed step's DetailedError: its first line, then its command and output
    std::size_t failures = 0;
    for (std::size_t e = 0; e < plans.size(); ++e) {
        try {
            reproduced = finish(options, experiments[e], plans[e], batch.result(e), runOptions.toolDir, hasher, start) &&
                         reproduced;
        } catch (const vri::Error& error) {
            if (!firstFailure) {
                firstFailure = experiments[e].name + ": " + error.what();
                firstFailureDetailed = dynamic_cast<const vri::DetailedError*>(&error) != nullptr;
            }
            ++failures;
        }
    }
    if (!firstFailure) return reproduced;
    if (failures > 1) {  // said on the first line, before the failed step's details
        const std::size_t lineEnd = std::min(firstFailure->find('\n'), firstFailure->size());
        firstFailure->insert(lineEnd, " (and " + std::to_string(failures - 1) +
                                          " more experiments failed: see their .steps/ logs)");
    }
    if (firstFailureDetailed) throw vri::DetailedError(*firstFailure);
    throw vri::Error(*firstFailure);
}

int run(const Options& options) {
    if ((options.record || options.check) && !options.quick)
        throw vri::Error("--record and --check apply to quick runs (add --quick)");
    const fs::path toolDir = vri::thisProgramFolder();
    const fs::path resultsRoot = !options.results.empty() ? fs::path(options.results)
                                 : options.quick          ? fs::path("build/experiments-quick")
                                                          : fs::path("results");
    bool reproduced = true;
    std::vector<std::pair<std::string, vri::CostEstimate>> estimates;
    std::vector<vri::Experiment> experiments;
    std::vector<vri::Plan> plans;
    for (const std::string& file : options.experiments) {
        if (vri::isDatasetCatalog(file)) {  // beside the experiments, so experiments/*.yaml names it
            std::cerr << kTool << ": " << file << " is the dataset catalog, not an experiment: skipped\n";
            continue;
        }
        experiments.push_back(vri::loadExperiment(file, options.quick));
        if (!options.quick)  // quick runs are for checking, not for reading times
            for (const std::string& warning : experiments.back().warnings)
                std::cerr << kTool << ": warning: " << experiments.back().name << ": " << warning << '\n';
        // The name is the results folder: a second experiment of that name would replace the first's
        // manifest and reuse its runs' files.
        for (std::size_t e = 0; e + 1 < experiments.size(); ++e)
            if (experiments[e].name == experiments.back().name)
                throw vri::Error(file + ": name '" + experiments.back().name + "' is also " +
                                 experiments[e].source.string() + "'s (both would write " +
                                 (resultsRoot / experiments.back().name).string() + "/)");
        plans.push_back(vri::planExperiment(experiments.back(), resultsRoot / experiments.back().name, fs::current_path()));
    }
    vri::RunOptions runOptions{toolDir, options.jobs, options.force, options.quiet, vri::Executor::Local, {}, {}};
    if (options.executor == "slurm") {
        runOptions.executor = vri::Executor::Slurm;
        runOptions.slurm = slurmOptions(options);
        // The jobs' folders (--chdir) are under the results folder, and Slurm reads '%' in them as a pattern
        // (%j: the job id): the jobs would then work in another folder and fail, blaming the file system.
        for (const vri::Plan& plan : plans)
            if (const std::string folder = fs::absolute(plan.resultsDir).string(); folder.find('%') != std::string::npos)
                throw vri::Error("--executor slurm: the results folder " + folder + " holds a '%', which Slurm reads as "
                                 "a pattern in the jobs' folders (%j: the job id); choose --results without '%'");
    }
    // --check runs what its numbers need, and what another experiment of the run reads.
    for (std::size_t e = 0; options.check && e < plans.size(); ++e) {
        std::set<fs::path> readElsewhere;
        for (std::size_t other = 0; other < plans.size(); ++other)
            for (const vri::Step& step : plans[other].steps)
                if (other != e) readElsewhere.insert(step.inputs.begin(), step.inputs.end());
        plans[e] = vri::checkedPart(experiments[e], plans[e], readElsewhere);
    }
    // An experiment that reads another's results runs after it (plan_waves.h).
    std::vector<std::string> names;
    for (const vri::Experiment& experiment : experiments) names.push_back(experiment.source.string());
    const std::vector<std::vector<std::size_t>> waves = vri::planWaves(plans, names);
    vri::FileHasher hasher;
    const bool onSlurm = !options.estimate && !options.dryRun && runOptions.executor == vri::Executor::Slurm;
    // On Slurm each wave's jobs are submitted once the wave before has finished (its outputs are the next's inputs).
    for (std::size_t w = 0; onSlurm && w < waves.size(); ++w) {
        std::vector<vri::Experiment> waveExperiments;
        std::vector<vri::Plan> wavePlans;
        for (std::size_t e : waves[w]) {
            waveExperiments.push_back(experiments[e]);
            wavePlans.push_back(plans[e]);
        }
        reproduced = runOnSlurm(options, waveExperiments, wavePlans, runOptions, hasher, resultsRoot) && reproduced;
    }
    // --dry-run --executor slurm: the jobs and their sbatch commands, wave by wave; nothing submitted or written.
    const bool describeSlurm = options.dryRun && runOptions.executor == vri::Executor::Slurm;
    for (std::size_t w = 0; describeSlurm && w < waves.size(); ++w) {
        if (waves.size() > 1)
            std::cout << "# wave " << w + 1 << " of " << waves.size()
                      << (w == 0 ? "" : ": submitted once the wave before has ended (it reads that wave's outputs)")
                      << '\n';
        vri::RunOptions dry = runOptions;
        dry.slurm.dryRun = true;
        vri::SlurmBatch batch(dry, hasher);
        for (std::size_t e : waves[w])
            batch.add(plans[e], vri::stepPrices(plans[e], plans[e].resultsDir / "manifest.json"));
        batch.describe(std::cout);
    }
    std::vector<std::size_t> order;
    for (const std::vector<std::size_t>& wave : waves) order.insert(order.end(), wave.begin(), wave.end());
    for (std::size_t k = 0; !onSlurm && !describeSlurm && k < order.size(); ++k) {
        const std::size_t e = order[k];
        const vri::Experiment& experiment = experiments[e];
        const vri::Plan& plan = plans[e];
        if (options.estimate) {
            estimates.emplace_back(experiment.name, vri::estimateCost(plan, plan.resultsDir / "manifest.json"));
            continue;
        }
        if (options.dryRun) {
            for (const vri::Step& step : plan.steps)
                std::cout << vri::shellCommand(vri::commandWords(plan, step, toolDir)) << '\n';
            continue;
        }
        const auto start = std::chrono::steady_clock::now();
        const StartedPlan started = startPlan(options, experiment, plan, resultsRoot);
        vri::RunOptions planOptions = runOptions;
        planOptions.prices = started.prices;
        fs::remove(plan.resultsDir / "manifest.json");
        const std::vector<vri::StepOutcome> outcomes = vri::runPlan(plan, planOptions, hasher);
        reproduced = finish(options, experiment, plan, outcomes, toolDir, hasher, start) && reproduced;
    }
    if (options.estimate) printEstimate(estimates);
    if (!options.gallery.empty()) {
        const std::vector<vri::GalleryEntry> entries = vri::galleryEntries(options.gallery);
        for (const vri::GalleryPage& page : vri::galleryPages(entries, vri::scriptPages(options.gallery))) {
            const fs::path file = fs::path(options.gallery) / page.name;
            vri::writeTextFile(file, page.text);
            std::cerr << kTool << ": wrote " << file.string() << '\n';
        }
        for (const vri::GalleryPage& page : vri::viewerPages(entries))
            vri::writeTextFile(fs::path(options.gallery) / page.name, page.text);
        const std::size_t floats = vri::writeViewerFloats(entries);
        std::cerr << kTool << ": wrote the viewer, " << (fs::path(options.gallery) / "index.html").string()
                  << ", and the float data of " << floats << (floats == 1 ? " render" : " renders")
                  << " from their EXRs\n";
    }
    return reproduced ? vri::kExitOk : vri::kExitError;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Runs experiment files: expands each into the exact command lines of the small tools (vri-render, "
                 "vri-diff, vri-tabulate, vri-plot, and any vri tool under commands:), runs those whose inputs changed "
                 "since their last successful run, and writes results/<experiment>/ with a manifest.json of commands, "
                 "digests, build, machine and times.",
                 kTool};
    app.add_option("EXPERIMENT", options.experiments, "experiment YAML files (schema: experiments/README.md)");
    app.add_flag("--quick", options.quick, "apply each file's quick: overrides (small sizes, fewer sweep values)");
    app.add_flag(
        "--dry-run", options.dryRun,
        "print the commands, one per line, runnable from here (with --executor slurm: the jobs, their steps and "
        "sbatch commands); run nothing");
    app.add_flag("--estimate", options.estimate,
                 "print what each experiment costs from nothing, its steps priced by the wall times of the last "
                 "manifest in the results root; run nothing")
        ->excludes("--dry-run");
    app.add_flag("-q,--quiet", options.quiet,
                 "no progress: without a terminal a line per started and finished step, on one a live line with "
                 "an ETA; and no summary line");
    app.add_flag("--force", options.force, "run every step even when its cache record vouches for it");
    app.add_option("--results", options.results, "results root (default: results, with --quick build/experiments-quick)");
    app.add_flag("--allow-dirty", options.allowDirty,
                 "write into the work tree's results/ even when its tracked files differ from the commit");
    app.add_option("--jobs", options.jobs,
                   "steps run at once (1 to 64); an untiled, unbricked render or a command runs alone, so that its "
                   "time is its own")
        ->check(vri::integerRange(1, 64))
        ->capture_default_str();
    app.add_option("--executor", options.executor,
                   "where steps run: local (child processes, up to --jobs at once) or slurm (a batch job per step or "
                   "bundle of small steps, ordered by the cluster; README \"On a cluster\")")
        ->check(CLI::IsMember({"local", "slurm"}))
        ->capture_default_str();
    app.add_option("--slurm-partition", options.slurmPartition, "sbatch --partition for every job");
    app.add_option("--slurm-account", options.slurmAccount, "sbatch --account for every job");
    app.add_option("--slurm-arg", options.slurmArguments,
                   "one more sbatch option for every job, as one word (repeatable): --slurm-arg=--qos=long; after "
                   "vri-run's own and $VRI_SLURM_ARGS, so it wins")
        ->allow_extra_args(false);
    app.add_option("--slurm-bundle", options.slurmBundle,
                   "steps whose last run took less than SECONDS share jobs of about SECONDS; 0: a job per step")
        ->check(vri::numberRange(0.0, 86400.0))
        ->capture_default_str();
    app.add_option("--slurm-cpus", options.slurmCpus, "CPUs a render or command asks for when it sets no --threads (1 to 1024)")
        ->check(vri::integerRange(1, 1024))
        ->capture_default_str();
    app.add_option("--slurm-poll", options.slurmPoll,
                   "seconds between two looks at the jobs (squeue) while their states change, 0.1 to 600 (up to 10 s "
                   "while none changes)")
        ->check(vri::numberRange(0.1, 600.0))
        ->capture_default_str();
    app.add_option("--slurm-max-jobs", options.slurmMaxJobs,
                   "at most N jobs in the queue at once, the next submitted as one ends (0: every job at once)")
        ->check(vri::integerRange(0, 100000))
        ->capture_default_str();
    app.add_option("--slurm-max-pending", options.slurmMaxPending,
                   "give up (cancelling every job) once no job has run for SECONDS while some pend for the cluster "
                   "(a partition down, a drained node, a hold); 0: wait; a line says why they pend after a minute")
        ->check(vri::numberRange(0.0, 1e7))
        ->capture_default_str();
    app.add_option("--slurm-retries", options.slurmRetries,
                   "submit a job again up to N times when it ends NODE_FAIL, PREEMPTED, BOOT_FAIL or LAUNCH_FAILED, "
                   "TIMEOUT (its --time "
                   "doubled) or OUT_OF_MEMORY (its --mem doubled); 0 to 10")
        ->check(vri::integerRange(0, 10))
        ->capture_default_str();
    app.add_option("--slurm-max-outage", options.slurmMaxOutage,
                   "give up (cancelling every job) once squeue has failed for SECONDS in a row (a controller "
                   "restarting or out of reach); the jobs run on meanwhile; 0: at the first failure")
        ->check(vri::numberRange(0.0, 1e7))
        ->capture_default_str();
    app.add_option("--new", options.newStudy,
                   "write NAME.yaml, NAME-tf.yaml and NAME-plot.yaml: a commented study to start an own one from, "
                   "which runs as written (an analytic field; no data set); then vri-run NAME.yaml");
    app.add_option("--slurm-node-steps", options.nodeSteps)->group("");  // what a Slurm job runs (slurm_node.h)
    app.add_option("--slurm-node-check", options.nodeCheck)->group("");
    app.add_flag("--record", options.record, "with --quick: write the reproduce: numbers to COMMITTED/<experiment>/reproduce.json");
    app.add_flag("--check", options.check, "with --quick: run the steps the reproduce: numbers need (an experiment without them runs whole) and "
                 "compare the numbers with the committed ones; exit 1 on a mismatch")
        ->excludes("--record");
    app.add_option("--committed", options.committed, "the committed results root for --record and --check")
        ->capture_default_str();
    app.add_option("--gallery", options.gallery, "afterwards, write the gallery from DIR/*/manifest.json: DIR/README.md and the viewer, DIR/index.html");
    app.footer(R"(Steps are cached in <results>/<experiment>/.steps/: a step is skipped when its command, tool binary,
input files (or the steps that write them) and outputs are as when it last succeeded.
Tools are taken from the directory vri-run is in. One vri-run at a time works in an experiment's folder
(it holds <results>/<experiment>/.vri-run.lock): a second one exits 1 naming the process that holds it.
Writing into results/ of the git work tree that holds the experiment file is refused while its
tracked files differ from HEAD (--allow-dirty overrides; each manifest records the commit).
Temporary files (.NAME.tmp.PID.*) whose process is gone are removed first.
The sweeps of one file may expand to at most 10000 runs (counted before expanding, --dry-run included).

Examples:
  vri-run --new mystudy && vri-run mystudy.yaml                 # an own study: written, then run
  vri-run experiments/paper-a-fig4.yaml
  vri-run --dry-run experiments/paper-a-fig4.yaml > fig4.sh     # the commands, to rerun by hand
  vri-run --estimate experiments/*.yaml                         # what make experiments costs from nothing
  vri-run --quick --check experiments/paper-a-fig4.yaml         # the reproducibility check of make test
  vri-run --gallery results experiments/*.yaml                  # everything, then results/README.md
  vri-run --executor slurm --slurm-partition short experiments/convergence.yaml   # on a Slurm cluster

On Slurm (--executor slurm), before the first job of a run, one small job checks that the compute nodes see the
tools, the inputs and the results folder at the same paths; then every step of an experiment that must run
is submitted at once, ordered by the cluster
(--dependency=afterok). $VRI_SLURM_ARGS holds a site's sbatch options (blank-separated words). Ctrl-C or
SIGTERM cancels the submitted jobs. README "On a cluster" has the details.)");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;
    options.slurmCpusGiven = app.count("--slurm-cpus") > 0;
    return vri::guardedMain(kTool, [&] {
        if (!options.nodeSteps.empty()) return vri::runNodeSteps(options.nodeSteps);
        if (!options.nodeCheck.empty()) return vri::runNodeCheck(options.nodeCheck);
        if (app.count("--new") > 0 && options.newStudy.empty())
            throw vri::UsageError("--new: expected a study's name (NAME.yaml is written), got nothing");
        if (!options.newStudy.empty()) {
            if (!options.experiments.empty()) throw vri::UsageError("--new writes files and runs none: name no EXPERIMENT");
            for (const fs::path& file : vri::writeNewStudy(options.newStudy))
                std::cerr << kTool << ": wrote " << file.string() << '\n';
            return vri::kExitOk;
        }
        if (options.experiments.empty() && options.gallery.empty())
            throw vri::Error("nothing to do: name experiment files or --gallery DIR (see --help)");
        vri::requireUtf8Arguments(argc, argv);  // the steps' commands and the manifest name these files
        // Every render step would refuse a bad VRI_VOXEL_LOADS: once here instead, before any step. Not
        // VRI_SIMD_TARGET: a cluster's nodes may have targets this host lacks.
        vri::voxelLoads();
        return run(options);
    });
}
