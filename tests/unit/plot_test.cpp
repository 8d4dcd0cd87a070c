// Figure specs and the gnuplot scripts made from them; a real PNG and SVG when gnuplot is installed.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "temp_dir.h"
#include "libvri/report/plot.h"
#include "libvri/report/plot_axes.h"
#include "libvri/report/plot_slopes.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/process.h"

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
          "fig.yaml:2:1: unknown key 'colour' (expected one of: title, size, grid, x, y, key, pareto, aspect, "
          "reference_slopes, labels, colorbar, series)");
    CHECK(errorOf("series:\n  - {file: d.csv, x: h, y: err, style: bars}\n", dir.path) ==
          "fig.yaml:2:40: series[0].style 'bars' is unknown (expected line, dashed, dotted, points, linespoints, "
          "histogram, heatmap or segments)");
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
    has("png_out = ARGC >= 2 ? ARG1 : 'fig.png'\n");
    has("cd (i > 0 ? script_dir[1:i] : \".\")\n");
    has("$pareto1 << EOD\n1,0.2\n2,0.1\nEOD\n");
    has("set terminal pngcairo size 640,480 noenhanced");
    has("set multiplot layout 1,2 title 'It''s a test'\n");
    has("    set xlabel 'seconds'\n    set logscale x\n    set format x '%g'\n    set xtics autofreq\n"
        "    set xrange [0.5:4] extend\n");
    has("    unset logscale y\n    set format y '% h'\n    set ytics autofreq\n    set yrange [*:*] extend\n"
        "    set bmargin\n    unset key\n"
        "    set size noratio\n    unset label\n");
    has("plot '../data/speed.csv' skip 1 using 2:3 with points pt 7 ps 0.8 title 'all', \\\n"
        "         $pareto1 using 1:2 with linespoints");
    has("plot '../data/hist.csv' skip 1 using (($1 > 0 && $2 < 1e300) ? ($1 + $2) / 2 : NaN):($4 / 2):1:2:(0):($4) "
        "with boxxyerror fs transparent solid 0.35 border lc rgb '#ff0000' title 'A'\n");

    if (!vri::commandAvailable("gnuplot")) return;
    std::filesystem::create_directories(dir / "out");
    drawPlot(spec, dir / "out/fig.png");
    CHECK(std::filesystem::file_size(dir / "out/fig.png") > 1000);
    CHECK(std::filesystem::file_size(dir / "out/fig.svg") > 1000);
    CHECK(std::filesystem::is_regular_file(dir / "out/fig.gp"));
    std::size_t entries = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "out")) entries += !entry.path().empty();
    CHECK(entries == 3);  // no temporary file left behind
}

TEST_CASE("plot: speed against accuracy, each point labelled with its run, the front of the points drawn") {
    test::TempDir dir("plot");
    writeFile(dir / "t.csv", "run,seconds,max,pareto max,scene\n"
                             "r1,1,0.5,1,a\nr2,2,0.1,1,a\nr3,3,0.2,0,a\nfast,0.5,0.01,1,b\n");
    const PlotSpec spec = parsePlotSpec(
        "pareto: true\n"
        "series:\n"
        "  - {file: t.csv, x: seconds, y: max, style: points, labels: run, color: \"#1f77b4\", where: {scene: a}}\n"
        "  - {file: t.csv, x: seconds, y: max, style: points, label: front, where: {scene: a, pareto max: 1}}\n",
        "fig.yaml", dir.path);
    CHECK(spec.panels[0].series[0].labelColumn == 1);
    CHECK(spec.panels[0].series[1].labelColumn == 0);
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    auto has = [&](const std::string& text) {
        INFO(text);
        CHECK(script.find(text) != std::string::npos);
    };
    // Scene b's point is not drawn, so it is not on the front; a point in both series is one vertex.
    has("$pareto1 << EOD\n1,0.5\n2,0.1\nEOD\n");
    has("plot 't.csv' skip 1 using 2:(strcol(5) eq 'a' ? $3 : NaN) with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'max', "
        "\\\n         't.csv' skip 1 using 2:(strcol(5) eq 'a' ? $3 : NaN):(strcol(1)) with labels left offset char 0.5,0.5 "
        "font ',8' tc rgb '#1f77b4' notitle, \\\n");

    CHECK(errorOf("series:\n  - {file: t.csv, x: seconds, y: max, labels: name}\n", dir.path) ==
          "fig.yaml:2:47: column 'name' is not in " + (dir / "t.csv").string() +
              " (it has: run, seconds, max, pareto max, scene)");
    CHECK(errorOf("series:\n  - {file: t.csv, x: seconds, y: max, x2: seconds, y2: max, style: segments, labels: run}\n",
                  dir.path) ==
          "fig.yaml:2:86: series[0].labels is not for style segments (only for line, dashed, dotted, points, linespoints)");
}

TEST_CASE("plot: a heatmap from a grid in any order, with its colour bar") {
    test::TempDir dir("plot");
    writeFile(dir / "f.csv", "u,v,f\n1,0.5,0.3\n0,0,0\n0,0.5,0.1\n1,0,0.2\n");
    const PlotSpec spec = parsePlotSpec("aspect: equal\n"
                                        "colorbar: {label: \"f(u, v)\", min: 0, max: 1, palette: gray}\n"
                                        "labels:\n"
                                        "  - {x: 0.5, y: 0.25, text: centre}\n"
                                        "series:\n"
                                        "  - {file: f.csv, x: u, y: v, z: f, style: heatmap}\n",
                                        "fig.yaml", dir.path);
    REQUIRE(spec.panels.size() == 1);
    CHECK(spec.panels[0].series[0].zColumn == 3);
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    auto has = [&](const std::string& text) {
        INFO(text);
        CHECK(script.find(text) != std::string::npos);
    };
    has("# 'f.csv' as x,y,z in scan order, which gnuplot's image needs\n"
        "$heatmap1_1 << EOD\n0,0,0\n1,0,0.2\n0,0.5,0.1\n1,0.5,0.3\nEOD\n");
    has("    set xrange [*:*] noextend\n");
    has("    set size ratio -1\n    unset label\n    set label 'centre' at 0.5,0.25 front\n");
    has("    set palette defined (0 '#000000', 1 '#ffffff')\n    set cbrange [0:1]\n    set cblabel 'f(u, v)'\n"
        "    set colorbox\n");
    has("    plot $heatmap1_1 using 1:2:3 with image notitle\n");

    // By default viridis, over the data's range.
    const std::string plain = gnuplotScript(
        parsePlotSpec("series:\n  - {file: f.csv, x: u, y: v, z: f, style: heatmap}\n", "fig.yaml", dir.path),
        dir / "fig.gp", "fig.png", "fig.svg");
    CHECK(plain.find("set palette defined (0 '#440154'") != std::string::npos);
    CHECK(plain.find("set cbrange [*:*]\n") != std::string::npos);
}

TEST_CASE("plot: heatmap spec errors") {
    test::TempDir dir("plot");
    writeFile(dir / "f.csv", "u,v,f\n0,0,0\n1,0,1\n0,1,1\n1,1,2\n");
    const std::string heatmap = "series:\n  - {file: f.csv, x: u, y: v, z: f, style: heatmap}\n";
    CHECK(errorOf(heatmap, dir.path) == "no error");
    CHECK(errorOf("series:\n  - {file: f.csv, x: u, y: v, style: heatmap}\n", dir.path) ==
          "fig.yaml:2:5: series[0] is missing 'z'");
    CHECK(errorOf("series:\n  - {file: f.csv, x: u, y: v, z: g, style: heatmap}\n", dir.path) ==
          "fig.yaml:2:34: column 'g' is not in " + (dir / "f.csv").string() + " (it has: u, v, f)");
    CHECK(errorOf("series:\n  - {file: f.csv, x: u, y: v, z: f}\n", dir.path) ==
          "fig.yaml:2:34: series[0].z is not for style line (only for heatmap)");
    CHECK(errorOf("series:\n  - {file: f.csv, x: u, y: v, z: f, style: heatmap, color: \"#ff0000\"}\n", dir.path) ==
          "fig.yaml:2:60: series[0].color is not for style heatmap (only for line, dashed, dotted, points, linespoints, "
          "histogram, segments)");
    CHECK(errorOf("colorbar: {palette: jet}\n" + heatmap, dir.path) ==
          "fig.yaml:1:21: colorbar.palette 'jet' is unknown (expected viridis, gray or diverging)");
    CHECK(errorOf("colorbar: {min: 1, max: 0}\n" + heatmap, dir.path) == "fig.yaml:1:25: colorbar.max must be above its min");
    CHECK(errorOf("colorbar: {label: f}\nseries:\n  - {file: f.csv, x: u, y: v}\n", dir.path) ==
          "fig.yaml:1:11: colorbar is for panels with a heatmap series");
    CHECK(errorOf("aspect: square\n" + heatmap, dir.path) ==
          "fig.yaml:1:9: aspect 'square' is unknown (expected auto or equal)");

    // The rows must fill an evenly spaced grid, each point once.
    auto gridError = [&](const std::string& csv) {
        writeFile(dir / "g.csv", csv);
        return errorOf("series:\n  - {file: g.csv, x: u, y: v, z: f, style: heatmap}\n", dir.path);
    };
    const std::string at = "fig.yaml:2:12: " + (dir / "g.csv").string() + ": ";
    CHECK(gridError("u,v,f\n0,0,0\n1,0,1\n0,1,1\n") ==
          at + "the points do not fill a grid: 2 x values and 2 y values make 4 points, there are 3");
    CHECK(gridError("u,v,f\n0,0,0\n1,0,1\n0,1,1\n1,1,2\n1,1,3\n") == at + "the point (1, 1) is in more than one row");
    CHECK(gridError("u,v,f\n0,0,0\n1,0,1\n3,0,1\n0,1,1\n1,1,2\n3,1,2\n") ==
          at + "the values of u are not evenly spaced, as those of a heatmap's grid must be");
    CHECK(gridError("u,v,f\n0,0,0\n1,0,1\n") == at + "a heatmap needs a grid of at least 2 x 2 points, this one is 2 x 1");
    CHECK(gridError("u,v,f\n0,0,0\n1,0,x\n0,1,1\n1,1,2\n") == at + "data row 2: f 'x' is not a number");
}

TEST_CASE("plot: segments, point shapes, line widths and labels") {
    test::TempDir dir("plot");
    writeFile(dir / "s.csv", "t0,t1,row,t\n0,0.5,1,0.25\n0.5,1,1,0.75\n");
    const PlotSpec spec = parsePlotSpec(
        "labels:\n"
        "  - {x: 0, y: 1.2, text: \"it's the ray\"}\n"
        "series:\n"
        "  - {file: s.csv, x: t0, y: row, x2: t1, y2: row, style: segments, width: 3, color: \"#000000\", label: spans}\n"
        "  - {file: s.csv, x: t, y: row, style: points, size: 1.5, point: square, label: samples}\n"
        "  - {file: s.csv, x: t, y: row, style: linespoints, point: triangle, width: 0.5}\n"
        "  - {file: s.csv, x: t, y: row, style: dashed, width: 1}\n"
        "  - {file: s.csv, x: t, y: row, style: points, point: diamond, label: d}\n",
        "fig.yaml", dir.path);
    const PlotSeries& segments = spec.panels[0].series[0];
    CHECK(segments.x2Column == 2);
    CHECK(segments.y2Column == 3);
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    auto has = [&](const std::string& text) {
        INFO(text);
        CHECK(script.find(text) != std::string::npos);
    };
    has("    set label 'it''s the ray' at 0,1.2 front\n");
    has("plot 's.csv' skip 1 using 1:3:($2 - $1):($3 - $3) with vectors nohead lw 3 lc rgb '#000000' title 'spans'");
    has("'s.csv' skip 1 using 4:3 with points pt 5 ps 1.5 title 'samples'");
    has("'s.csv' skip 1 using 4:3 with linespoints lw 0.5 pt 9 ps 0.8 title 'row'");
    has("'s.csv' skip 1 using 4:3 with lines lw 1 dt 2 title 'row'");
    has("'s.csv' skip 1 using 4:3 with points pt 13 ps 0.8 title 'd'\n");
    CHECK(script.find("set colorbox") == std::string::npos);
}

TEST_CASE("plot: where picks the rows of one file for each series") {
    test::TempDir dir("plot");
    writeFile(dir / "d.csv", "panel,kind,x,y,x2,y2\neye,covered,0,0,1,0\neye,missed,1,0,2,0\n");
    const PlotSpec spec = parsePlotSpec(
        "series:\n"
        "  - {file: d.csv, x: x, y: y, x2: x2, y2: y2, style: segments, where: {panel: eye, kind: covered}}\n"
        "  - {file: d.csv, x: x, y: y, style: points, label: \"\", where: {kind: \"it's\"}}\n",
        "fig.yaml", dir.path);
    CHECK(spec.panels[0].series[0].where == std::vector<std::pair<int, std::string>>{{1, "eye"}, {2, "covered"}});
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    INFO(script);
    CHECK(script.find("using 3:(strcol(1) eq 'eye' && strcol(2) eq 'covered' ? $4 : NaN):($5 - $3):($6 - $4) "
                      "with vectors nohead") != std::string::npos);
    CHECK(script.find("using 3:(strcol(2) eq 'it''s' ? $4 : NaN) with points pt 7 ps 0.8 notitle") != std::string::npos);
    CHECK_THROWS_WITH_AS(parsePlotSpec("series:\n  - {file: d.csv, x: x, y: y, where: {colour: red}}\n", "fig.yaml",
                                       dir.path),
                         doctest::Contains("fig.yaml:2:39: column 'colour' is not in"), Error);
    CHECK_THROWS_WITH_AS(parsePlotSpec("series:\n  - {file: d.csv, y: y, style: histogram, where: {kind: a}}\n",
                                       "fig.yaml", dir.path),
                         doctest::Contains("where is not for style histogram"), Error);
}

TEST_CASE("plot: an optional series that keeps no row on this host is left out of its panel and key") {
    test::TempDir dir("plot");
    writeFile(dir / "t.csv", "method,seconds,max\nexact,1,0.1\nexact AVX2,2,0.1\nriemann float SIMD,0.5,0.2\n");
    const std::string series = "  - {file: t.csv, x: seconds, y: max, style: linespoints, where: {method: exact}}\n"
                               "  - {file: t.csv, x: seconds, y: max, style: linespoints, label: lower, optional: true, "
                               "where: {method: \"exact ";
    // On a host with the forced target its series is drawn; on one without, it is dropped, not drawn empty.
    const PlotSpec here = parsePlotSpec("series:\n" + series + "AVX2\"}}\n", "fig.yaml", dir.path);
    REQUIRE(here.panels[0].series.size() == 2);
    CHECK(gnuplotScript(here, dir / "fig.gp", "fig.png", "fig.svg").find("title 'lower'") != std::string::npos);
    const PlotSpec elsewhere = parsePlotSpec("series:\n" + series + "SSE4\"}}\n", "fig.yaml", dir.path);
    REQUIRE(elsewhere.panels[0].series.size() == 1);
    CHECK(gnuplotScript(elsewhere, dir / "fig.gp", "fig.png", "fig.svg").find("lower") == std::string::npos);
    // Without optional an empty series stays, in the key alone, with a warning that names it (a spec's typo
    // shows); a panel of only empty optional series has nothing to draw.
    const PlotSpec typo = parsePlotSpec(
        "series:\n  - {file: t.csv, x: seconds, y: max, style: points, where: {method: none}}\n", "fig.yaml", dir.path);
    CHECK(typo.panels[0].series.size() == 1);
    REQUIRE(typo.warnings.size() == 1);
    CHECK(typo.warnings[0] == "fig.yaml:2:5: series[0]: its where keeps no row of " + (dir / "t.csv").string() +
                                  ": drawn in the key alone (optional: true drops a series only some hosts or runs have)");
    CHECK(here.warnings.empty());
    CHECK(elsewhere.warnings.empty());
    CHECK(errorOf("series:\n  - {file: t.csv, x: seconds, y: max, style: points, optional: true, where: {method: none}}\n",
                  dir.path)
              .find("fig.yaml:2:3: series: every series is optional and keeps no row") != std::string::npos);
    CHECK(errorOf("series:\n  - {file: t.csv, x: seconds, y: max, style: points, optional: maybe}\n", dir.path)
              .find("fig.yaml:2:") != std::string::npos);
}

TEST_CASE("plot: segments and point spec errors") {
    test::TempDir dir("plot");
    writeFile(dir / "s.csv", "t0,t1,row\n0,0.5,1\n");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, x2: t1, style: segments}\n", dir.path) ==
          "fig.yaml:2:5: series[0] is missing 'y2'");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, x2: t1, y2: row}\n", dir.path) ==
          "fig.yaml:2:38: series[0].x2 is not for style line (only for segments)");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, x2: t2, y2: row, style: segments}\n", dir.path) ==
          "fig.yaml:2:38: column 't2' is not in " + (dir / "s.csv").string() + " (it has: t0, t1, row)");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, size: 2}\n", dir.path) ==
          "fig.yaml:2:40: series[0].size is not for style line (only for points, linespoints)");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, style: points, width: 2}\n", dir.path) ==
          "fig.yaml:2:56: series[0].width is not for style points (only for line, dashed, dotted, linespoints, segments)");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, width: -1}\n", dir.path) ==
          "fig.yaml:2:41: series[0].width must be a positive number");
    CHECK(errorOf("series:\n  - {file: s.csv, x: t0, y: row, style: points, point: star}\n", dir.path) ==
          "fig.yaml:2:56: series[0].point 'star' is unknown (expected circle, square, cross, triangle, triangle-down or diamond)");
    const std::string series = "series:\n  - {file: s.csv, x: t0, y: row}\n";
    CHECK(errorOf("labels:\n  - {x: 0, y: 1}\n" + series, dir.path) == "fig.yaml:2:5: labels[0] is missing 'text'");
    CHECK(errorOf("labels:\n  - {x: left, y: 1, text: a}\n" + series, dir.path) ==
          "fig.yaml:2:9: labels[0].x must be a number");
    CHECK(errorOf("labels: {x: 0, y: 1, text: a}\n" + series, dir.path) ==
          "fig.yaml:1:9: labels must be a list of {x, y, text}");
}

TEST_CASE("plot: relative data paths from a data directory") {
    test::TempDir dir("plot");
    std::filesystem::create_directories(dir / "specs");
    std::filesystem::create_directories(dir / "results/a");
    writeFile(dir / "results/a/d.csv", "h,err\n1,2\n");
    writeFile(dir / "specs/fig.yaml", "series:\n  - {file: d.csv, x: h, y: err}\n");
    const std::string text = "series:\n  - {file: d.csv, x: h, y: err}\n";
    CHECK(parsePlotSpec(text, "fig.yaml", dir / "specs", dir / "results/a").panels[0].series[0].file ==
          dir / "results/a/d.csv");
    CHECK(loadPlotSpec(dir / "specs/fig.yaml", dir / "results/a").panels[0].series[0].file == dir / "results/a/d.csv");
    // Without one, paths start at the spec's folder, which has no d.csv.
    CHECK(errorOf(text, dir / "specs") == "fig.yaml:2:12: data file " + (dir / "specs/d.csv").string() + " does not exist");
    // Absolute paths stay as they are.
    const std::string absolute = "series:\n  - {file: " + (dir / "results/a/d.csv").string() + ", x: h, y: err}\n";
    CHECK(parsePlotSpec(absolute, "fig.yaml", dir / "specs", dir / "elsewhere").panels[0].series[0].file ==
          dir / "results/a/d.csv");
}

TEST_CASE("plot: no character of a title, label, series or file name is read as gnuplot code") {
    test::TempDir dir("plot");
    // Each would run `touch` if it reached gnuplot unquoted: a quote that ends a string, a backquote
    // command, a newline that ends the command, a trailing backslash that continues a comment.
    const std::string hostile = "it's ';system('touch marker1');x=' `touch marker2` $(touch marker3) @ARG0 \u00e9";
    const std::string dataName = "d'\n system('touch marker4') \\";
    std::filesystem::create_directories(dir / "data");
    writeFile(dir / ("data/" + dataName + ".csv"), "x,y\n1,2\n2,3\n");
    const std::string quotedData = "\"data/d'\\n system('touch marker4') \\\\.csv\"";
    const PlotSpec spec = parsePlotSpec("title: \"" + hostile +
                                            "\\nsecond line\"\n"
                                            "labels: [{x: 1, y: 2, text: \"" +
                                            hostile +
                                            "\"}]\n"
                                            "series:\n"
                                            "  - {file: " +
                                            quotedData + ", x: x, y: y, label: \"" + hostile +
                                            "\"}\n"
                                            "  - {file: " +
                                            quotedData + ", x: x, y: y, where: {x: \"1\\n'\"}}\n",
                                        "fig.yaml", dir.path);
    const std::string script = gnuplotScript(spec, dir / "out/fig.gp", "f'ig.png", "f'ig.svg");
    CHECK(script.find("'it''s '';system(''touch marker1'');x='' `touch marker2` $(touch marker3) @ARG0 \u00e9'") !=
          std::string::npos);
    CHECK(script.find("(\'it''s ") != std::string::npos);  // the title's newline splits it into pieces
    CHECK(script.find(".\"\\012\".'second line')") != std::string::npos);
    CHECK(script.find("png_out = ARGC >= 2 ? ARG1 : 'f''ig.png'\n") != std::string::npos);

    if (!vri::commandAvailable("gnuplot")) return;
    std::filesystem::create_directories(dir / "out'; `touch marker5`");
    const std::filesystem::path png = dir / "out'; `touch marker5`" / "it's $(touch marker6).png";
    drawPlot(spec, png);
    CHECK(std::filesystem::file_size(png) > 1000);
    std::ostringstream svg;
    svg << std::ifstream(std::filesystem::path(png).replace_extension(".svg")).rdbuf();
    CHECK(svg.str().find("system(") != std::string::npos);  // the text was drawn, not run
    for (const char* marker : {"marker1", "marker2", "marker3", "marker4", "marker5", "marker6"}) {
        INFO(marker);
        CHECK(!std::filesystem::exists(dir / marker));
        CHECK(!std::filesystem::exists(dir / "out'; `touch marker5`" / marker));
        CHECK(!std::filesystem::exists(dir / "data" / marker));
        CHECK(!std::filesystem::exists(std::filesystem::current_path() / marker));
    }
}

TEST_CASE("plot: a family's line joins its runs in file order, keyed by its ends; log axes fit the data, 0 on a band") {
    test::TempDir dir("plot");
    // The exact rows lie between Riemann's: its line must still join h0.5 to h0.1.
    writeFile(dir / "speed.csv", "run,method,seconds,worst,max\n"
                                 "a-riemann-h0.5,riemann,0.2,20,0.1\n"
                                 "a-exact-eps1e-6,exact,0.7,0,1e-5\n"
                                 "a-riemann-h0.1,riemann,0.5,10,0.02\n"
                                 "a-exact-eps1e-7,exact,0.8,0,1e-6\n");
    const PlotSpec spec = parsePlotSpec(
        "x: {label: seconds, log: true}\n"
        "y: {label: worst, log: true}\n"
        "pareto: true\n"
        "series:\n"
        "  - {file: speed.csv, x: seconds, y: worst, style: linespoints, where: {method: riemann}, label: riemann, "
        "label_ends: run}\n"
        "  - {file: speed.csv, x: seconds, y: worst, style: points, where: {method: exact}, label: exact, label_ends: run}\n",
        "fig.yaml", dir.path);
    // Past the words both ends share; a '-' before a digit is a number's sign, not a word's end.
    CHECK(spec.panels[0].series[0].label == "riemann, h0.5 to h0.1");
    CHECK(spec.panels[0].series[1].label == "exact, eps1e-6 to eps1e-7");
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    auto has = [&](const std::string& text) {
        INFO(text);
        CHECK(script.find(text) != std::string::npos);
    };
    // x: 0.2 to 0.8 with a margin of 1.15 each side, under one decade: a tic at every digit.
    has("    set xtics (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9)\n    set xrange [" + exactNumber(0.2 / 1.15) + ":" +
        exactNumber(0.8 * 1.15) + "] noextend\n");
    // y: 10 to 20 with a margin, and below a break the exact runs' 0 on a band at the bottom of the axis:
    // the band and the break are 5 % and 6 % of the axis, the positive range the rest.
    const double length = std::log10(20 * 1.15 / (10 / 1.15)) / 0.89;
    const double low = 10 / 1.15 / std::pow(10, 0.11 * length), floor = low * std::pow(10, 0.025 * length);
    has("    set ylabel 'worst (0 on the grey band below the break)'\n");
    has("    set ytics ('0' " + exactNumber(floor) + ", 9, 10, 20)\n");
    has("    set object rect from graph 0, graph 0 to graph 1, graph 0.05 fc rgb '#e0e0e0' fs solid 1 noborder behind\n");
    has("    set object rect from graph -0.012, graph 0.05 to graph 0.012, graph 0.11 fc rgb 'white' fs solid 1 noborder "
        "front\n");
    has("    set yrange [" + exactNumber(low) + ":" + exactNumber(20 * 1.15) + "] noextend\n");
    has("$series1_1 << EOD\n0.2,20\n0.5,10\nEOD\n");
    has("$series1_2 << EOD\n0.7," + exactNumber(floor) + "\n0.8," + exactNumber(floor) + "\nEOD\n");
    has("plot $series1_1 using 1:2 with linespoints lw 2 pt 7 ps 0.8 title 'riemann, h0.5 to h0.1', \\\n"
        "         $series1_2 using 1:2 with points pt 7 ps 0.8 title 'exact, eps1e-6 to eps1e-7'");
    // The front runs from the fastest run down to the band, where the exact run is as good as it gets.
    has("$pareto1 << EOD\n0.2,20\n0.5,10\n0.7," + exactNumber(floor) + "\nEOD\n");
    // Every panel resets what the last one set.
    has("    unset arrow\n    unset object\n");
    if (vri::commandAvailable("gnuplot")) drawPlot(spec, dir / "fig.png");

    CHECK(errorOf("series:\n  - {file: speed.csv, x: seconds, y: max, label_ends: name}\n", dir.path) ==
          "fig.yaml:2:55: column 'name' is not in " + (dir / "speed.csv").string() +
              " (it has: run, method, seconds, worst, max)");
    CHECK(errorOf("series:\n  - {file: speed.csv, x: seconds, y: max, x2: seconds, y2: max, style: segments, "
                  "label_ends: run}\n",
                  dir.path) ==
          "fig.yaml:2:94: series[0].label_ends is not for style segments (only for line, dashed, dotted, points, "
          "linespoints)");
}

TEST_CASE("plot: a log axis given a range, or spanning decades, keeps gnuplot's tics") {
    test::TempDir dir("plot");
    writeFile(dir / "e.csv", "h,error\n0.5,1e-2\n0.1,1e-6\n");
    const std::string script = gnuplotScript(parsePlotSpec("x: {label: h, log: true, range: [0.01, 1]}\n"
                                                           "y: {label: error, log: true}\n"
                                                           "series:\n  - {file: e.csv, x: h, y: error}\n",
                                                           "fig.yaml", dir.path),
                                             dir / "fig.gp", "fig.png", "fig.svg");
    CHECK(script.find("    set xtics autofreq\n    set xrange [0.01:1] extend\n") != std::string::npos);
    const double margin = std::pow(1e4, 0.06);  // four decades: 6 % of the span at each end
    CHECK(script.find("    set ytics autofreq\n    set yrange [" + exactNumber(1e-6 / margin) + ":" +
                      exactNumber(1e-2 * margin) + "] noextend\n") != std::string::npos);
    CHECK(script.find("    set arrow from") == std::string::npos);
}

TEST_CASE("plot: a log axis with zeros keeps its tic labels apart, the band's 0 below a break") {
    PlotAxis axis;
    axis.log = true;
    // Counts from one ray to many (paper B's histograms), narrow ranges, and many decades.
    for (const auto& [lo, hi] : {std::pair{1.0, 3e4}, {4.0, 2e4}, {1.0, 2.0}, {0.3, 0.9}, {1e-30, 1.0}, {7.0, 700.0}}) {
        INFO(lo, " to ", hi);
        const auto fit = plot::fitLogAxis(axis, {0, lo, hi, -1});
        REQUIRE(fit);
        REQUIRE(fit->zero);
        CHECK(plot::axisFraction(*fit, *fit->zero) == doctest::Approx(plot::kZeroBand / 2));
        CHECK(plot::axisFraction(*fit, fit->bottom) == doctest::Approx(plot::kZeroBand + plot::kZeroGap));
        CHECK(fit->bottom < lo);
        REQUIRE(!fit->tics.empty());
        double below = plot::axisFraction(*fit, *fit->zero);
        for (double tic : fit->tics) {
            INFO(tic);
            CHECK(tic >= fit->bottom);  // none in the break or the band
            CHECK(plot::axisFraction(*fit, tic) - below >= plot::kMinTicSpacing);
            below = plot::axisFraction(*fit, tic);
        }
    }
}

TEST_CASE("plot: reference slopes, data tics and a key below the panel") {
    test::TempDir dir("plot");
    writeFile(dir / "o.csv", "h,error\n0.2,0.1\n0.1,0.03\n0.05,0.01\n0.0125,1e-3\n");
    const PlotSpec spec = parsePlotSpec("x: {label: h, log: true, ticks: data}\n"
                                        "y: {label: error, log: true}\n"
                                        "key: below\n"
                                        "reference_slopes: [1, 2, 4]\n"
                                        "series:\n  - {file: o.csv, x: h, y: error}\n",
                                        "fig.yaml", dir.path);
    CHECK(spec.panels[0].referenceSlopes == std::vector<double>{1, 2, 4});
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    auto has = [&](const std::string& text) {
        INFO(text);
        CHECK(script.find(text) != std::string::npos);
    };
    has("    set xtics (0.0125, 0.05, 0.1, 0.2)\n");  // every step, the smallest too
    // One column, in a margin of its one entry and four lines for the x axis's tics and label.
    has("    set key below vertical maxcols 1\n    set bmargin 5\n");
    for (const char* order : {"order 1", "order 2", "order 4"})
        has("    set label '" + std::string(order) + "' at ");
    has(" nohead dt 2 lw 1 lc rgb 'gray50' back\n");
    if (vri::commandAvailable("gnuplot")) drawPlot(spec, dir / "fig.png");

    // Through the rightmost point (0.2, 0.1), cut to the box: order 1 runs across, order 4 enters at the bottom.
    const auto lines = plot::referenceLines({1, 4}, {0.2, 0.1}, 0.01, 0.25, 1e-4, 0.2);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].x1 == doctest::Approx(0.01));
    CHECK(lines[0].y1 == doctest::Approx(0.005));
    CHECK(lines[0].x2 == doctest::Approx(0.25));
    CHECK(lines[0].y2 == doctest::Approx(0.125));
    CHECK(lines[1].y1 == doctest::Approx(1e-4));
    CHECK(lines[1].x1 == doctest::Approx(0.2 * std::pow(1e-3, 0.25)));
    CHECK(lines[1].y2 == doctest::Approx(0.2));
    CHECK(lines[1].x2 == doctest::Approx(0.2 * std::pow(2.0, 0.25)));

    const std::string series = "series:\n  - {file: o.csv, x: h, y: error}\n";
    CHECK(errorOf("x: {log: true}\nreference_slopes: [1, 2]\n" + series, dir.path) ==
          "fig.yaml:2:19: reference_slopes needs log x and y axes (x: {log: true}, y: {log: true})");
    CHECK(errorOf("x: {log: true}\ny: {log: true}\nreference_slopes: [1, -2]\n" + series, dir.path) ==
          "fig.yaml:3:23: reference_slopes[1] must be a positive number");
    CHECK(errorOf("x: {log: true}\ny: {log: true}\nreference_slopes: 2\n" + series, dir.path) ==
          "fig.yaml:3:19: reference_slopes must be a non-empty list of orders, such as [1, 2, 4]");
    CHECK(errorOf("x: {ticks: every}\n" + series, dir.path) ==
          "fig.yaml:1:12: x.ticks 'every' is unknown (expected auto or data)");
    CHECK(errorOf("key: under\n" + series, dir.path) ==
          "fig.yaml:1:6: key 'under' is unknown (expected top left, top right, bottom left, bottom right, outside, "
          "below or off)");
    writeFile(dir / "hist.csv", "bin_lo,bin_hi,R\n0,1e-3,1\n1e-3,1e-2,3\n");
    CHECK(errorOf("x: {log: true, ticks: data}\nseries:\n  - {file: hist.csv, y: R, style: histogram}\n", dir.path) ==
          "fig.yaml:1:23: x.ticks is for panels of points and lines only (no histogram, heatmap or segments)");
}

TEST_CASE("plot: group_by makes a series per family, each in a colour-blind-safe colour and point of its own") {
    test::TempDir dir("plot");
    writeFile(dir / "s.csv",
              "run,method,seconds,max\nr-h1,riemann,1,0.1\nr-h0.5,riemann,2,0.05\nc-h1,composite,1.1,0.01\n"
              "x,exact,3,1e-7\nt-h1,three.js,0.5,0.9\n");
    const PlotSpec spec = parsePlotSpec("series:\n"
                                        "  - {file: s.csv, x: seconds, y: max, style: linespoints, group_by: method, "
                                        "label_ends: run}\n",
                                        "fig.yaml", dir.path);
    const std::vector<PlotSeries>& series = spec.panels[0].series;
    REQUIRE(series.size() == 4);  // in the order the families first appear
    CHECK(series[0].label == "riemann, h1 to h0.5");  // each keyed by its family and its own ends
    CHECK(series[1].label == "composite");
    CHECK(series[3].label == "three.js");
    CHECK(series[2].where == std::vector<std::pair<int, std::string>>{{2, "exact"}});
    std::set<std::pair<std::string, std::string>> looks;
    for (const PlotSeries& s : series) looks.insert({s.color, s.point});
    CHECK(looks.size() == series.size());
    CHECK(series[0].color == "#0072B2");  // Okabe and Ito's, darkest first
    // A colour given holds for every family; a where keeps its rows before they are grouped.
    const PlotSpec blue = parsePlotSpec("series:\n  - {file: s.csv, x: seconds, y: max, group_by: method, "
                                        "color: \"#112233\", where: {method: riemann}}\n",
                                        "fig.yaml", dir.path);
    REQUIRE(blue.panels[0].series.size() == 1);
    CHECK(blue.panels[0].series[0].color == "#112233");
    CHECK(errorOf("series:\n  - {file: s.csv, x: seconds, y: max, group_by: colour}\n", dir.path).find(
              "column 'colour' is not in") != std::string::npos);
}

TEST_CASE("plot: a key below grows the canvas and gives every panel its margin") {
    test::TempDir dir("plot");
    writeFile(dir / "o.csv", "h,error\n0.2,0.1\n0.1,0.03\n");
    const std::string series = "    series:\n      - {file: o.csv, x: h, y: error}\n      - {file: o.csv, x: h, y: error}\n";
    const PlotSpec spec = parsePlotSpec("size: [800, 400]\ngrid: [1, 2]\npanels:\n  - key: off\n" + series +
                                            "  - key: below\n" + series,
                                        "fig.yaml", dir.path);
    const std::string script = gnuplotScript(spec, dir / "fig.gp", "fig.png", "fig.svg");
    INFO(script);
    // Two entries and four lines: 6 lines of 16 pixels added to the 400 the plots keep.
    CHECK(script.find("size 800,496 ") != std::string::npos);
    CHECK(script.find("    set bmargin 6\n    unset key\n") != std::string::npos);  // the keyless panel too
    CHECK(script.find("    set key below vertical maxcols 1\n    set bmargin 6\n") != std::string::npos);
}
