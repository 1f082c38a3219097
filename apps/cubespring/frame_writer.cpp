// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "frame_writer.h"

#include <cstdio>
#include <string>
#include <utility>

#include "cubespring/render/image.h"

namespace cubespring::app {

std::string frame_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return name;
}

FrameWriter::FrameWriter(scene::SceneFrames& frames, scene::SceneWorld& world, std::filesystem::path folder)
    : frames_(frames), world_(world), folder_(std::move(folder)), thread_([this] { work(); }) {}

FrameWriter::~FrameWriter() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

Status FrameWriter::submit(int index, double t, Eigen::Matrix3Xd organ_positions) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return !error_.ok() || queue_.size() < kMaxQueued; });
  if (!error_.ok()) return error_;
  queue_.push_back(Job{index, t, std::move(organ_positions)});
  lock.unlock();
  changed_.notify_all();
  return {};
}

Status FrameWriter::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return !error_.ok() || (queue_.empty() && !busy_); });
  return error_;
}

void FrameWriter::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return closing_ || !queue_.empty(); });
    if (queue_.empty() || !error_.ok()) return;  // closing, or a frame failed: draw no more
    const Job job = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    Status written = write(job);
    lock.lock();
    busy_ = false;
    if (!written) {
      error_ = std::move(written);
      queue_.clear();
    }
    changed_.notify_all();
  }
}

Status FrameWriter::write(const Job& job) {
  Result<Image> image = frames_.render(world_, job.organ_positions, job.time);
  if (!image) return Status::error("frame " + std::to_string(job.index) + ": " + image.message());
  if (Status s = write_png(*image, (folder_ / frame_name(job.index)).string()); !s) return s;
  written_.fetch_add(1, std::memory_order_relaxed);
  return {};
}

}  // namespace cubespring::app
