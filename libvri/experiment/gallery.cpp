#include "libvri/experiment/gallery.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "libvri/experiment/caption_numbers.h"
#include "libvri/experiment/experiment_spec.h"  // isSafeName
#include "libvri/experiment/gallery_grid.h"
#include "libvri/experiment/step_costs.h"
#include "libvri/render/render_job.h"  // timingLoadOf
#include "libvri/util/file_text.h"
#include "libvri/util/json_file.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// "commit 0123456789ab" (12 digits, as git shows short ids), with "(tracked files modified)" when the
// tree was dirty: what the gallery says an experiment's results were made from.
std::string commitNote(const nlohmann::json& sourceTree) {
    const std::string commit = sourceTree.at("commit").get<std::string>();
    if (commit == "unknown") return "commit unknown";
    std::string note = "commit `" + commit.substr(0, 12) + "`";
    if (sourceTree.value("modified_files", false)) note += " (tracked files modified)";
    return note;
}

// A table's Markdown without the notes under its last row when an earlier table of the experiment had
// the same: a kind of table is explained once, not under each of its tables.
std::string withNewNotes(const std::string& table, std::set<std::string>& notesSeen) {
    const std::size_t lastRow = table.rfind("\n|");
    const std::size_t rowEnd = lastRow == std::string::npos ? std::string::npos : table.find('\n', lastRow + 1);
    if (rowEnd == std::string::npos) return table;
    const std::string notes = table.substr(rowEnd + 1);
    if (notes.find_first_not_of(" \n") == std::string::npos || notesSeen.insert(notes).second) return table;
    return table.substr(0, rowEnd + 1);
}

// One experiment's section: its heading, what the paper says, its datasets' notes, image grids, tables,
// figures, how ours agrees, and where it came from. `notedIn` names the section that explained each
// dataset that is not exact, so that later sections point there instead of repeating it.
std::string gallerySection(const fs::path& path, std::map<std::string, std::string>& notedIn) {
    std::ostringstream md;
    readingJsonOf(path, [&] {
        const nlohmann::json m = readJsonFile(path);
        const nlohmann::json& e = m.at("experiment");
        const std::string dir = path.parent_path().filename().string();
        md << "\n## " << e.at("title").get<std::string>() << "\n\n";
        const nlohmann::json& paper = e.at("paper");
        if (paper.at("paper") != "none")
            md << "**Paper " << paper.at("paper").get<std::string>() << ", " << paper.at("item").get<std::string>()
               << ":** " << paper.at("says").get<std::string>() << "\n\n";
        for (const nlohmann::json& d : m.at("datasets")) {
            const std::string dataset = d.at("dataset").get<std::string>();
            if (d.at("status") == "exact" || (notedIn.contains(dataset) && notedIn.at(dataset) == dir)) continue;
            md << "*Dataset " << dataset << " is " << d.at("status").get<std::string>();
            if (const auto first = notedIn.emplace(dataset, dir); first.second)
                md << ":* " << d.at("note").get<std::string>() << "\n\n";
            else
                md << "* (see " << first.first->second << ").\n\n";
        }
        const nlohmann::json& outputs = m.at("outputs");
        md << imageGrid(gridImages(outputs.at("images"), m.at("steps"), dir), "scene");
        md << imageGrid(gridImages(outputs.at("diff_images"), m.at("steps"), dir), "scene");
        if (const std::string caption = heatMapCaption(outputs.at("diff_images"), path.parent_path()); !caption.empty())
            md << "*" << caption << "*\n\n";
        std::set<std::string> notesSeen;
        for (const nlohmann::json& table : outputs.at("tables"))
            if (const auto text = tryReadFileText(path.parent_path() / table.at("file").get<std::string>());
                text && !text->empty())
                md << withNewNotes(*text, notesSeen) << "\n";
        if (const std::string caption = loadCaption(m.at("steps"), path.parent_path()); !caption.empty())
            md << "*" << caption << "*\n\n";
        // A figure is as wide as the page: one a line.
        for (const nlohmann::json& figure : outputs.at("figures"))
            md << "![" << figure.at("id").get<std::string>() << "](" << dir << "/"
               << figure.at("file").get<std::string>() << ")\n\n";
        if (!e.at("agreement").get<std::string>().empty())
            md << "**Ours against the paper:** "
               << fillCaptionNumbers(e.at("agreement").get<std::string>(), path.parent_path()) << "\n\n";
        md << "Experiment file `" << e.at("source").get<std::string>() << "`, " << commitNote(m.at("source_tree"))
           << ", manifest [" << dir << "/manifest.json](" << dir << "/manifest.json); from nothing its "
           << m.at("steps").size() << (m.at("steps").size() == 1 ? " step takes " : " steps take ")
           << secondsText(manifestSeconds(m)) << ".\n";
        if (m.contains("part"))  // a run of part of the experiment: its outputs are not all here
            md << "\n**Only part of the experiment ran here:** " << m.at("part").get<std::string>() << ".\n";
    });
    return md.str();
}

GalleryEntry galleryEntry(const fs::path& path) {
    return readingJsonOf(path, [&] {
        const nlohmann::json m = readJsonFile(path);
        const nlohmann::json& e = m.at("experiment");
        GalleryEntry entry{path,
                         path.parent_path().filename().string(),
                         e.at("title").get<std::string>(),
                         e.at("paper").at("paper").get<std::string>(),
                         e.at("paper").value("item", ""),
                         ""};
        // The verdict: the agreement's opening words, up to its first ':' or '.' ("Agrees", "Partly",
        // "Differs, as a CPU device must"); an own study has none to give.
        if (entry.paper != "none") {
            const std::string agreement = fillCaptionNumbers(e.at("agreement").get<std::string>(), path.parent_path());
            entry.verdict = agreement.substr(0, agreement.find_first_of(".:"));
            if (entry.verdict.size() > 60) entry.verdict = entry.verdict.substr(0, 57) + "...";
        }
        return entry;
    });
}

// Text with its runs of digits compared as numbers.
bool naturalLess(const std::string& a, const std::string& b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
            std::size_t ie = i, je = j;
            while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
            while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
            const std::string x = a.substr(i, ie - i), y = b.substr(j, je - j);
            if (x.size() != y.size()) return x.size() < y.size();
            if (x != y) return x < y;
            i = ie;
            j = je;
        } else {
            if (a[i] != b[j]) return a[i] < b[j];
            ++i;
            ++j;
        }
    }
    return a.size() - i < b.size() - j;
}

// GitHub's anchor of a heading: lower case, punctuation dropped but '-' and '_', blanks as '-'.
std::string headingAnchor(const std::string& heading) {
    std::string anchor;
    for (const char c : heading) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (std::isalnum(u) || c == '-' || c == '_' || u >= 0x80)
            anchor += static_cast<char>(std::tolower(u));
        else if (c == ' ')
            anchor += '-';
    }
    return anchor;
}

// A section longer than this many lines gets a page of its own, linked from the index.
constexpr std::size_t kLongSectionLines = 120;

}  // namespace

// The caption of an experiment's heat maps: what they show and each one's scale, read from the
// comparison's vri-diff JSON beside it (a diff image is named as its JSON: <comparison id>.png). Maps
// that share a scale (vri-diff --scale-over and --scale-from, `diff_scale: shared`) are listed together, the top
// once.
std::string heatMapCaption(const nlohmann::json& diffImages, const fs::path& dir) {
    std::vector<std::pair<std::string, std::string>> scales;  // ids, the top they share or have alone
    bool anySigned = false;
    for (const nlohmann::json& item : diffImages) {
        const std::string id = item.at("id").get<std::string>();
        const fs::path json = dir / (id + ".json");
        if (!fs::is_regular_file(json)) continue;
        const nlohmann::json diff = readJsonFile(json);
        if (!diff.contains("heat_map")) continue;  // results of a vri-diff that drew RGB on black
        char top[160];
        std::snprintf(top, sizeof top, "%.3g",
                      readingJsonOf(json, [&] { return diff.at("heat_map").at("top").get<double>(); }));
        if (diff.at("heat_map").value("scale", "linear") == "log")  // "0.99, log over 3 decades"
            std::snprintf(top + std::strlen(top), sizeof top - std::strlen(top), ", log over %d decades",
                          readingJsonOf(json, [&] { return diff.at("heat_map").at("decades").get<int>(); }));
        const std::string topFrom = diff.at("heat_map").value("top_from", "max");
        if (topFrom.starts_with("p"))  // "0.12, the 99th percentile of the errors"
            std::snprintf(top + std::strlen(top), sizeof top - std::strlen(top), ", the %sth percentile", topFrom.c_str() + 1);
        if (diff.at("heat_map").value("value", "") == "B - A per channel") {
            std::snprintf(top + std::strlen(top), sizeof top - std::strlen(top), ", signed per channel");
            anySigned = true;
        }
        const bool shared = diff.at("heat_map").contains("scale_over") || diff.at("heat_map").contains("scale_from");
        if (shared && !scales.empty() && scales.back().second == top + std::string(" (one scale)"))
            scales.back().first += ", " + id;
        else
            scales.emplace_back(id, top + std::string(shared ? " (one scale)" : ""));
    }
    if (scales.empty()) return "";
    std::ostringstream md;
    md << "Difference images: heat maps of the largest |run - reference| over the channels (alpha included), "
          "viridis from the bottom of the scale (dark blue, the colour bar's left end: 0, or on a log scale the top "
          "over 10^decades) to its top (yellow, its right end; larger errors in magenta), the bar numbered at "
          "quarters of it or at each decade";
    if (anySigned) md << "; a signed map shows run - reference per channel, blue below 0, red above";
    md << ". Top of the scale: ";
    for (std::size_t i = 0; i < scales.size(); ++i) md << (i ? "; " : "") << scales[i].first << " " << scales[i].second;
    md << ".";
    return md.str();
}

// The caption under an experiment's tables and charts when any of its renders was timed while other processes
// kept the cores busy (timing.load.overloaded in the run's stats, frame_timing.h): its seconds are inflated.
std::string loadCaption(const nlohmann::json& steps, const fs::path& dir) {
    std::vector<std::string> loaded;
    for (const nlohmann::json& step : steps) {
        if (step.value("kind", "") != "render") continue;
        const fs::path stats = dir / (step.at("id").get<std::string>() + ".json");
        if (!fs::is_regular_file(stats)) continue;
        const std::optional<TimingLoad> load = timingLoadOf(readJsonFile(stats));
        if (load && load->overloaded()) loaded.push_back(step.at("id").get<std::string>());
    }
    if (loaded.empty()) return "";
    std::ostringstream md;
    md << "Timed under load: " << loaded.size() << (loaded.size() == 1 ? " run (" : " runs (") << loaded.front()
       << (loaded.size() > 1 ? ", ..." : "") << ") ran while other processes kept the cores busy (timing.load in "
       << "their stats): their seconds, in the tables and charts here, are inflated.";
    return md.str();
}

std::vector<GalleryEntry> galleryEntries(const fs::path& resultsRoot) {
    std::vector<GalleryEntry> entries;
    for (const fs::directory_entry& entry : fs::directory_iterator(resultsRoot))
        if (fs::is_regular_file(entry.path() / "manifest.json"))
            entries.push_back(galleryEntry(entry.path() / "manifest.json"));
    const auto rank = [](const std::string& paper) { return paper == "A" ? 0 : paper == "B" ? 1 : 2; };
    std::sort(entries.begin(), entries.end(), [&](const GalleryEntry& x, const GalleryEntry& y) {
        if (rank(x.paper) != rank(y.paper)) return rank(x.paper) < rank(y.paper);
        if (x.item != y.item) return naturalLess(x.item, y.item);
        return x.dir < y.dir;
    });
    return entries;
}

// The trail galleryPages opens an experiment's own page with.
constexpr std::string_view kPageTrail = "[Results](README.md) / ";

std::vector<ScriptPage> scriptPages(const fs::path& resultsRoot) {
    std::vector<ScriptPage> pages;
    for (const fs::directory_entry& entry : fs::directory_iterator(resultsRoot)) {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() || !name.ends_with(".md") || name == "README.md" ||
            !isSafeName(name.substr(0, name.size() - 3)))
            continue;
        const std::optional<std::string> text = tryReadFileText(entry.path());
        if (!text || text->starts_with(kPageTrail)) continue;
        std::string title = name;
        std::istringstream lines(*text);
        for (std::string line; std::getline(lines, line);)
            if (line.starts_with("# ")) {
                title = line.substr(2);
                break;
            }
        // A heading of the page's own: nothing in it may close the index's link or cell.
        std::erase_if(title, [](char c) {
            return c == '[' || c == ']' || c == '|' || std::iscntrl(static_cast<unsigned char>(c));
        });
        title.erase(std::unique(title.begin(), title.end(), [](char a, char b) { return a == ' ' && b == ' '; }),
                    title.end());
        pages.push_back({name, title});
    }
    std::sort(pages.begin(), pages.end(), [](const ScriptPage& a, const ScriptPage& b) { return a.name < b.name; });
    return pages;
}

std::vector<GalleryPage> galleryPages(const std::vector<GalleryEntry>& entries,
                                      const std::vector<ScriptPage>& scripts) {
    std::vector<GalleryPage> pages{{"README.md", ""}};
    std::ostringstream index, sections;
    index
        << "# Results\n\n"
           "Generated by `vri-run --gallery` from each experiment's `manifest.json`; regenerate everything with\n"
           "`make experiments`. Each experiment's folder holds its images, tables, figures and the manifest with the\n"
           "exact commands, input digests, build, machine and wall times. The sections follow the papers: paper A's\n"
           "items, then paper B's, then our own studies; a long section has a page of its own. Last, the pages\n"
           "that scripts write (their measurements need what an experiment cannot ask for, a cluster of its own).\n\n"
           "| paper item | section | ours against the paper |\n|:--|:--|:--|\n";
    std::map<std::string, std::string> notedIn;
    for (const GalleryEntry& entry : entries) {
        const std::string section = gallerySection(entry.manifest, notedIn);
        const bool own =
            std::count(section.begin(), section.end(), '\n') > static_cast<std::ptrdiff_t>(kLongSectionLines);
        const std::string link = own ? entry.dir + ".md" : "#" + headingAnchor(entry.title);
        index << "| " << (entry.paper == "none" ? "own study" : "Paper " + entry.paper + ", " + entry.item) << " | ["
              << entry.title << "](" << link << ") | " << (entry.verdict.empty() ? "-" : entry.verdict) << " |\n";
        if (own) {
            pages.push_back({entry.dir + ".md", std::string(kPageTrail) + entry.dir + "\n" + section});
            sections << "\n## " << entry.title << "\n\nOn a page of its own: [" << entry.dir << ".md](" << entry.dir
                     << ".md).\n";
        } else {
            sections << section;
        }
    }
    for (const ScriptPage& page : scripts)
        index << "| written by a script | [" << page.title << "](" << page.name << ") | - |\n";
    pages.front().text = index.str() + sections.str();
    return pages;
}

}  // namespace vri
