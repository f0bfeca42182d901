/// rosbag2 sqlite3 bags (https://github.com/ros2/rosbag2, rosbag2_storage_default_plugins): a folder
/// with metadata.yaml and one or more .db3 files, each with tables `topics` (id, name, type,
/// serialization_format, ...) and `messages` (id, topic_id, timestamp, data). Humble's schema
/// version 3 and Iron's 4 (which adds message_definitions and a type hash) read alike: only those
/// columns are used. Messages come ordered by timestamp, then id, file after file.
#include <sqlite3.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "io/bag_source.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

std::vector<fs::path> Db3Files(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (entry.is_regular_file() && entry.path().extension() == ".db3") files.push_back(entry.path());
    }
    // rosbag2 splits as NAME_0.db3, NAME_1.db3, ...: by the number after the last '_', then by name.
    const auto number = [](const fs::path& p) {
        const std::string stem = p.stem().string();
        const auto underscore = stem.find_last_of('_');
        const std::string digits = underscore == std::string::npos ? "" : stem.substr(underscore + 1);
        return !digits.empty() && digits.size() < 10 && digits.find_first_not_of("0123456789") == std::string::npos ? std::stol(digits) : -1L;
    };
    std::sort(files.begin(), files.end(), [&](const fs::path& a, const fs::path& b) {
        return std::make_pair(number(a), a.string()) < std::make_pair(number(b), b.string());
    });
    return files;
}

/// A URI for sqlite3_open_v2: immutable (no locks, no journal: the folder may be read-only).
std::string ImmutableUri(const fs::path& file) {
    std::string uri = "file:";
    for (const char c : fs::absolute(file).string()) {
        if (c == '?' || c == '#' || c == '%') {
            static const char* hex = "0123456789ABCDEF";
            uri += '%';
            uri += hex[(unsigned char)c >> 4];
            uri += hex[(unsigned char)c & 15];
        } else {
            uri += c;
        }
    }
    return uri + "?immutable=1";
}

class Db3Source final : public BagSource {
  public:
    explicit Db3Source(const fs::path& folder) : folder_(folder), files_(Db3Files(folder)) {
        CheckMetadata();
        if (files_.empty()) throw DatasetError(folder_, "no .db3 file next to metadata.yaml");
        try {
            for (std::size_t f = 0; f < files_.size(); ++f) {
                Open(f);
                ReadTopics(f);
            }
        } catch (...) {
            Close();  // a throwing constructor runs no destructor
            throw;
        }
    }
    ~Db3Source() override { Close(); }

    std::string Format() const override { return "rosbag2 sqlite3"; }
    const std::vector<BagTopic>& Topics() const override { return topics_; }

    void Start(std::function<bool(std::size_t)> wanted) override {
        wanted_ = std::move(wanted);
        file_ = 0;
        Close();
    }

    bool Next(BagMessage& message) override {
        while (true) {
            if (!statement_) {
                if (file_ >= files_.size()) return false;
                Open(file_);
                Prepare();
                if (!statement_) {  // no wanted topic in this file
                    ++file_;
                    continue;
                }
            }
            const int status = sqlite3_step(statement_);
            if (status == SQLITE_ROW) {
                const auto topic_id = sqlite3_column_int64(statement_, 0);
                const auto found = topic_of_[file_].find(topic_id);
                if (found == topic_of_[file_].end()) Fail("a message of topic id " + std::to_string(topic_id) + ", not in table topics");
                message.topic = found->second;
                message.log_time_ns = sqlite3_column_int64(statement_, 1);
                message.data = static_cast<const std::uint8_t*>(sqlite3_column_blob(statement_, 2));
                message.size = std::size_t(sqlite3_column_bytes(statement_, 2));
                message.position = std::uint64_t(sqlite3_column_int64(statement_, 3));
                message.inner = file_;
                return true;
            }
            if (status != SQLITE_DONE) Fail(std::string("reading messages: ") + sqlite3_errmsg(db_));
            Close();
            ++file_;
        }
    }

    std::string Where(const BagMessage& message) const override {
        return files_.at(message.inner).filename().string() + " messages row id " + std::to_string(message.position);
    }

  private:
    [[noreturn]] void Fail(const std::string& problem) const {
        throw DatasetError(file_ < files_.size() ? files_[file_] : folder_, problem);
    }

    void CheckMetadata() {
        std::ifstream in(folder_ / "metadata.yaml");
        std::stringstream text;
        text << in.rdbuf();
        const std::string yaml = text.str();
        const fs::path metadata = folder_ / "metadata.yaml";
        if (yaml.find("rosbag2_bagfile_information") == std::string::npos) {
            throw DatasetError(metadata, "not a rosbag2 metadata file (no rosbag2_bagfile_information)");
        }
        const auto value = [&](const std::string& key) {
            const auto at = yaml.find(key + ":");
            if (at == std::string::npos) return std::string();
            std::string v = yaml.substr(at + key.size() + 1, yaml.find('\n', at) - at - key.size() - 1);
            v.erase(0, v.find_first_not_of(" \t\"'"));
            v.erase(v.find_last_not_of(" \t\r\"'") + 1);
            return v;
        };
        if (const std::string storage = value("storage_identifier"); !storage.empty() && storage != "sqlite3") {
            throw DatasetError(metadata, "storage " + storage + " in a folder with .db3 files: only sqlite3 is read here");
        }
        if (const std::string compression = value("compression_format"); !compression.empty()) {
            throw DatasetError(metadata, "compressed rosbag2 bags (" + compression + ") are not read; decompress with `ros2 bag convert`");
        }
    }

    void Open(std::size_t f) {
        Close();
        if (sqlite3_open_v2(ImmutableUri(files_[f]).c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr) != SQLITE_OK) {
            const std::string problem = db_ ? sqlite3_errmsg(db_) : "out of memory";
            Close();
            throw DatasetError(files_[f], "cannot open as sqlite3: " + problem);
        }
        // No value can be longer than the file: a damaged record's length is refused before sqlite
        // allocates it (by default sqlite allows 1 GB).
        std::error_code ec;
        const std::uintmax_t bytes = fs::file_size(files_[f], ec);
        sqlite3_limit(db_, SQLITE_LIMIT_LENGTH, int(std::min<std::uintmax_t>(ec ? 0 : bytes + 1, 1'000'000'000)));
        file_ = f;
    }

    void Close() {
        if (statement_) sqlite3_finalize(statement_);
        statement_ = nullptr;
        if (db_) sqlite3_close_v2(db_);
        db_ = nullptr;
    }

    sqlite3_stmt* Query(const std::string& sql) {
        sqlite3_stmt* statement = nullptr;
        if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement, nullptr) != SQLITE_OK) {
            Fail("not a rosbag2 sqlite3 bag (" + std::string(sqlite3_errmsg(db_)) + ")");
        }
        return statement;
    }

    static std::string Text(sqlite3_stmt* statement, int column) {
        const auto* text = sqlite3_column_text(statement, column);
        return text ? reinterpret_cast<const char*>(text) : "";
    }

    void ReadTopics(std::size_t f) {
        topic_of_.resize(files_.size());
        sqlite3_stmt* statement = Query("SELECT id, name, type, serialization_format FROM topics");
        int status;
        while ((status = sqlite3_step(statement)) == SQLITE_ROW) {
            const std::string name = Text(statement, 1), type = Text(statement, 2), format = Text(statement, 3);
            const bool ros1 = format == "ros1";
            const std::string shown = ros1 || format == "cdr" ? type : type + " (" + format + " encoded)";
            std::size_t index = 0;
            while (index < topics_.size() && !(topics_[index].name == name && topics_[index].type == shown)) ++index;
            if (index == topics_.size()) topics_.push_back({name, shown, ros1 ? RosWire::kRos1 : RosWire::kCdr, 0, 0, 0});
            topic_of_[f][sqlite3_column_int64(statement, 0)] = index;
        }
        sqlite3_finalize(statement);
        if (status != SQLITE_DONE) Fail(std::string("reading topics: ") + sqlite3_errmsg(db_));
        statement = Query("SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages GROUP BY topic_id");
        while ((status = sqlite3_step(statement)) == SQLITE_ROW) {
            const auto found = topic_of_[f].find(sqlite3_column_int64(statement, 0));
            if (found == topic_of_[f].end()) continue;  // reported when the messages are read
            BagTopic& topic = topics_[found->second];
            const auto first = sqlite3_column_int64(statement, 2), last = sqlite3_column_int64(statement, 3);
            topic.first_ns = topic.count == 0 ? first : std::min<std::int64_t>(topic.first_ns, first);
            topic.last_ns = topic.count == 0 ? last : std::max<std::int64_t>(topic.last_ns, last);
            topic.count += std::size_t(sqlite3_column_int64(statement, 1));
        }
        sqlite3_finalize(statement);
        if (status != SQLITE_DONE) Fail(std::string("counting messages: ") + sqlite3_errmsg(db_));
    }

    void Prepare() {
        std::string ids;
        for (const auto& [id, topic] : topic_of_[file_]) {
            if (wanted_(topic)) ids += (ids.empty() ? "" : ",") + std::to_string(id);
        }
        if (ids.empty()) return;
        statement_ = Query("SELECT topic_id, timestamp, data, id FROM messages WHERE topic_id IN (" + ids +
                           ") ORDER BY timestamp, id");
    }

    fs::path folder_;
    std::vector<fs::path> files_;
    std::vector<std::map<std::int64_t, std::size_t>> topic_of_;  ///< per file: topics.id -> index into topics_
    std::vector<BagTopic> topics_;
    std::function<bool(std::size_t)> wanted_;
    std::size_t file_ = 0;
    sqlite3* db_ = nullptr;
    sqlite3_stmt* statement_ = nullptr;
};

}  // namespace

bool IsRosbag2Folder(const fs::path& folder) {
    return fs::is_regular_file(folder / "metadata.yaml") && !Db3Files(folder).empty();
}

std::unique_ptr<BagSource> OpenDb3Source(const fs::path& folder) { return std::make_unique<Db3Source>(folder); }

}  // namespace revisit
