#include "libvri/experiment/results_viewer.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

#include "libvri/experiment/caption_numbers.h"
#include "libvri/experiment/gallery_grid.h"
#include "libvri/io/image_io.h"
#include "libvri/io/viewer_floats.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/file_text.h"
#include "libvri/util/json_file.h"
#include "libvri/util/script_json.h"

namespace vri {

extern const std::string_view kViewerScript;  // tools/viewer/vri-viewer.js
extern const std::string_view kViewerStyle;   // tools/viewer/vri-viewer.css

namespace fs = std::filesystem;

namespace {

constexpr const char* kFloatsFolder = "viewer-data";

// A page: its title (with '<' and '&' escaped), the data for the script, which builds everything else. `up` leads from the page to the results
// folder ("" or "../").
std::string page(const std::string& title, const char* dataId, const nlohmann::json& data, const std::string& up) {
    std::string escaped;
    for (const char c : title) escaped += c == '<' ? std::string("&lt;") : c == '&' ? std::string("&amp;") : std::string(1, c);
    return "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + escaped +
           "</title>\n<link rel=\"stylesheet\" href=\"" + up + "viewer/vri-viewer.css\"></head>\n<body>\n"
           "<p id=\"vri-fallback\">This page is drawn by " + up + "viewer/vri-viewer.js, which did not run: open it from its "
           "results folder, beside viewer/ (vri-run --gallery writes both), in a browser with JavaScript.</p>\n<script id=\"" +
           dataId + "\" type=\"application/json\">" + scriptSafeJson(data) + "</script>\n<script src=\"" + up +
           "viewer/vri-viewer.js\"></script>\n</body></html>\n";
}

// A PNG's width and height from its IHDR chunk, which the format puts first; nullopt for a file that is
// missing or not a PNG.
std::optional<std::pair<std::uint32_t, std::uint32_t>> pngSize(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::array<unsigned char, 24> head{};
    if (!in.read(reinterpret_cast<char*>(head.data()), head.size())) return std::nullopt;
    static constexpr std::array<unsigned char, 8> kSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (!std::equal(kSignature.begin(), kSignature.end(), head.begin()) || std::string(&head[12], &head[16]) != "IHDR")
        return std::nullopt;
    const auto big = [&](int at) {
        return std::uint32_t(head[at]) << 24 | std::uint32_t(head[at + 1]) << 16 | std::uint32_t(head[at + 2]) << 8 |
               head[at + 3];
    };
    return std::pair{big(16), big(20)};
}

// The EXR file name each step wrote (by step id), the float data a render's image has.
std::map<std::string, std::string> exrOfSteps(const nlohmann::json& steps) {
    std::map<std::string, std::string> exr;
    for (const nlohmann::json& step : steps)
        for (const nlohmann::json& output : step.at("outputs")) {
            const fs::path path = output.at("path").get<std::string>();
            if (path.extension() == ".exr") exr.emplace(step.at("id").get<std::string>(), path.filename().string());
        }
    return exr;
}

// One grid of the page: its images in the gallery's rows and columns.
nlohmann::json grid(const std::string& name, const nlohmann::json& list, const nlohmann::json& steps,
                    const fs::path& dir, const std::map<std::string, std::string>& exr) {
    std::map<std::string, const nlohmann::json*> parameters;
    for (const nlohmann::json& step : steps) parameters.emplace(step.at("id").get<std::string>(), &step.at("parameters"));
    nlohmann::json rows = nlohmann::json::array(), columns = nlohmann::json::array(), images = nlohmann::json::array();
    const auto addOnce = [](nlohmann::json& to, const std::string& value) {
        if (std::find(to.begin(), to.end(), value) == to.end()) to.push_back(value);
    };
    for (const GridImage& image : gridImages(list, steps, "")) {
        const std::string png = fs::path(image.file).filename().string();
        nlohmann::json item{{"id", image.id}, {"row", image.row}, {"column", image.column}, {"png", png},
                            {"floats", nullptr}, {"width", nullptr}, {"height", nullptr}};
        if (const auto size = pngSize(dir / png)) {
            item["width"] = size->first;
            item["height"] = size->second;
        }
        if (const auto found = exr.find(image.id); found != exr.end()) {
            item["floats"] = std::string(kFloatsFolder) + "/" + image.id + ".js";
        }
        if (const auto found = parameters.find(image.id); found != parameters.end() && found->second->contains("run")) {
            item["run"] = found->second->at("run");
            if (found->second->contains("reference")) item["reference"] = found->second->at("reference");
            const fs::path json = dir / (image.id + ".json");
            if (fs::is_regular_file(json))
                readingJsonOf(json, [&] {
                    const nlohmann::json diff = readJsonFile(json);
                    if (diff.contains("heat_map")) {
                        const nlohmann::json& heat = diff.at("heat_map");
                        item["heat"] = {{"scale", heat.value("scale", "linear")}, {"top", heat.at("top")}};
                        if (heat.contains("decades")) item["heat"]["decades"] = heat.at("decades");
                    }
                });
        }
        addOnce(rows, image.row);
        addOnce(columns, image.column);
        images.push_back(std::move(item));
    }
    return {{"name", name}, {"rows", rows}, {"columns", columns}, {"images", images}};
}

nlohmann::json experimentData(const GalleryEntry& entry) {
    return readingJsonOf(entry.manifest, [&] {
        const nlohmann::json m = readJsonFile(entry.manifest);
        const nlohmann::json& e = m.at("experiment");
        const fs::path dir = entry.manifest.parent_path();
        const nlohmann::json& outputs = m.at("outputs");
        const std::map<std::string, std::string> exr = exrOfSteps(m.at("steps"));
        nlohmann::json data{{"title", entry.title},
                            {"paper", entry.paper},
                            {"item", entry.item},
                            {"says", e.at("paper").value("says", "")},
                            {"agreement", fillCaptionNumbers(e.at("agreement").get<std::string>(), dir)},
                            {"commit", m.at("source_tree").at("commit")},
                            {"modified", m.at("source_tree").value("modified_files", false)},
                            {"manifest", "manifest.json"},
                            {"index", "../index.html"}};
        data["grids"] = nlohmann::json::array();
        for (const auto& [name, key] : {std::pair{"Renders", "images"}, std::pair{"Difference images", "diff_images"}})
            if (!outputs.at(key).empty()) data["grids"].push_back(grid(name, outputs.at(key), m.at("steps"), dir, exr));
        data["figures"] = nlohmann::json::array();
        for (const nlohmann::json& figure : outputs.at("figures"))
            data["figures"].push_back({{"id", figure.at("id")}, {"file", figure.at("file")}});
        data["tables"] = nlohmann::json::array();
        for (const nlohmann::json& table : outputs.at("tables"))
            if (const auto text = tryReadFileText(dir / table.at("file").get<std::string>()); text && !text->empty())
                data["tables"].push_back({{"id", table.at("id")}, {"file", table.at("file")}, {"markdown", *text}});
        data["notes"] = nlohmann::json::array();
        for (const std::string& note : {heatMapCaption(outputs.at("diff_images"), dir), loadCaption(m.at("steps"), dir)})
            if (!note.empty()) data["notes"].push_back(note);
        return data;
    });
}

}  // namespace

std::vector<GalleryPage> viewerPages(const std::vector<GalleryEntry>& entries) {
    std::vector<GalleryPage> pages{{"viewer/vri-viewer.js", std::string(kViewerScript)},
                                   {"viewer/vri-viewer.css", std::string(kViewerStyle)}};
    nlohmann::json list = nlohmann::json::array();
    for (const GalleryEntry& entry : entries) {
        list.push_back({{"dir", entry.dir},
                        {"title", entry.title},
                        {"paper", entry.paper},
                        {"item", entry.item},
                        {"verdict", entry.verdict},
                        {"page", entry.dir + "/index.html"}});
        pages.push_back({entry.dir + "/index.html", page(entry.title, "vri-experiment", experimentData(entry), "../")});
    }
    pages.push_back({"index.html", page("vri results", "vri-index", {{"title", "vri results"}, {"experiments", list}}, "")});
    return pages;
}

std::size_t writeViewerFloats(const std::vector<GalleryEntry>& entries) {
    std::size_t written = 0;
    for (const GalleryEntry& entry : entries) {
        const fs::path dir = entry.manifest.parent_path();
        const nlohmann::json m = readingJsonOf(entry.manifest, [&] { return readJsonFile(entry.manifest); });
        const std::map<std::string, std::string> exr = exrOfSteps(m.at("steps"));
        for (const nlohmann::json& image : m.at("outputs").at("images")) {
            const std::string id = image.at("id").get<std::string>();
            const auto found = exr.find(id);
            if (found == exr.end() || !fs::is_regular_file(dir / found->second)) continue;
            const fs::path script = dir / kFloatsFolder / (id + ".js");
            if (fs::is_regular_file(script) && fs::last_write_time(script) >= fs::last_write_time(dir / found->second))
                continue;
            writeTextFile(script, viewerFloatsScript(id, readImage(dir / found->second)));
            ++written;
        }
    }
    return written;
}

}  // namespace vri
