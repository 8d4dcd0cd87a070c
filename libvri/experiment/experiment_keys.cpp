#include "libvri/experiment/experiment_keys.h"

#include "libvri/core/render_option_table.h"

namespace vri {

std::vector<std::pair<std::string_view, std::string_view>> experimentKeys() {
    std::vector<std::pair<std::string_view, std::string_view>> keys;
    const auto add = [&](std::string_view where, const auto& list) {
        for (const std::string_view key : list) keys.emplace_back(where, key);
    };
    add("the file", kTopLevelKeys);
    add("paper:", kPaperKeys);
    add("a scene", kSceneKeys);
    add("a scene's camera:", kCameraKeys);
    add("a scene's png:", kPngKeys);
    add("a renderers: entry", kRendererKeys);
    add("a comparison", kComparisonKeys);
    add("a command", kCommandKeys);
    add("a table", kTableKeys);
    add("a figure", kFigureKeys);
    add("reproduce:", kReproduceKeys);
    add("a reproduce: check", kReproduceCheckKeys);
    add("quick:", kQuickKeys);
    add("a method", kMethodKeysBesideOptions);
    for (const RenderOptionRow& row : renderOptionTable())
        if (!row.key.empty()) keys.emplace_back("a method", row.key);
    return keys;
}

}  // namespace vri
