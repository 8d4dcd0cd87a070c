// The gallery's scene-by-run matrices of thumbnails.
#include "libvri/experiment/gallery_grid.h"

#include <algorithm>
#include <map>
#include <utility>

namespace vri {

namespace {

// A row's label: its scene, or a dash for the images of no scene. (Every label is a safe name,
// experiment_spec.h, so none holds a pipe that would end its cell.)
std::string rowLabel(const std::string& scene) { return scene.empty() ? "–" : scene; }

void addOnce(std::vector<std::string>& list, const std::string& value) {
    if (std::ranges::find(list, value) == list.end()) list.push_back(value);
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

}  // namespace vri
