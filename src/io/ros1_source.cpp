/// ROS 1 bags (format 2.0, uncompressed, bz2 or lz4 chunks) through Debian's rosbag_storage: the
/// library reads the container (chunks, connections, index); the messages' bytes are decoded by
/// io/ros_messages.hpp like ROS 2's, bounded.
#include "io/bag_source.hpp"

#include "core/error.hpp"
#include "io/ros1_container.hpp"

#ifdef REVISIT_HAVE_ROSBAG
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <map>
#include <optional>
#endif

namespace revisit {

#ifdef REVISIT_HAVE_ROSBAG
namespace {

class Ros1Source final : public BagSource {
  public:
    explicit Ros1Source(const std::filesystem::path& file) : file_(file) {
        CheckRos1Container(file);
        Guard([&] {
            bag_.open(file.string(), rosbag::bagmode::Read);
            rosbag::View all(bag_);
            for (const rosbag::ConnectionInfo* connection : all.getConnections()) {
                std::size_t index = 0;
                while (index < topics_.size() && topics_[index].name != connection->topic) ++index;
                if (index == topics_.size()) {
                    topics_.push_back({connection->topic, connection->datatype, RosWire::kRos1, 0, 0, 0});
                } else if (topics_[index].type != connection->datatype) {
                    throw DatasetError(file_, "topic " + connection->topic + " has two types: " + topics_[index].type +
                                                  " and " + connection->datatype);
                }
            }
            for (BagTopic& topic : topics_) {
                rosbag::View view(bag_, rosbag::TopicQuery(topic.name));
                topic.count = view.size();
                if (topic.count > 0) {
                    topic.first_ns = std::int64_t(view.getBeginTime().toNSec());
                    topic.last_ns = std::int64_t(view.getEndTime().toNSec());
                }
            }
        });
    }

    std::string Format() const override { return "rosbag1"; }
    const std::vector<BagTopic>& Topics() const override { return topics_; }

    void Start(std::function<bool(std::size_t)> wanted) override {
        std::vector<std::string> names;
        index_of_.clear();
        for (std::size_t i = 0; i < topics_.size(); ++i) {
            if (!wanted(i)) continue;
            names.push_back(topics_[i].name);
            index_of_[topics_[i].name] = i;
        }
        view_.reset();
        Guard([&] {
            view_.emplace(bag_, rosbag::TopicQuery(names));
            it_ = view_->begin();
        });
        position_ = 0;
    }

    bool Next(BagMessage& message) override {
        if (!view_ || index_of_.empty()) return false;
        return Guard([&] {
            if (it_ == view_->end()) return false;
            const rosbag::MessageInstance& m = *it_;
            buffer_.resize(m.size());
            ros::serialization::OStream stream(buffer_.data(), std::uint32_t(buffer_.size()));
            m.write(stream);
            message.topic = index_of_.at(m.getTopic());
            message.log_time_ns = std::int64_t(m.getTime().toNSec());
            message.data = buffer_.data();
            message.size = buffer_.size();
            message.position = position_++;
            ++it_;
            return true;
        });
    }

    std::string Where(const BagMessage& message) const override {
        return "message " + std::to_string(message.position) + " of the pass in time order";
    }

  private:
    /// The library's exceptions (rosbag::BagException and the rest) become DatasetError.
    template <typename F>
    auto Guard(F&& f) -> decltype(f()) {
        try {
            return f();
        } catch (const DatasetError&) {
            throw;
        } catch (const std::exception& e) {
            throw DatasetError(file_, std::string("damaged ROS 1 bag (rosbag_storage: ") + e.what() + ")");
        }
    }

    std::filesystem::path file_;
    rosbag::Bag bag_;
    std::vector<BagTopic> topics_;
    std::map<std::string, std::size_t> index_of_;
    std::optional<rosbag::View> view_;
    rosbag::View::iterator it_;
    std::vector<std::uint8_t> buffer_;
    std::uint64_t position_ = 0;
};

}  // namespace

std::unique_ptr<BagSource> OpenRos1Source(const std::filesystem::path& file) { return std::make_unique<Ros1Source>(file); }
#else
std::unique_ptr<BagSource> OpenRos1Source(const std::filesystem::path& file) {
    throw DatasetError(file, "this revisit was built without ROS 1 bag support (librosbag-storage-dev)");
}
#endif

}  // namespace revisit
