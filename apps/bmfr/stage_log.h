// Per-stage frame times collected over a run, with medians: shared by denoise and bench.
#pragma once
#include <algorithm>
#include <bmfr/frame.h>
#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace bmfr::app {

inline double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

class StageLog {
  public:
    void add(const StageTimes& t) {
        for (int i = 0; i < t.count; ++i) series(t.name[i]).push_back(t.ms[i]);
        total_.push_back(t.total);
    }
    /// "name 1.23 | name 4.56 | total 5.79"
    std::string line() const {
        std::string s;
        for (const auto& [name, v] : stages_) s += fmt::format("{} {:.2f} | ", name, median(v));
        return s + fmt::format("total {:.2f}", median(total_));
    }
    nlohmann::json medians() const {
        nlohmann::json j;
        for (const auto& [name, v] : stages_) j[name] = median(v);
        return j;
    }
    double totalMedian() const { return median(total_); }

  private:
    std::vector<std::pair<std::string, std::vector<double>>> stages_;
    std::vector<double> total_;
    std::vector<double>& series(const char* name) {
        for (auto& [n, v] : stages_)
            if (n == name) return v;
        return stages_.emplace_back(name, std::vector<double>{}).second;
    }
};

} // namespace bmfr::app
