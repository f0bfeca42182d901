#include "fleet/batch_plan.hpp"

#include <yaml-cpp/yaml.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <set>

#include "core/error.hpp"
#include "runfolder/run_folder.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

std::string Trim(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

fs::path Resolve(const fs::path& base, const std::string& path) {
    if (path.empty()) return {};
    const fs::path p(path);
    return (p.is_absolute() ? p : base / p).lexically_normal();
}

/// A preset name stays a name; anything that looks like a file is resolved like a path.
std::string ResolveConfig(const fs::path& base, const std::string& config) {
    const bool is_path = config.find('/') != std::string::npos || fs::path(config).extension() == ".yaml";
    return is_path ? Resolve(base, config).string() : config;
}

std::vector<BatchSequence> ReadYamlManifest(const fs::path& manifest, const fs::path& base) {
    YAML::Node root;
    try {
        root = YAML::LoadFile(manifest.string());
    } catch (const YAML::Exception& e) {
        throw DatasetError(manifest, "line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
    }
    const YAML::Node list = root["sequences"];
    if (!list || !list.IsSequence()) throw DatasetError(manifest, "needs a list `sequences:` of {path, config, reference}");
    std::vector<BatchSequence> sequences;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node item = list[i];
        const std::string where = "sequence " + std::to_string(i + 1) + " (line " + std::to_string(item.Mark().line + 1) + ")";
        BatchSequence sequence;
        try {
            if (item.IsScalar()) {
                sequence.path = Resolve(base, item.as<std::string>());
            } else if (item.IsMap() && item["path"]) {
                for (const auto& field : item) {
                    const auto key = field.first.as<std::string>();
                    if (key != "path" && key != "config" && key != "reference" && key != "from" && key != "to")
                        throw DatasetError(manifest, where + ": unknown key '" + key + "' (path, config, reference, from, to)");
                }
                sequence.path = Resolve(base, item["path"].as<std::string>());
                if (item["config"]) sequence.config = ResolveConfig(base, item["config"].as<std::string>());
                if (item["reference"]) sequence.reference = Resolve(base, item["reference"].as<std::string>());
                if (item["from"]) sequence.from = item["from"].as<std::size_t>();
                if (item["to"]) sequence.to = item["to"].as<std::size_t>();
            } else {
                throw DatasetError(manifest, where + ": needs a path");
            }
        } catch (const YAML::Exception& e) {
            throw DatasetError(manifest, where + ": " + e.msg);
        }
        sequences.push_back(sequence);
    }
    return sequences;
}

std::vector<BatchSequence> ReadCsvManifest(const fs::path& manifest, const fs::path& base) {
    std::ifstream in(manifest);
    std::vector<BatchSequence> sequences;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        line = Trim(line);
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> fields;
        std::size_t start = 0;
        for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
            fields.push_back(Trim(line.substr(start, comma - start)));
        fields.push_back(Trim(line.substr(start)));
        if (sequences.empty() && fields[0] == "path") continue;  // header
        if (fields.size() > 5)
            throw DatasetError(manifest, "line " + std::to_string(number) + ": more than 5 fields (path,config,reference,from,to)");
        if (fields[0].empty()) throw DatasetError(manifest, "line " + std::to_string(number) + ": empty path");
        BatchSequence sequence;
        sequence.path = Resolve(base, fields[0]);
        if (fields.size() > 1 && !fields[1].empty()) sequence.config = ResolveConfig(base, fields[1]);
        if (fields.size() > 2) sequence.reference = Resolve(base, fields[2]);
        for (std::size_t f = 3; f < fields.size(); ++f) {
            if (fields[f].empty()) continue;
            if (fields[f].find_first_not_of("0123456789") != std::string::npos)
                throw DatasetError(manifest, "line " + std::to_string(number) + ": '" + fields[f] + "' is not a scan index");
            (f == 3 ? sequence.from : sequence.to) = std::stoull(fields[f]);
        }
        sequences.push_back(sequence);
    }
    return sequences;
}

}  // namespace

std::vector<BatchSequence> ReadManifest(const fs::path& manifest) {
    if (!fs::is_regular_file(manifest)) throw DatasetError(manifest, "no such manifest file");
    const fs::path base = fs::absolute(manifest).parent_path();
    const std::string extension = manifest.extension().string();
    auto sequences = extension == ".yaml" || extension == ".yml" ? ReadYamlManifest(manifest, base) : ReadCsvManifest(manifest, base);
    if (sequences.empty()) throw DatasetError(manifest, "lists no sequence");
    for (const auto& s : sequences) {
        if (!fs::exists(s.path)) throw DatasetError(manifest, "sequence " + s.path.string() + ": no such dataset");
        if (!s.reference.empty() && !fs::exists(s.reference))
            throw DatasetError(manifest, "reference " + s.reference.string() + ": no such file");
    }
    return sequences;
}

std::string ShellQuote(const std::string& word) {
    std::string quoted = "'";
    for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string ShellCommand(const fs::path& executable, const std::vector<std::string>& arguments) {
    std::string command = ShellQuote(executable.string());
    for (const auto& argument : arguments) command += ' ' + ShellQuote(argument);
    return command;
}

BatchPlan MakeBatchPlan(const std::vector<BatchSequence>& sequences, const fs::path& out, const fs::path& executable,
                        const std::vector<std::string>& configs, const std::vector<std::string>& overrides, int threads) {
    BatchPlan plan;
    plan.executable = fs::absolute(executable).lexically_normal();
    plan.out = fs::absolute(out).lexically_normal();
    plan.merge_dir = plan.out / "merge";
    plan.merge_log = plan.out / "logs" / "merge.log";
    plan.merge_arguments = {"merge"};
    for (std::size_t i = 0; i < sequences.size(); ++i) {
        const auto& s = sequences[i];
        fs::path base = s.path.filename().empty() ? s.path.parent_path().filename() : s.path.filename();
        char prefix[32];
        std::snprintf(prefix, sizeof(prefix), "%02zu_", i);
        BatchTask task;
        task.index = i;
        task.name = prefix + base.string();
        if (s.from || s.to) task.name += "_" + std::to_string(s.from.value_or(0)) + "-" + (s.to ? std::to_string(*s.to) : "end");
        task.run_dir = plan.out / "runs" / task.name;
        task.log = plan.out / "logs" / (task.name + ".log");
        task.arguments = {"run", fs::absolute(s.path).lexically_normal().string(), "--out", task.run_dir.string(), "--force", "--quiet"};
        for (const auto& c : configs) task.arguments.insert(task.arguments.end(), {"--config", c});
        if (!s.config.empty()) task.arguments.insert(task.arguments.end(), {"--config", s.config});
        for (const auto& o : overrides) task.arguments.insert(task.arguments.end(), {"--set", o});
        if (!s.reference.empty()) task.arguments.insert(task.arguments.end(), {"--gt", fs::absolute(s.reference).string()});
        if (s.from) task.arguments.insert(task.arguments.end(), {"--from", std::to_string(*s.from)});
        if (s.to) task.arguments.insert(task.arguments.end(), {"--to", std::to_string(*s.to)});
        if (threads > 0) task.arguments.insert(task.arguments.end(), {"--threads", std::to_string(threads)});
        plan.merge_arguments.push_back(task.run_dir.string());
        plan.tasks.push_back(task);
    }
    plan.merge_arguments.insert(plan.merge_arguments.end(), {"--out", plan.merge_dir.string(), "--force"});
    if (threads > 0) plan.merge_arguments.insert(plan.merge_arguments.end(), {"--threads", std::to_string(threads)});
    return plan;
}

bool TaskFinished(const BatchTask& task) {
    const RunFolder run(task.run_dir);
    if (!fs::exists(run.database())) return false;
    std::ifstream in(run.run_info());
    if (!in) return false;
    try {
        return nlohmann::json::parse(in).value("complete", false);
    } catch (const nlohmann::json::exception&) {
        return false;  // a damaged run.json: run it again
    }
}

}  // namespace revisit
