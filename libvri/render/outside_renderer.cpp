#include "libvri/render/outside_renderer.h"

#include <chrono>
#include <cmath>
#include <fstream>

#include "libvri/core/image_compare.h"
#include "libvri/io/image_io.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/json_file.h"
#include "libvri/util/printable.h"
#include "libvri/util/process.h"
#include "libvri/util/sha512.h"

namespace vri {

namespace fs = std::filesystem;

std::vector<std::string> expandPlaceholders(const std::vector<std::string>& command,
                                            const std::map<std::string, std::string, std::less<>>& values) {
    std::vector<std::string> words;
    for (const std::string& word : command) {
        std::string out;
        for (std::size_t i = 0; i < word.size(); ++i) {
            const char c = word[i];
            if ((c == '{' || c == '}') && i + 1 < word.size() && word[i + 1] == c) {  // {{ and }}: a brace
                out += c;
                ++i;
                continue;
            }
            if (c == '}')
                throw Error("renderer command word '" + printable(word) + "': a '}' without its '{' (write }})");
            if (c != '{') {
                out += c;
                continue;
            }
            const std::size_t end = word.find('}', i);
            if (end == std::string::npos)
                throw Error("renderer command word '" + printable(word) + "': a '{' without its '}' (write {{)");
            const std::string_view name = std::string_view(word).substr(i + 1, end - i - 1);
            const auto found = values.find(name);
            if (found == values.end()) {
                std::string known;
                for (const auto& [key, value] : values) known += (known.empty() ? "{" : ", {") + key + "}";
                throw Error("renderer command word '" + printable(word) + "': unknown placeholder {" + printable(name) +
                            "} (expected " + known + ")");
            }
            out += found->second;
            i = end;
        }
        words.push_back(std::move(out));
    }
    return words;
}

namespace {

// A PNG's bit depth, from its IHDR chunk (byte 24): 8 or 16 for what we read.
int pngBitDepth(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char header[25] = {};
    in.read(header, sizeof header);
    return in ? static_cast<unsigned char>(header[24]) : 0;
}

Image readRawFloat(const fs::path& path, int width, int height) {
    const std::uintmax_t expected = static_cast<std::uintmax_t>(width) * height * 4 * sizeof(float);
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw Error(path.string() + ": cannot read: " + ec.message());
    if (size != expected)
        throw Error(path.string() + ": " + std::to_string(size) + " bytes, expected " + std::to_string(expected) +
                    " (float32 RGBA, " + std::to_string(width) + "x" + std::to_string(height) + ")");
    Image image(width, height);
    std::ifstream in(path, std::ios::binary);
    static_assert(std::endian::native == std::endian::little, ".f32 images are little-endian");
    in.read(reinterpret_cast<char*>(image.pixels.data()), static_cast<std::streamsize>(expected));
    if (!in) throw Error(path.string() + ": cannot read " + std::to_string(expected) + " bytes");
    return image;
}

}  // namespace

Image readOutsideImage(const fs::path& path, int width, int height, std::string& quantisation) {
    if (!fs::is_regular_file(path)) throw Error(path.string() + ": the renderer wrote no image there");
    const std::string extension = path.extension().string();
    if (extension == ".f32") {
        quantisation = "float32";
        return readRawFloat(path, width, height);
    }
    Image image = readImage(path);
    quantisation = extension == ".png" ? std::to_string(pngBitDepth(path)) + "-bit" : "float32";
    if (image.width != width || image.height != height)
        throw Error(path.string() + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    ", the card's image is " + std::to_string(width) + "x" + std::to_string(height));
    try {
        return selectChannels(image, {"R", "G", "B", "A"}, path.string());
    } catch (const Error& e) {
        throw Error(std::string(e.what()) +
                    ": expected R, G, B and A, premultiplied, as the card's output section says");
    }
}

OutsideRun runOutsideRenderer(const OutsideRenderer& renderer, const nlohmann::json& card, const fs::path& workDir) {
    if (renderer.command.empty()) throw Error("the renderer's command is empty");
    if (renderer.imageFormat != "exr" && renderer.imageFormat != "png" && renderer.imageFormat != "f32")
        throw Error("renderer image format '" + printable(renderer.imageFormat) + "': expected exr, png or f32");
    const int width = card.at("camera").at("width"), height = card.at("camera").at("height");
    const fs::path image = workDir / ("image." + renderer.imageFormat), stats = workDir / "stats.json";
    const nlohmann::json& voxels = card.at("volume").contains("voxels") ? card["volume"]["voxels"] : nlohmann::json();
    const nlohmann::json& method = card.at("method");
    const std::map<std::string, std::string, std::less<>> values = {
        {"card", (workDir / "card.json").string()},
        {"voxels", voxels.contains("file") ? (workDir / voxels["file"].get<std::string>()).string() : std::string()},
        {"output", image.string()},
        {"stats", stats.string()},
        {"step", method.contains("step") ? exactNumber(method["step"].get<double>()) : std::string()},
        {"seed", method.contains("jitter") ? std::to_string(method["jitter"]["seed"].get<std::uint32_t>()) : "0"},
        {"width", std::to_string(width)},
        {"height", std::to_string(height)},
        {"vri_bin", thisProgramFolder().string()}};
    const std::vector<std::string> words = expandPlaceholders(renderer.command, values);
    const std::optional<fs::path> program = findProgram(words[0]);
    if (!program)
        throw Error("renderer command '" + printable(words[0]) + "': no such executable (in PATH or as a path)");

    // Its name: its stats' (below), else the one given, else the program's file name (the script's, after an
    // interpreter such as python3 or node).
    std::string name = renderer.name;
    if (name.empty()) {
        const std::string file = fs::path(words[0]).filename().string();
        const bool interpreter = file.starts_with("python") || file == "node" || file == "sh" || file == "bash";
        name = fs::path(interpreter && words.size() > 1 ? words[1] : words[0]).filename().string();
    }
    OutsideRun run;
    const auto start = std::chrono::steady_clock::now();
    bool timedOut = false;
    const ExitStatus status = runProcessWithin(*program, words, renderer.timeoutSeconds, timedOut);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (timedOut)
        throw Error("renderer '" + printable(name) + "' ran past the time limit of " +
                    exactNumber(renderer.timeoutSeconds) + " s and was stopped (--timeout)");
    if (!status.ok()) throw Error("renderer '" + printable(name) + "' failed (" + status.describe() + ")");
    run.image = readOutsideImage(image, width, height, run.quantisation);

    run.renderer = {{"name", name},
                    {"version", ""},
                    {"command", renderer.command},
                    {"argv", words},
                    {"executable", {{"path", fs::absolute(*program).string()}, {"sha512", sha512File(*program)}}},
                    {"image_format", renderer.imageFormat},
                    {"quantisation", run.quantisation},
                    {"process_seconds", seconds}};
    run.wallSeconds = {seconds};
    run.timed = "process";
    if (fs::exists(stats)) {
        const nlohmann::json own = readJsonFile(stats);
        if (own.value("format", "") != kOutsideStatsFormat)
            throw Error(stats.string() + ": the renderer's stats: expected \"format\": \"" +
                        std::string(kOutsideStatsFormat) + "\" (docs/outside-renderers.md)");
        run.renderer["stats"] = own;
        // An image read back from 8 bits and written as float is 8-bit: the renderer's word for it holds.
        if (const auto i = own.find("image"); i != own.end() && i->is_object() && i->contains("quantisation")) {
            run.quantisation = i->at("quantisation").get<std::string>();
            run.renderer["quantisation"] = run.quantisation;
        }
        if (const auto r = own.find("renderer"); r != own.end() && r->is_object()) {
            if (const std::string n = r->value("name", ""); !n.empty()) run.renderer["name"] = n;
            run.renderer["version"] = r->value("version", "");
        }
        if (const auto t = own.find("timing"); t != own.end() && t->contains("wall_seconds")) {
            const std::vector<double> frames = t->at("wall_seconds").get<std::vector<double>>();
            if (frames.empty() ||
                std::ranges::any_of(frames, [](double s) { return !(s >= 0.0) || !std::isfinite(s); }))
                throw Error(stats.string() + ": timing.wall_seconds: expected a non-empty list of seconds >= 0");
            run.wallSeconds = frames;
            run.timed = t->value("what", "frame");
        }
    }
    return run;
}

}  // namespace vri
