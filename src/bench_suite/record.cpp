#include "bench_suite/record.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace revisit {

namespace {
using Json = nlohmann::json;

const char* KindName(FigureKind kind) {
    switch (kind) {
        case FigureKind::kItemsPerSecond:
            return "rate";
        case FigureKind::kAbsolute:
            return "value";
        default:
            return "time";
    }
}

FigureKind KindFromName(const std::string& name) {
    if (name == "rate") return FigureKind::kItemsPerSecond;
    if (name == "value") return FigureKind::kAbsolute;
    return FigureKind::kMsPerItem;
}

std::string Printf(const char* format, double a, double b = 0.0, double c = 0.0) {
    char text[64];
    std::snprintf(text, sizeof(text), format, a, b, c);
    return text;
}

/// Three significant digits at most, without exponent for everyday magnitudes.
std::string Number(double v) {
    const double a = std::abs(v);
    if (a >= 1000.0 || a == 0.0) return Printf("%.0f", v);
    if (a >= 100.0) return Printf("%.1f", v);
    if (a >= 10.0) return Printf("%.2f", v);
    if (a >= 0.01) return Printf("%.3f", v);
    return Printf("%.2e", v);
}

std::string Pad(const std::string& s, std::size_t width, bool right = false) {
    if (s.size() >= width) return s;
    const std::string fill(width - s.size(), ' ');
    return right ? fill + s : s + fill;
}
}  // namespace

std::string RecordToJson(const BenchRecord& r) {
    Json json;
    json["format"] = "revisit-bench-1";
    json["suite"] = r.suite;
    json["started_utc"] = r.started_utc;
    json["duration_s"] = r.duration_s;
    json["peak_memory_kb"] = r.peak_memory_kb;
    json["data_dir"] = r.data_dir;
    json["skipped"] = r.skipped;
    json["machine"] = {{"cores", r.machine.cores},
                       {"threads", r.machine.threads},
                       {"build_type", r.machine.build_type},
                       {"compiler", r.machine.compiler},
                       {"cpu", r.machine.cpu},
                       {"hostname", r.machine.hostname},
                       {"load_average", r.machine.load_average}};
    json["results"] = Json::array();
    for (const auto& m : r.results) {
        json["results"].push_back({{"name", m.name},
                                   {"unit", m.unit},
                                   {"kind", KindName(m.kind)},
                                   {"median", m.median},
                                   {"min", m.min},
                                   {"max", m.max},
                                   {"spread", m.spread},
                                   {"samples", m.samples},
                                   {"note", m.note}});
    }
    // A host or path name that is not UTF-8 is written as U+FFFD instead of failing.
    return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

BenchRecord RecordFromJson(const std::string& text, const std::string& source) {
    try {
        const Json json = Json::parse(text);
        if (json.value("format", "") != "revisit-bench-1")
            throw DatasetError(source, "not a revisit bench record (format)");
        BenchRecord r;
        r.suite = json.at("suite").get<std::string>();
        r.started_utc = json.value("started_utc", "");
        r.duration_s = json.value("duration_s", 0.0);
        r.peak_memory_kb = json.value("peak_memory_kb", std::size_t{0});
        r.data_dir = json.value("data_dir", "");
        r.skipped = json.value("skipped", std::vector<std::string>{});
        const Json& machine = json.at("machine");
        r.machine.cores = machine.value("cores", 0u);
        r.machine.threads = machine.value("threads", 0);
        r.machine.build_type = machine.value("build_type", "");
        r.machine.compiler = machine.value("compiler", "");
        r.machine.cpu = machine.value("cpu", "");
        r.machine.hostname = machine.value("hostname", "");
        r.machine.load_average = machine.value("load_average", 0.0);
        for (const Json& item : json.at("results")) {
            Measurement m;
            m.name = item.at("name").get<std::string>();
            m.unit = item.value("unit", "");
            m.kind = KindFromName(item.value("kind", "time"));
            m.samples = item.value("samples", std::vector<double>{});
            m.median = item.at("median").get<double>();
            m.min = item.value("min", m.median);
            m.max = item.value("max", m.median);
            m.spread = item.value("spread", 0.0);
            m.note = item.value("note", "");
            r.results.push_back(std::move(m));
        }
        return r;
    } catch (const Json::exception& e) {
        throw DatasetError(source, std::string("malformed benchmark record: ") + e.what());
    }
}

void WriteRecord(const std::filesystem::path& file, const BenchRecord& record) {
    WriteFileAtomically(file, [&record](std::ostream& out) { out << RecordToJson(record); });
}

BenchRecord ReadRecord(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw DatasetError(file.string(), "cannot open");
    std::stringstream text;
    text << in.rdbuf();
    return RecordFromJson(text.str(), file.string());
}

Comparison CompareRecords(const BenchRecord& old_record, const BenchRecord& new_record) {
    Comparison c;
    double log_sum = 0.0;
    for (const auto& now : new_record.results) {
        const Measurement* before = nullptr;
        for (const auto& m : old_record.results)
            if (m.name == now.name) before = &m;
        if (!before) {
            c.only_new.push_back(now.name);
            continue;
        }
        FigureRatio f;
        f.name = now.name;
        f.unit = now.unit;
        f.old_median = before->median;
        f.new_median = now.median;
        f.ratio = f.old_median != 0.0 ? f.new_median / f.old_median : 0.0;
        f.speedup = now.higher_is_better() ? f.ratio : (f.ratio != 0.0 ? 1.0 / f.ratio : 0.0);
        f.noise = std::max(before->spread, now.spread);
        f.same_setup = before->note == now.note;
        f.slower = now.higher_is_better() ? now.max < before->min : now.min > before->max;
        if (f.slower) c.slower.push_back(f.name);
        if (f.speedup > 0.0) log_sum += std::log(f.speedup);
        c.ratios.push_back(f);
    }
    for (const auto& m : old_record.results) {
        bool found = false;
        for (const auto& now : new_record.results) found = found || now.name == m.name;
        if (!found) c.only_old.push_back(m.name);
    }
    if (!c.ratios.empty()) c.geometric_mean_speedup = std::exp(log_sum / double(c.ratios.size()));
    return c;
}

std::string FormatRecord(const BenchRecord& r) {
    std::ostringstream out;
    out << "suite " << r.suite << ", " << r.machine.cores << " cores (" << r.machine.threads << " threads allowed), "
        << r.machine.build_type << " build, " << r.machine.cpu << ", load average "
        << Printf("%.2f", r.machine.load_average) << " at start\n";
    out << Pad("figure", 46) << Pad("median", 11, true) << Pad("min", 11, true) << Pad("max", 11, true)
        << Pad("spread", 9, true) << "  unit\n";
    for (const auto& m : r.results) {
        out << Pad(m.name, 46) << Pad(Number(m.median), 11, true) << Pad(Number(m.min), 11, true)
            << Pad(Number(m.max), 11, true) << Pad(Printf("%.1f%%", 100.0 * m.spread), 9, true) << "  " << m.unit
            << "\n";
    }
    for (const auto& s : r.skipped) out << "skipped: " << s << "\n";
    out << "suite took " << Printf("%.1f", r.duration_s) << " s, peak memory "
        << Printf("%.0f", double(r.peak_memory_kb) / 1024.0) << " MiB\n";
    return out.str();
}

std::string FormatComparison(const Comparison& c) {
    std::ostringstream out;
    out << Pad("figure", 46) << Pad("old", 11, true) << Pad("new", 11, true) << Pad("new/old", 9, true)
        << Pad("speedup", 9, true) << "  unit\n";
    for (const auto& f : c.ratios) {
        const bool significant = std::abs(f.speedup - 1.0) > f.noise;
        out << Pad(f.name, 46) << Pad(Number(f.old_median), 11, true) << Pad(Number(f.new_median), 11, true)
            << Pad(Printf("%.3f", f.ratio), 9, true) << Pad(Printf("%.2fx", f.speedup), 9, true) << "  " << f.unit
            << (significant ? "" : "  (within noise)") << (f.same_setup ? "" : "  (different setup)")
            << (f.slower ? "  SLOWER" : "") << "\n";
    }
    if (!c.only_old.empty()) {
        out << c.only_old.size() << " figure(s) only in old:";
        for (const auto& n : c.only_old) out << " " << n << ";";
        out << "\n";
    }
    for (const auto& n : c.only_new) out << "only in new: " << n << "\n";
    out << "geometric mean speedup " << Printf("%.3f", c.geometric_mean_speedup) << "x over " << c.ratios.size()
        << " figures\n";
    if (!c.slower.empty()) {
        out << c.slower.size() << " figure(s) SLOWER beyond the runs' spread (every new sample worse than every old one):";
        for (const auto& n : c.slower) out << " " << n << ";";
        out << "\n";
    }
    return out.str();
}

std::vector<StageRatio> StageRatios(const Comparison& c) {
    std::vector<StageRatio> stages;
    std::vector<double> log_sums;
    for (const auto& f : c.ratios) {
        const std::string stage = f.name.substr(0, f.name.find('/'));
        std::size_t k = 0;
        while (k < stages.size() && stages[k].stage != stage) ++k;
        if (k == stages.size()) {
            stages.push_back({stage, 0, 1.0, f.name, f.speedup, 0});
            log_sums.push_back(0.0);
        }
        StageRatio& s = stages[k];
        s.figures++;
        if (f.speedup > 0.0) log_sums[k] += std::log(f.speedup);
        if (f.speedup < s.worst_speedup) s.worst_figure = f.name, s.worst_speedup = f.speedup;
        s.slower += f.slower ? 1 : 0;
    }
    for (std::size_t k = 0; k < stages.size(); ++k)
        stages[k].geometric_mean_speedup = std::exp(log_sums[k] / double(stages[k].figures));
    return stages;
}

std::string FormatStageRatios(const std::vector<StageRatio>& stages) {
    std::ostringstream out;
    out << Pad("stage", 14) << Pad("figures", 8, true) << Pad("speedup", 10, true) << Pad("slower", 8, true)
        << "  worst figure\n";
    for (const auto& s : stages) {
        out << Pad(s.stage, 14) << Pad(std::to_string(s.figures), 8, true)
            << Pad(Printf("%.2fx", s.geometric_mean_speedup), 10, true) << Pad(std::to_string(s.slower), 8, true)
            << "  " << s.worst_figure << " " << Printf("%.2fx", s.worst_speedup) << "\n";
    }
    out << "speedup: reference time / this time per stage (geometric mean over its figures); > 1 is faster\n";
    return out.str();
}

}  // namespace revisit
