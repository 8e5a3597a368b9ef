#include "sensors/recorder.h"

#include <chrono>

#include "io/sequence.h"

namespace hdrf::sensors {

namespace fs = std::filesystem;

namespace {
double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
std::uintmax_t SizeOr0(const fs::path& p) {
  std::error_code ec;
  const auto s = fs::file_size(p, ec);
  return ec ? 0 : s;
}
}  // namespace

SequenceRecorder::SequenceRecorder(const fs::path& folder, const SensorInfo& sensor, std::size_t queue)
    : folder_(folder),
      writer_(std::make_unique<io::SequenceWriter>(
          folder, sensor, io::SequenceWriter::Options{.write_exposure = true, .write_groundtruth = false, .write_hdr = false})),
      capacity_(std::max<std::size_t>(queue, 1)) {
  thread_ = std::thread([this] { Run(); });
}

SequenceRecorder::~SequenceRecorder() { Finish(); }

bool SequenceRecorder::Push(LiveFrame frame, std::optional<double> exposure_ms, std::optional<double> gain) {
  std::lock_guard lock(mutex_);
  if (!started_) {
    started_ = true;
    t0_ = Now();
  }
  if (failed_ || closing_ || queue_.size() >= capacity_) {
    ++stats_.dropped;
    return false;
  }
  queue_.push_back({std::move(frame), exposure_ms, gain});
  wake_.notify_all();
  return true;
}

void SequenceRecorder::Run() {
  for (;;) {
    Item item;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;
      item = std::move(queue_.front());
      queue_.pop_front();
      if (failed_) {
        ++stats_.dropped;
        continue;
      }
    }
    Write(item);
  }
}

// One frame, all or nothing: on failure the lists are cut back to where they were and the
// frame's images removed, so the sequence on disk is every earlier frame, complete.
void SequenceRecorder::Write(const Item& item) {
  const char* lists[] = {"rgb.txt", "depth.txt", "exposure.txt"};
  std::uintmax_t before[3];
  for (int i = 0; i < 3; ++i) before[i] = SizeOr0(folder_ / lists[i]);
  const std::string stem = io::TimestampName(item.frame.timestamp);
  try {
    writer_->Add(item.frame.timestamp, item.frame.color, &item.frame.depth_mm, item.exposure_ms, std::nullopt,
                 nullptr, item.gain);
    const double bytes = double(SizeOr0(folder_ / "rgb" / (stem + ".png")) + SizeOr0(folder_ / "depth" / (stem + ".png")));
    std::lock_guard lock(mutex_);
    ++stats_.written;
    stats_.bytes += bytes;
    stats_.seconds = Now() - t0_;
  } catch (const std::exception& e) {
    writer_.reset();  // closes the lists before they are cut back
    std::error_code ec;
    for (int i = 0; i < 3; ++i)
      if (fs::exists(folder_ / lists[i], ec)) fs::resize_file(folder_ / lists[i], before[i], ec);
    fs::remove(folder_ / "rgb" / (stem + ".png"), ec);
    fs::remove(folder_ / "depth" / (stem + ".png"), ec);
    const fs::space_info space = fs::space(folder_, ec);
    const std::string disk = !ec && space.available < 16u * 1024 * 1024
                                 ? " (the disk is full: " + std::to_string(space.available / 1024) + " kB free)"
                                 : "";
    std::lock_guard lock(mutex_);
    failed_ = true;
    ++stats_.dropped;
    stats_.error = std::string(e.what()) + disk + "; the recording stopped after " + std::to_string(stats_.written) +
                   " complete frames, all readable";
  }
}

RecordingStats SequenceRecorder::Finish() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    wake_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
  writer_.reset();
  return stats();
}

RecordingStats SequenceRecorder::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

bool SequenceRecorder::failed() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

}  // namespace hdrf::sensors
