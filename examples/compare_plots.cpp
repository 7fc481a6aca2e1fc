#include "examples/compare_plots.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

bool gnuplot_on_path() {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty() && access((fs::path(dir) / "gnuplot").c_str(), X_OK) == 0) return true;
    return false;
}

// A gnuplot string literal: double quotes, with \ and " escaped and line breaks as \n.
std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        if (c == '\\' || c == '"') out += '\\';
        out += c;
    }
    return out + "\"";
}

struct Series {
    std::string title;
    std::vector<std::pair<double, double>> points;
};

struct Plot {
    std::string name;  // file stem
    std::string xlabel, ylabel;
    bool log_x = false, log_y = false;
    std::vector<Series> series;
    std::vector<std::string> extra;  // gnuplot commands before `plot` (the crossover marks)
};

// Runs gnuplot on `script`, writing through a temporary beside `target` that is renamed into
// place only when gnuplot succeeded.
void run_gnuplot(const std::string& script, const fs::path& target) {
    char script_path[] = "/tmp/tessera-plot-XXXXXX";
    const int fd = mkstemp(script_path);
    if (fd < 0) throw Error("--plots: cannot create a temporary file for gnuplot");
    close(fd);
    const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".tmp");
    {
        std::ofstream out(script_path);
        out << "set output " << quoted(temporary.string()) << "\n" << script;
    }
    std::string output;
    FILE* pipe = popen(("gnuplot " + std::string(script_path) + " 2>&1").c_str(), "r");
    if (pipe) {
        char buffer[512];
        while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    }
    const int status = pipe ? pclose(pipe) : -1;
    std::remove(script_path);
    std::error_code ec;
    if (status != 0 || !fs::exists(temporary, ec)) {
        fs::remove(temporary, ec);
        std::string first = output.substr(0, output.find('\n'));
        throw Error("--plots: gnuplot failed on " + target.string() + (first.empty() ? "" : ": " + first));
    }
    fs::rename(temporary, target, ec);
    if (ec) throw Error("cannot write '" + target.string() + "': " + ec.message());
}

std::string script_for(const Plot& plot, const ComparisonReport& r) {
    std::ostringstream s;
    s.precision(9);
    s << "set terminal pngcairo size 960,600 font 'sans,10'\n"
      << "set title " << quoted(r.content + ", " + std::to_string(r.triangles) + " triangles\n" + r.cpu + ", " + r.date)
      << " noenhanced\n"
      << "set xlabel " << quoted(plot.xlabel) << "\nset ylabel " << quoted(plot.ylabel) << "\n"
      << "set key outside right top noenhanced\nset grid\n";
    if (plot.log_x) s << "set logscale x\n";
    if (plot.log_y) s << "set logscale y\n";
    for (const std::string& line : plot.extra) s << line << "\n";
    std::string plots;
    for (size_t i = 0; i < plot.series.size(); ++i) {
        s << "$d" << i << " << EOD\n";
        for (const auto& [x, y] : plot.series[i].points) s << x << " " << y << "\n";
        s << "EOD\n";
        plots += (i ? ", " : "") + std::string("$d") + std::to_string(i) + " using 1:2 with linespoints lw 2 title " +
                 quoted(plot.series[i].title);
    }
    s << "plot " << plots << "\n";
    return s.str();
}

// Times never reach a log axis at zero (a stage that did not run).
double positive(double ms) { return ms > 0.0 ? ms : 1e-6; }

}  // namespace

void check_plots(const fs::path& dir) {
    if (!gnuplot_on_path())
        throw Error("--plots needs gnuplot, which is not on PATH (Debian package gnuplot-nox); "
                    "run without --plots for the table and JSON only");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw Error("cannot write '" + dir.string() + "': " +
                                                  (ec ? ec.message() : std::string("not a directory")));
    check_writable(dir / "time_vs_threads.png");
}

std::vector<std::string> write_plots(const fs::path& dir, const ComparisonReport& r) {
    std::vector<Plot> plots;
    if (!r.sweep.empty()) {
        Plot p{"time_vs_triangles", "triangles (copies of the content)", "ms (median)", true, true, {}, {}};
        Series raster_frame{"raster frame", {}}, rays_frame{"raytrace frame", {}},
            raster_vis{"raster visibility", {}}, rays_vis{"primary rays", {}};
        for (const SweepPoint& s : r.sweep) {
            const double t = double(s.triangles);
            raster_frame.points.push_back({t, positive(s.raster.frame_ms)});
            rays_frame.points.push_back({t, positive(s.raytrace.frame_ms)});
            raster_vis.points.push_back({t, positive(s.raster.visibility_ms)});
            rays_vis.points.push_back({t, positive(s.raytrace.visibility_ms)});
        }
        p.series = {raster_frame, rays_frame, raster_vis, rays_vis};
        int arrow = 1;
        for (const auto& [c, what] : {std::pair{r.frame_crossover, "frames"}, std::pair{r.visibility_crossover, "visibility"}}) {
            if (!c) continue;
            std::ostringstream mark;
            mark.precision(9);
            mark << "set arrow " << arrow << " from " << c->triangles << ", graph 0 to " << c->triangles
                 << ", graph 1 nohead dashtype 2 lc rgb 'gray40'\n"
                 << "set label " << arrow << " " << quoted(std::string("crossover (") + what + "): " +
                                                             std::to_string(std::llround(c->triangles)))
                 << " at " << c->triangles << ", graph " << (arrow == 1 ? 0.95 : 0.88) << " offset 1,0 noenhanced";
            p.extra.push_back(mark.str());
            ++arrow;
        }
        plots.push_back(std::move(p));
    }
    const ConfigFigures& first = r.configs.front();
    Plot resolution{"time_vs_resolution", "pixels (" + std::to_string(first.threads) + " threads)", "ms (median)",
                    true, true, {}, {}};
    Plot threads{"time_vs_threads", "threads (" + std::to_string(first.width) + "x" + std::to_string(first.height) + ")",
                 "ms (median)", false, false, {}, {}};
    for (Plot* p : {&resolution, &threads})
        p->series = {{"raster frame", {}}, {"raytrace frame", {}}, {"raster visibility", {}}, {"primary rays", {}}};
    const auto add = [](Plot& p, double x, const ConfigFigures& c) {
        p.series[0].points.push_back({x, positive(c.raster.frame_ms)});
        p.series[1].points.push_back({x, positive(c.raytrace.frame_ms)});
        p.series[2].points.push_back({x, positive(c.raster.visibility_ms)});
        p.series[3].points.push_back({x, positive(c.raytrace.visibility_ms)});
    };
    for (const ConfigFigures& c : r.configs) {
        if (c.threads == first.threads) add(resolution, double(c.width) * double(c.height), c);
        if (c.width == first.width && c.height == first.height) add(threads, double(c.threads), c);
    }
    for (Plot* p : {&resolution, &threads})  // lines drawn left to right, whatever order the flags gave
        for (Series& s : p->series) std::sort(s.points.begin(), s.points.end());
    plots.push_back(std::move(resolution));
    plots.push_back(std::move(threads));
    std::vector<std::string> written;
    for (const Plot& p : plots) {
        const fs::path target = dir / (p.name + ".png");
        run_gnuplot(script_for(p, r), target);
        written.push_back(target.string());
    }
    return written;
}

}  // namespace tessera::cli
