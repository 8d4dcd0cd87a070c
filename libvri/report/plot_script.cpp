// Writing the gnuplot script of a figure, with the Pareto front it may mark and its heatmaps' grids.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <optional>

#include "libvri/report/pareto.h"
#include "libvri/report/plot_axes.h"
#include "libvri/report/plot.h"
#include "libvri/report/plot_csv.h"
#include "libvri/report/plot_slopes.h"
#include "libvri/util/csv.h"
#include "libvri/util/format.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// Any text as a gnuplot string expression that evaluates to exactly that text. Inside gnuplot's
// single quotes nothing is special (no backquote command, no @macro, no backslash escape) except
// the quote, written twice, and the end of the line, which ends the command. Two exceptions, found
// by trying gnuplot 5.4: a string cannot start with a written-twice quote ('''' reads as the empty
// string and a stray quote), and cannot hold a newline. So a leading quote goes as "'" and a control
// character as an octal escape ("\012"), in double quotes that hold nothing else (gnuplot runs
// backquotes inside double quotes), and the pieces are joined with gnuplot's `.`, in parentheses.
// Plot titles, labels, file names and `eq` all take such an expression.
std::string quoted(const std::string& text) {
    std::vector<std::string> pieces;
    bool inQuotes = false;
    for (char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f || (c == '\'' && !inQuotes)) {
            if (inQuotes) pieces.back() += '\'';
            inQuotes = false;
            char escape[8] = "\"'\"";
            if (c != '\'') std::snprintf(escape, sizeof escape, "\"\\%03o\"", byte);
            pieces.emplace_back(escape);
            continue;
        }
        if (!inQuotes) pieces.emplace_back("'");
        inQuotes = true;
        pieces.back() += c == '\'' ? std::string("''") : std::string(1, c);
    }
    if (inQuotes) pieces.back() += '\'';
    if (pieces.empty()) return "''";
    if (pieces.size() == 1) return pieces.front();
    std::string joined = "(";
    for (const std::string& piece : pieces) joined += (joined.size() == 1 ? "" : ".") + piece;
    return joined + ")";
}

// What fitLogAxis made of a panel's log axes (nullopt: the spec's range, or gnuplot's), the tics of
// an axis with `ticks: data` (every distinct value drawn on it), and the panel's reference slopes.
struct PanelFit {
    std::optional<plot::LogAxisFit> x, y;
    std::vector<double> xTics, yTics;
    std::vector<plot::ReferenceLine> references;
};

// A list of tics for `set xtics (...)`, the band's 0 first where there is one.
std::string ticList(const std::vector<double>& tics, std::optional<double> zero) {
    std::string out = zero ? "'0' " + exactNumber(*zero) : "";
    for (double tic : tics) out += (out.empty() ? "" : ", ") + exactNumber(tic);
    return "(" + out + ")";
}

// The band of values <= 0 at the bottom of a y axis, and the break above it: the border is cut there
// (a white patch over each side, in front of everything) and marked with slanted strokes at both ends
// of the cut. In graph units, since the band and the break are fractions of the axis.
std::string zeroBandCommands() {
    const auto graph = [](double x, double y) { return "graph " + exactNumber(x) + ", graph " + exactNumber(y); };
    const double band = plot::kZeroBand, top = plot::kZeroBand + plot::kZeroGap;
    std::string out = "    set object rect from " + graph(0, 0) + " to " + graph(1, band) +
                      " fc rgb '#e0e0e0' fs solid 1 noborder behind\n";
    for (double side : {0.0, 1.0}) {
        out += "    set object rect from " + graph(side - 0.012, band) + " to " + graph(side + 0.012, top) +
               " fc rgb 'white' fs solid 1 noborder front\n";
        for (double at : {band, top})
            out += "    set arrow from " + graph(side - 0.012, at - 0.01) + " to " + graph(side + 0.012, at + 0.01) +
                   " nohead lw 1 lc rgb 'black' front\n";
    }
    return out;
}

// A heatmap's axes end where its image does (fit), other axes at a tic mark beyond the data, and a log
// axis the spec leaves open where plot::fitLogAxis says, with its values <= 0 on a band below a break;
// its label says so. An axis with `ticks: data` is labelled at dataTics alone.
std::string axisCommands(const char* name, const PlotAxis& axis, bool fit, const std::optional<plot::LogAxisFit>& log,
                         const std::vector<double>& dataTics) {
    const std::string n = name;
    const bool band = log && log->zero;
    const std::string note = "0 on the grey band below the break";
    const std::string label = !band ? axis.label : axis.label.empty() ? note : axis.label + " (" + note + ")";
    std::string out = "    set " + n + "label " + quoted(label) + "\n";
    // A log axis labels its decades 1e-06 ... 0.01 ... 1, not 0.0000010 with gnuplot's fixed decimals.
    out += axis.log ? "    set logscale " + n + "\n    set format " + n + " '%g'\n"
                    : "    unset logscale " + n + "\n    set format " + n + " '% h'\n";
    std::vector<double> tics = log ? log->tics : std::vector<double>{};
    if (axis.dataTics) tics = dataTics;
    if (tics.empty() && !band)
        out += "    set " + n + "tics autofreq\n";
    else
        out += "    set " + n + "tics " + ticList(tics, band ? log->zero : std::nullopt) + "\n";
    if (!log)
        return out + "    set " + n + "range [" + (axis.min ? exactNumber(*axis.min) : "*") + ":" +
               (axis.max ? exactNumber(*axis.max) : "*") + "]" + (fit ? " noextend" : " extend") + "\n";
    if (band) out += zeroBandCommands();  // only y has one (fitPanel gives x its positive values alone)
    return out + "    set " + n + "range [" + exactNumber(log->min) + ":" + exactNumber(log->max) + "] noextend\n";
}

// A key below the plot is one column of entries, under the x axis's tics and label: `belowRows` lines of
// margin hold the longest such key of the figure, and every panel of such a figure gets them, keyed below or
// not, so that every panel's plot is as high as its neighbours' (gnuplot would shrink each panel by its own
// key). In a figure without such a key (belowRows 0) the margin is gnuplot's.
std::string keyCommand(const std::string& key, int belowRows) {
    if (key == "below")
        return "    set key below vertical maxcols 1\n    set bmargin " + std::to_string(belowRows) + "\n";
    std::string out = belowRows > 0 ? "    set bmargin " + std::to_string(belowRows) + "\n" : "    set bmargin\n";
    if (key == "off") return out + "    unset key\n";
    if (key == "outside") return out + "    set key outside right top\n";
    return out + "    set key " + key + "\n";
}

// The height of a line of text in the figures' 10-point sans font, in pixels.
constexpr int kKeyLinePixels = 16;

// The lines of bottom margin that the figure's longest key below a panel needs: its entries, and four
// for the x tic labels, the x label and the space around them.
int belowRows(const PlotSpec& spec) {
    const auto keyed = [](const PlotSeries& s) { return s.style != "heatmap" && !s.label.empty(); };
    std::ptrdiff_t most = 0;
    for (const PlotPanel& panel : spec.panels)
        if (panel.key == "below") most = std::max(most, panel.pareto + std::ranges::count_if(panel.series, keyed));
    return static_cast<int>(most) + 4;
}

// Colours from the lowest value to the highest, at evenly spaced stops.
std::string paletteCommand(const std::string& palette) {
    if (palette == "gray") return "    set palette defined (0 '#000000', 1 '#ffffff')\n";
    if (palette == "diverging") return "    set palette defined (0 '#3b4cc0', 1 '#f2f2f2', 2 '#b40426')\n";
    return "    set palette defined (0 '#440154', 1 '#482878', 2 '#3e4a89', 3 '#31688e', 4 '#26828e', 5 '#1f9e89', "
           "6 '#35b779', 7 '#6dcd59', 8 '#b4de2c', 9 '#fde725')\n";  // viridis
}

// Everything a panel sets before it plots; what one panel sets, the next resets, so that no
// setting leaks into a later panel (or from the PNG's last panel into the SVG's first).
std::string panelCommands(const PlotPanel& panel, const PanelFit& fit, int keyRows) {
    const bool heatmap = panel.hasStyle("heatmap");
    std::string out = "    set title " + quoted(panel.title) + "\n    unset arrow\n";
    out += "    unset object\n";
    out += axisCommands("x", panel.x, heatmap, fit.x, fit.xTics) +
           axisCommands("y", panel.y, heatmap, fit.y, fit.yTics) + keyCommand(panel.key, keyRows);
    out += panel.equalAspect ? "    set size ratio -1\n" : "    set size noratio\n";
    out += "    unset label\n";
    for (const PlotLabel& label : panel.labels)
        out += "    set label " + quoted(label.text) + " at " + exactNumber(label.x) + "," + exactNumber(label.y) +
               " front\n";
    // Each reference line labelled at its left end, above it: the lines fan out leftwards from one point, so
    // their labels lie furthest apart there.
    for (const plot::ReferenceLine& line : fit.references) {
        const std::string from = exactNumber(line.x1) + ", " + exactNumber(line.y1);
        out += "    set arrow from " + from + " to " + exactNumber(line.x2) + ", " + exactNumber(line.y2) +
               " nohead dt 2 lw 1 lc rgb 'gray50' back\n";
        out += "    set label " + quoted("order " + exactNumber(line.order)) + " at " + from +
               " left offset char 0.5, char 0.6 tc rgb '#404040' front\n";
    }
    if (heatmap) {
        const PlotColorbar& bar = panel.colorbar;
        out += paletteCommand(bar.palette);
        out += "    set cbrange [" + (bar.min ? exactNumber(*bar.min) : "*") + ":" +
               (bar.max ? exactNumber(*bar.max) : "*") + "]\n";
        out += "    set cblabel " + quoted(bar.label) + "\n    set colorbox\n";
    }
    return out;
}

// gnuplot's filled circle, filled square, cross, filled triangle (up and down) and filled diamond.
int pointType(const std::string& point) {
    if (point == "square") return 5;
    if (point == "diamond") return 13;
    if (point == "cross") return 2;
    if (point == "triangle") return 9;
    if (point == "triangle-down") return 11;
    return 7;
}

std::string styleClause(const PlotSeries& series) {
    const std::string colour = series.color.empty() ? "" : " lc rgb " + quoted(series.color);
    const std::string width = " lw " + exactNumber(series.width);
    const std::string point = " pt " + std::to_string(pointType(series.point)) + " ps " + exactNumber(series.pointSize);
    if (series.style == "histogram") return "with boxxyerror fs transparent solid 0.35 border" + colour;
    if (series.style == "heatmap") return "with image";
    if (series.style == "segments") return "with vectors nohead" + width + colour;
    if (series.style == "points") return "with points" + point + colour;
    if (series.style == "linespoints") return "with linespoints" + width + point + colour;
    if (series.style == "dashed") return "with lines" + width + " dt 2" + colour;
    if (series.style == "dotted") return "with lines" + width + " dt 3" + colour;
    return "with lines" + width + colour;
}

// The y column, or NaN (which gnuplot skips) on the rows that `where` leaves out.
std::string yExpression(const PlotSeries& series) {
    const std::string y = std::to_string(series.yColumn);
    if (series.where.empty()) return y;
    std::string condition;
    for (const auto& [column, text] : series.where) {
        const std::string cell = "strcol(" + std::to_string(column) + ")";
        condition += (condition.empty() ? "" : " && ") +
                     (text.ends_with('*') ? "strstrt(" + cell + ", " + quoted(text.substr(0, text.size() - 1)) + ") == 1"
                                          : cell + " eq " + quoted(text));
    }
    return "(" + condition + " ? $" + y + " : NaN)";
}

std::string usingClause(const PlotSeries& series) {
    const std::string x = std::to_string(series.xColumn), y = yExpression(series);
    if (series.style == "heatmap") return "using 1:2:3";  // its datablock's columns
    if (series.style == "segments") {
        // From (x, y) by (x2 - x, y2 - y).
        const std::string x2 = std::to_string(series.x2Column), y2 = std::to_string(series.y2Column);
        const std::string y1 = std::to_string(series.yColumn);
        return "using " + x + ":" + y + ":($" + x2 + " - $" + x + "):($" + y2 + " - $" + y1 + ")";
    }
    if (series.style != "histogram") return "using " + x + ":" + y;
    // Boxes from bin_lo to bin_hi (the next column) and from 0 to the count. Only bins with finite,
    // positive edges are drawn (a log axis has no room for the others): vri-diff's zero bin, its
    // first bin (0, lo] and its overflow bin (hi, inf) are left out.
    const std::string hi = std::to_string(series.xColumn + 1);
    std::string clause = "using (($";
    clause.append(x).append(" > 0 && $").append(hi).append(" < 1e300) ? ($").append(x).append(" + $").append(hi);
    clause.append(") / 2 : NaN):($").append(y).append(" / 2):").append(x).append(":").append(hi);
    return clause.append(":(0):($").append(y).append(")");
}

// Where gnuplot reads a series from: its CSV past the header, or for a heatmap the datablock that
// holds the CSV's grid in scan order.
std::string dataSource(const PlotSeries& series, std::size_t panel, std::size_t index, const fs::path& scriptDir) {
    if (series.style == "heatmap") return "$heatmap" + std::to_string(panel + 1) + "_" + std::to_string(index + 1);
    return quoted(fs::relative(fs::absolute(series.file), scriptDir).generic_string()) + " skip 1";
}

std::string heatmapBlock(const PlotSeries& series, std::size_t panel, std::size_t index, const fs::path& scriptDir) {
    // Names in comments are quoted too: a newline in one would end the comment, a trailing backslash
    // would continue it onto the next line.
    std::string out = "# " + quoted(fs::relative(fs::absolute(series.file), scriptDir).generic_string()) +
                      " as x,y,z in scan order, which gnuplot's image needs\n";
    out += dataSource(series, panel, index, scriptDir) + " << EOD\n";
    for (const auto& [x, y, z] : plot::gridRows(series.file, series.xColumn, series.yColumn, series.zColumn))
        out.append(x).append(",").append(y).append(",").append(z).append("\n");
    return out + "EOD\n";
}

// Each point's text from the series' labels column, right of and above the point, clear of its
// marker; the rows that `where` leaves out get none.
std::string labelsClause(const PlotSeries& series) {
    const std::string colour = series.color.empty() ? "" : " tc rgb " + quoted(series.color);
    return "using " + std::to_string(series.xColumn) + ":" + yExpression(series) + ":(strcol(" +
           std::to_string(series.labelColumn) + ")) with labels left offset char 0.5,0.5 font ',8'" + colour +
           " notitle";
}

bool drawsPoints(const PlotSeries& series) {
    return series.style != "histogram" && series.style != "heatmap" && series.style != "segments";
}

// The panel's points from every series of points or lines, for its Pareto front: the points drawn,
// so not the rows that a series' `where` leaves out.
std::vector<std::pair<double, double>> panelPoints(const PlotPanel& panel) {
    std::vector<std::pair<double, double>> points;
    for (const PlotSeries& series : panel.series)
        if (drawsPoints(series)) std::ranges::copy(plot::keptPoints(series), std::back_inserter(points));
    return points;
}

// The distinct values drawn on an axis, in increasing order, for its `ticks: data`; a log axis's positive ones.
std::vector<double> dataTics(std::vector<double> values, bool log) {
    std::erase_if(values, [&](double v) { return log && v <= 0; });
    std::ranges::sort(values);
    values.erase(std::unique(values.begin(), values.end()), values.end());
    return values;
}

// Reference lines through the rightmost point on both log axes (the highest at that x), where a convergence
// study's largest step is, across the panel's box above any break: a series that runs parallel to one has
// its order.
std::vector<plot::ReferenceLine> referenceLines(const PlotPanel& panel, const PanelFit& fit,
                                                const std::vector<std::pair<double, double>>& points) {
    std::optional<std::pair<double, double>> anchor;
    for (const auto& point : points)
        if (point.first > 0 && point.second > 0 && (!anchor || point > *anchor)) anchor = point;
    const auto xmin = fit.x ? std::optional(fit.x->min) : panel.x.min,
               xmax = fit.x ? std::optional(fit.x->max) : panel.x.max;
    const auto ymin = fit.y ? std::optional(fit.y->bottom) : panel.y.min,
               ymax = fit.y ? std::optional(fit.y->max) : panel.y.max;
    if (!anchor || !xmin || !xmax || !ymin || !ymax) return {};
    return plot::referenceLines(panel.referenceSlopes, *anchor, *xmin, *xmax, *ymin, *ymax);
}

// The panel's log axes fitted to its points, its data tics and its reference lines; a panel with
// histograms, heatmaps or segments keeps gnuplot's axes (and takes neither `ticks: data` nor slopes).
PanelFit fitPanel(const PlotPanel& panel) {
    if (!std::ranges::all_of(panel.series, drawsPoints)) return {};
    const auto points = panelPoints(panel);
    std::vector<double> xs, ys;
    for (const auto& [x, y] : points) xs.push_back(x), ys.push_back(y);
    PanelFit fit;
    std::vector<double> positiveXs;  // only y has a band: a log x axis leaves out x <= 0, as gnuplot does
    std::ranges::copy_if(xs, std::back_inserter(positiveXs), [](double x) { return x > 0; });
    fit.x = plot::fitLogAxis(panel.x, positiveXs);
    fit.y = plot::fitLogAxis(panel.y, ys);
    if (panel.x.dataTics) fit.xTics = dataTics(xs, panel.x.log);
    if (panel.y.dataTics) fit.yTics = dataTics(ys, panel.y.log);
    fit.references = referenceLines(panel, fit, points);
    return fit;
}

// A series is drawn from a datablock of the points it keeps when its line joins the rows that `where`
// keeps (gnuplot would break the line at every row left out, and one family's runs need not follow each
// other in a file), and on a panel whose y axis has a band for its values <= 0 (they are drawn there).
bool drawnFromBlock(const PlotSeries& series, const PanelFit& fit) {
    if (!drawsPoints(series)) return false;
    const bool joins = series.style == "line" || series.style == "dashed" || series.style == "dotted" ||
                       series.style == "linespoints";
    return (joins && !series.where.empty()) || (fit.y && fit.y->zero);
}

// A datablock of x,y rows.
std::string pointsBlock(const std::string& name, const std::vector<std::pair<double, double>>& points) {
    std::string out = name + " << EOD\n";
    for (const auto& [x, y] : points) out += exactNumber(x) + "," + exactNumber(y) + "\n";
    return out + "EOD\n";
}

std::string blockName(const char* kind, std::size_t panel, std::size_t series) {
    return "$" + std::string(kind) + std::to_string(panel + 1) + "_" + std::to_string(series + 1);
}

// Whether a point has a place on the panel's log axes.
bool onLogAxes(const PlotPanel& panel, const std::pair<double, double>& point) {
    return !(panel.x.log && point.first <= 0) && !(panel.y.log && point.second <= 0);
}

}  // namespace

std::string gnuplotScript(const PlotSpec& spec, const fs::path& scriptPath, const std::string& pngName,
                          const std::string& svgName) {
    const fs::path scriptDir = fs::absolute(scriptPath).parent_path();
    std::string out = "# Generated by vri-plot from " + quoted(spec.source) + ". Redraw by hand with: gnuplot " +
                      quoted(scriptPath.filename().string()) +
                      "\n# It writes the PNG and SVG beside itself, or where its two arguments say:\n"
                      "#   gnuplot -c " + quoted(scriptPath.filename().string()) + " /tmp/a.png /tmp/a.svg\n"
                      "# (arguments are never parsed as gnuplot code, whatever characters they hold).\n";
    out += "png_out = ARGC >= 2 ? ARG1 : " + quoted(pngName) + "\n";
    out += "svg_out = ARGC >= 2 ? ARG2 : " + quoted(svgName) + "\n";
    out += "# Data paths are relative to this script's folder: go there.\n"
           "script_dir = ARG0\n"
           "i = strlen(script_dir)\n"
           "while (i > 0 && script_dir[i:i] ne \"/\") { i = i - 1 }\n"
           "cd (i > 0 ? script_dir[1:i] : \".\")\n"
           "set datafile separator comma\n";
    std::vector<PanelFit> fits;
    for (std::size_t p = 0; p < spec.panels.size(); ++p) {
        const PlotPanel& panel = spec.panels[p];
        const PanelFit& fit = fits.emplace_back(fitPanel(panel));
        for (std::size_t s = 0; s < panel.series.size(); ++s) {
            const PlotSeries& series = panel.series[s];
            if (series.style == "heatmap") out += heatmapBlock(series, p, s, scriptDir);
            if (!drawnFromBlock(series, fit)) continue;
            std::vector<std::pair<double, double>> drawn;
            for (auto [x, y] : plot::keptPoints(series)) {
                if (fit.y && fit.y->zero && y <= 0) y = *fit.y->zero;
                if (onLogAxes(panel, {x, y})) drawn.emplace_back(x, y);
            }
            out += pointsBlock(blockName("series", p, s), drawn);
        }
        if (!panel.pareto) continue;
        auto points = panelPoints(panel);
        if (fit.y && fit.y->zero)  // a front through a value of 0 runs down to the band
            for (auto& point : points) point.second = point.second <= 0 ? *fit.y->zero : point.second;
        const auto front = paretoFront(points);
        out += "$pareto" + std::to_string(p + 1) + " << EOD\n";
        for (std::size_t k = 0; k < front.size(); ++k) {
            const auto& [x, y] = points[front[k]];
            if (k == 0 || points[front[k]] != points[front[k - 1]])  // equal points are one vertex of the line
                out += exactNumber(x) + "," + exactNumber(y) + "\n";
        }
        out += "EOD\n";
    }
    // A key below a panel gets lines of its own: the canvas grows by them, so that the plots keep the height
    // the spec gives them however long the key (gnuplot would take the lines from the plot).
    const bool keyBelow = std::ranges::any_of(spec.panels, [](const PlotPanel& p) { return p.key == "below"; });
    const int height = spec.height + (keyBelow ? spec.rows * belowRows(spec) * kKeyLinePixels : 0);
    const std::string size = std::to_string(spec.width) + "," + std::to_string(height);
    out += "do for [format in \"png svg\"] {\n"
           "    if (format eq \"png\") {\n"
           "        set terminal pngcairo size " + size + " noenhanced font \"sans,10\"\n"
           "        set output png_out\n"
           "    } else {\n"
           "        set terminal svg size " + size + " noenhanced font \"sans,10\" background \"white\"\n"
           "        set output svg_out\n"
           "    }\n";
    out += "    set multiplot layout " + std::to_string(spec.rows) + "," + std::to_string(spec.columns) +
           (spec.title.empty() ? "" : " title " + quoted(spec.title)) + "\n";
    for (std::size_t p = 0; p < spec.panels.size(); ++p) {
        const PlotPanel& panel = spec.panels[p];
        out += "    # panel " + std::to_string(p + 1) + "\n";
        out += panelCommands(panel, fits[p], keyBelow ? belowRows(spec) : 0) + "    plot ";
        for (std::size_t s = 0; s < panel.series.size(); ++s) {
            const PlotSeries& series = panel.series[s];
            // A heatmap is keyed by its colour bar, not in the legend.
            const std::string title = series.style == "heatmap" || series.label.empty() ? "notitle" : "title " + quoted(series.label);
            const std::string source = dataSource(series, p, s, scriptDir);
            const std::string drawn = drawnFromBlock(series, fits[p]) ? blockName("series", p, s) + " using 1:2"
                                                                      : source + " " + usingClause(series);
            out += (s == 0 ? "" : ", \\\n         ") + drawn + " " + styleClause(series) + " " + title;
            if (series.labelColumn != 0) out += ", \\\n         " + source + " " + labelsClause(series);
        }
        if (panel.pareto)
            out += ", \\\n         $pareto" + std::to_string(p + 1) +
                   " using 1:2 with linespoints dt 2 lw 1 pt 6 ps 2 lc rgb 'black' title 'Pareto front'";
        out += "\n";
    }
    out += "    unset multiplot\n"
           "    unset output\n"
           "}\n";
    return out;
}

}  // namespace vri
