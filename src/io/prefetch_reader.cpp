#include "io/prefetch_reader.hpp"

#include <algorithm>

namespace revisit {

PrefetchReader::PrefetchReader(std::unique_ptr<Reader> inner, std::size_t depth)
    : inner_(std::move(inner)), depth_(std::max<std::size_t>(1, depth)), info_(inner_->Info()) {
    stats_ = inner_->Stats();
}

PrefetchReader::~PrefetchReader() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void PrefetchReader::Produce() {
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [this] { return stop_ || queue_.size() < depth_; });
            if (stop_) return;
        }
        Item item;
        try {
            item.scan = inner_->Next();
        } catch (...) {
            item.error = std::current_exception();
        }
        item.stats = inner_->Stats();
        item.info = inner_->Info();
        const bool last = !item.scan;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            queue_.push_back(std::move(item));
        }
        changed_.notify_all();
        if (last) return;
    }
}

bool PrefetchReader::SkipTo(std::size_t index) {
    if (thread_.joinable() || ended_) return false;
    if (!inner_->SkipTo(index)) return false;
    stats_ = inner_->Stats();
    return true;
}

std::optional<Scan> PrefetchReader::Next() {
    if (ended_) return std::nullopt;
    if (!thread_.joinable()) thread_ = std::thread([this] { Produce(); });
    Item item;
    {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [this] { return !queue_.empty(); });
        item = std::move(queue_.front());
        queue_.pop_front();
    }
    changed_.notify_all();
    stats_ = std::move(item.stats);
    info_ = std::move(item.info);
    if (!item.scan) {
        ended_ = true;
        thread_.join();
        if (item.error) std::rethrow_exception(item.error);
    }
    return std::move(item.scan);
}

}  // namespace revisit
