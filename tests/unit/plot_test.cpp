// Figure specs and the gnuplot scripts made from them; a real PNG and SVG when gnuplot is installed.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "temp_dir.h"
#include "vri/error.h"
#include "vri/plot.h"

using namespace vri;

namespace {

void writeFile(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string errorOf(const std::string& spec, const std::filesystem::path& base) {
    try {
        parsePlotSpec(spec, "fig.yaml", base);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST_CASE("plot: Pareto front in (x, y) minimisation") {
    const std::vector<std::pair<double, double>> points = {{1, 5}, {2, 3}, {3, 4}, {4, 1}, {2, 3}, {0.5, std::nan("")}, {5, 1}};
    CHECK(paretoFront(points) == std::vector<std::size_t>{0, 1, 3});
    CHECK(paretoFront({}).empty());
}

TEST_CASE("plot: spec errors point at file, line and column") {
    test::TempDir dir("plot");
    writeFile(dir / "d.csv", "h,err,name\n0.5,0.1,a\n0.1,0.01,b\n");
    const std::string series = "series:\n  - {file: d.csv, x: h, y: err}\n";
    CHECK(errorOf(series, dir.path) == "no error");
    CHECK(errorOf("series:\n  - {file: d.csv, x: h, y: error}\n", dir.path) ==
          "fig.yaml:2:28: column 'error' is not in " + (dir / "d.csv").string() + " (it has: h, err, name)");
    CHECK(errorOf("series:\n  - {file: e.csv, x: h, y: err}\n", dir.path) ==
          "fig.yaml:2:12: data file " + (dir / "e.csv").string() + " does not exist");
    CHECK(errorOf("title: t\ncolour: red\n" + series, dir.path) ==
          "fig.yaml:2:1: unknown key 'colour' (expected one of: title, size, grid, x, y, key, pareto, series)");
    CHECK(errorOf("series:\n  - {file: d.csv, x: h, y: err, style: bars}\n", dir.path).starts_with(
        "fig.yaml:2:40: style 'bars' is unknown"));
    CHECK(errorOf("x: {log: yes please}\n" + series, dir.path) == "fig.yaml:1:10: x.log must be true or false");
    CHECK(errorOf("grid: [1, 1]\npanels:\n  - " + series.substr(0, 7) + "\n    - {file: d.csv, x: h, y: err}\n  - " +
                      series.substr(0, 7) + "\n    - {file: d.csv, x: h, y: err}\n",
                  dir.path) == "fig.yaml:1:7: grid 1x1 has no room for 2 panels");
    CHECK(errorOf("series: [\n", dir.path).starts_with("fig.yaml:2:1: malformed YAML"));
}

TEST_CASE("plot: the gnuplot script") {
    test::TempDir dir("plot");
    std::filesystem::create_directories(dir / "data");
    writeFile(dir / "data/speed.csv", "method,seconds,error\nr,2,0.1\nc,1,0.2\nd,3,0.3\n");
    writeFile(dir / "data/hist.csv", "bin_lo,bin_hi,R,A\n0,0,5,5\n0,0.1,1,2\n0.1,1,3,0\n1,inf,0,0\n");
    const PlotSpec spec = parsePlotSpec("title: It's a test\n"
                                        "size: [640, 480]\n"
                                        "panels:\n"
                                        "  - title: speed\n"
                                        "    x: {label: seconds, log: true, range: [0.5, 4]}\n"
                                        "    y: error\n"
                                        "    pareto: true\n"
                                        "    key: off\n"
                                        "    series:\n"
                                        "      - {file: data/speed.csv, x: seconds, y: error, style: points, label: all}\n"
                                        "  - title: histogram\n"
                                        "    series:\n"
                                        "      - {file: data/hist.csv, y: A, style: histogram, color: \"#ff0000\"}\n",
                                        "fig.yaml", dir.path);
    CHECK(spec.rows == 1);
    CHECK(spec.columns == 2);
    const std::string script = gnuplotScript(spec, dir / "out/fig.gp", "fig.png", "fig.svg");
    auto has = [&](const std::string& text) {
        INFO(text);
        CHECK(script.find(text) != std::string::npos);
    };
    has("if (!exists(\"png_out\")) png_out = 'fig.png'\n");
    has("cd (i > 0 ? script_dir[1:i] : \".\")\n");
    has("$pareto1 << EOD\n1,0.20000000000000001\n2,0.10000000000000001\nEOD\n");
    has("set terminal pngcairo size 640,480 noenhanced");
    has("set multiplot layout 1,2 title 'It''s a test'\n");
    has("    set xlabel 'seconds'\n    set logscale x\n    set xrange [0.5:4]\n");
    has("    unset logscale y\n    set yrange [*:*]\n    unset key\n");
    has("plot '../data/speed.csv' skip 1 using 2:3 with points pt 7 ps 0.8 title 'all', \\\n"
        "         $pareto1 using 1:2 with linespoints");
    has("plot '../data/hist.csv' skip 1 using (($1 > 0 && $2 < 1e300) ? ($1 + $2) / 2 : NaN):($4 / 2):1:2:(0):($4) "
        "with boxxyerror fs transparent solid 0.35 border lc rgb '#ff0000' title 'A'\n");

    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return;
    std::filesystem::create_directories(dir / "out");
    drawPlot(spec, dir / "out/fig.png");
    CHECK(std::filesystem::file_size(dir / "out/fig.png") > 1000);
    CHECK(std::filesystem::file_size(dir / "out/fig.svg") > 1000);
    CHECK(std::filesystem::is_regular_file(dir / "out/fig.gp"));
    std::size_t entries = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "out")) entries += !entry.path().empty();
    CHECK(entries == 3);  // no temporary file left behind
}
