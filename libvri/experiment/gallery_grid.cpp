// The gallery's scene-by-run matrices of thumbnails.
#include "libvri/experiment/gallery_grid.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

namespace vri {

namespace {

// A row's label: its scene, or a dash for the images of no scene. (Every label is a safe name,
// experiment_spec.h, so none holds a pipe that would end its cell.)
std::string rowLabel(const std::string& scene) { return scene.empty() ? "–" : scene; }

void addOnce(std::vector<std::string>& list, const std::string& value) {
    if (std::ranges::find(list, value) == list.end()) list.push_back(value);
}

// An id without the scene's name in front (bonsai-riemann-h0.5 -> riemann-h0.5): the same run's
// column in every scene's row.
std::string withoutScene(const std::string& id, const std::string& scene) {
    return !scene.empty() && id.starts_with(scene + "-") ? id.substr(scene.size() + 1) : id;
}

}  // namespace

std::string imageGrid(const std::vector<GridImage>& images, const std::string& corner) {
    std::vector<std::string> rows, columns;
    std::map<std::pair<std::string, std::string>, const GridImage*> at;
    for (const GridImage& image : images) {
        addOnce(rows, image.row);
        addOnce(columns, image.column);
        at.emplace(std::pair(image.row, image.column), &image);  // the first image of a cell, if two share one
    }
    std::string md;
    for (std::size_t first = 0; first < columns.size(); first += kGridColumns) {
        const std::size_t last = std::min(columns.size(), first + kGridColumns);
        md += "| " + corner + " |";
        for (std::size_t c = first; c < last; ++c) md += " " + columns[c] + " |";
        md += "\n|:--|";
        for (std::size_t c = first; c < last; ++c) md += ":-:|";
        md += "\n";
        for (const std::string& row : rows) {
            std::string line = "| **" + rowLabel(row) + "** |";
            bool any = false;
            for (std::size_t c = first; c < last; ++c) {
                const auto found = at.find({row, columns[c]});
                if (found == at.end()) {
                    line += " |";
                    continue;
                }
                line += " ![" + found->second->id + "](" + found->second->file + ") |";
                any = true;
            }
            if (any) md += line + "\n";  // a scene with none of these runs takes no row here
        }
        md += "\n";
    }
    return md;
}

std::vector<GridImage> gridImages(const nlohmann::json& list, const nlohmann::json& steps, const std::string& dir) {
    std::map<std::string, const nlohmann::json*> parameters;
    for (const nlohmann::json& step : steps)
        parameters.emplace(step.at("id").get<std::string>(), &step.at("parameters"));
    const auto scene = [&](const std::string& id) {
        const auto found = parameters.find(id);
        return found == parameters.end() ? std::string() : found->second->value("scene", std::string());
    };
    std::vector<GridImage> images;
    std::set<std::pair<std::string, std::string>> cells;  // (row, column) taken
    for (const nlohmann::json& item : list) {
        const std::string id = item.at("id").get<std::string>();
        GridImage image{id, dir + "/" + item.at("file").get<std::string>(), scene(id), id};
        if (const auto found = parameters.find(id); found != parameters.end() && found->second->contains("run")) {
            const std::string run = found->second->at("run").get<std::string>();
            const std::string reference = found->second->value("reference", std::string());
            image.row = scene(run);
            image.column = withoutScene(run, image.row) + " vs " + withoutScene(reference, scene(reference));
            if (cells.contains({image.row, image.column})) image.column = withoutScene(id, image.row);
        } else {
            image.column = withoutScene(id, image.row);
        }
        cells.emplace(image.row, image.column);
        images.push_back(std::move(image));
    }
    return images;
}


}  // namespace vri
