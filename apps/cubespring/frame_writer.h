// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A run's frames drawn and written as PNG on a thread of their own, beside the physics: the run
// hands over a copy of the organ's nodes at each frame's time and steps on. The frames are the
// pictures the run would draw in turn (the drawing reads only what a step does not change).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

#include <Eigen/Core>

#include "cubespring/result.h"
#include "cubespring/scene/scene_frames.h"
#include "cubespring/scene/scene_world.h"

namespace cubespring::app {

/// frame_0000.png, frame_0001.png, ...: the name of frame `frame` in a run's output folder.
std::string frame_name(int frame);

class FrameWriter {
 public:
  /// Frames of `world` drawn by `frames` into `folder`; both must outlive the writer.
  FrameWriter(scene::SceneFrames& frames, scene::SceneWorld& world, std::filesystem::path folder);
  ~FrameWriter();  ///< lets the queued frames finish
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  /// Queues frame `index` at time t [s] with the organ's lattice nodes at `organ_positions` [m]. It
  /// waits while kMaxQueued frames are waiting (their copies are all the memory it holds), and
  /// returns the first error of a frame already drawn, after which no more are drawn.
  Status submit(int index, double t, Eigen::Matrix3Xd organ_positions);
  /// Waits until every queued frame is written; the first error, if any.
  Status finish();
  /// Frames written so far.
  int written() const { return written_.load(std::memory_order_relaxed); }

  static constexpr std::size_t kMaxQueued = 4;

 private:
  struct Job {
    int index;
    double time;
    Eigen::Matrix3Xd organ_positions;
  };
  void work();
  Status write(const Job& job);

  scene::SceneFrames& frames_;
  scene::SceneWorld& world_;
  const std::filesystem::path folder_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;  // under mutex_
  bool busy_ = false;      // a frame is being drawn; under mutex_
  bool closing_ = false;   // no more frames come; under mutex_
  Status error_;           // the first frame that failed; under mutex_
  std::atomic<int> written_{0};
  std::thread thread_;  // last: it starts once the rest is built
};

}  // namespace cubespring::app
