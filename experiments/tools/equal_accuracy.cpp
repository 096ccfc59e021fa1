#include "experiments/tools/equal_accuracy.hpp"
#include "experiments/tools/convergence.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace terrace::experiments {

std::vector<FrontPoint> paretoFront(std::vector<FrontPoint> points) {
    std::erase_if(points, [](const FrontPoint& p) {
        return !(p.cost > 0.0 && p.error > 0.0 && std::isfinite(p.cost) && std::isfinite(p.error));
    });
    std::sort(points.begin(), points.end(), [](const FrontPoint& a, const FrontPoint& b) {
        return a.cost < b.cost || (a.cost == b.cost && a.error < b.error);
    });
    std::vector<FrontPoint> front;
    for (const auto& p : points)
        if (front.empty() || p.error < front.back().error) front.push_back(p);
    return front;
}

CostAtError costAtError(const std::vector<FrontPoint>& front, double e) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (front.empty() || !(e > 0.0)) return {nan, false, ""};
    if (e >= front.front().error)
        return {front.front().cost, e > front.front().error, front.front().label};
    for (std::size_t k = 1; k < front.size(); ++k) {
        const FrontPoint &a = front[k - 1], &b = front[k]; // a cheaper, b more accurate
        if (e >= b.error) {
            const double t = std::log(e / a.error) / std::log(b.error / a.error);
            return {std::exp(std::log(a.cost) + t * std::log(b.cost / a.cost)), false,
                    e == b.error ? b.label : a.label + "~" + b.label};
        }
    }
    return {nan, false, ""};
}

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ','))
        out.push_back(cell);
    return out;
}

double number(const std::string& s) {
    try {
        std::size_t used = 0;
        const double x = std::stod(s, &used);
        return used == s.size() ? x : std::numeric_limits<double>::quiet_NaN();
    } catch (const std::exception&) {
        return std::numeric_limits<double>::quiet_NaN();
    }
}

} // namespace

std::vector<std::string> equalAccuracy(const std::filesystem::path& fronts,
                                       const std::string& targetSet) {
    std::ifstream in(fronts);
    if (!in) throw std::runtime_error("cannot open " + fronts.string());
    std::string line;
    if (!std::getline(in, line)) throw std::runtime_error(fronts.string() + ": empty");
    const auto header = splitCsv(line);
    auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end()) throw std::runtime_error(fronts.string() + ": no column " + name);
        return static_cast<std::size_t>(it - header.begin());
    };
    const std::size_t cSet = column("set"), cEngine = column("engine"), cDesign = column("design"),
                      cCost = column("cpu_s_per_ps"), cStatus = column("status");
    std::vector<std::string> quantities;
    for (const auto& h : header)
        if (h.rfind("err_", 0) == 0) quantities.push_back(h.substr(4));
    std::vector<std::vector<std::string>> rows;
    while (std::getline(in, line)) {
        auto r = splitCsv(line);
        if (r.size() < header.size()) continue;
        if (r[cStatus] == "ok") rows.push_back(std::move(r));
    }
    std::vector<std::string> out;
    char buf[512];
    for (const auto& q : quantities) {
        const std::size_t cErr = column("err_" + q), cFloor = column("floor_" + q);
        std::vector<FrontPoint> smd;
        std::map<std::string, std::vector<FrontPoint>> dmd;
        double targetError = std::numeric_limits<double>::quiet_NaN(), targetFloor = targetError;
        for (const auto& r : rows) {
            const FrontPoint p{r[cSet], number(r[cCost]), number(r[cErr])};
            if (r[cEngine] == "smd") smd.push_back(p);
            if (r[cEngine] == "dmd") dmd[r[cDesign]].push_back(p);
            if (r[cSet] == targetSet) targetError = p.error, targetFloor = number(r[cFloor]);
        }
        const auto smdFront = paretoFront(smd);
        for (const auto& [design, points] : dmd) {
            const auto front = paretoFront(points);
            for (const double factor : {1.0, 2.0}) {
                const double e = factor * targetError;
                const auto a = costAtError(smdFront, e), b = costAtError(front, e);
                std::snprintf(buf, sizeof buf, "%s,%s,%s%s,%.6g,%d,%.6g,%.6g,%.6g,%d,%s",
                              design.c_str(), q.c_str(), factor == 1.0 ? "" : "2x",
                              targetSet.c_str(), e, int(targetError > resolvedSigmas * targetFloor),
                              a.cost, b.cost, a.cost / b.cost, int(a.bound || b.bound),
                              a.via.c_str());
                out.emplace_back(buf);
            }
        }
    }
    return out;
}

} // namespace terrace::experiments
