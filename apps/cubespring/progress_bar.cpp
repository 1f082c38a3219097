// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <string>

namespace cubespring::app {
namespace {

constexpr int kBarWidth = 30;
constexpr double kRedrawSeconds = 0.1;

}  // namespace

ProgressBar::ProgressBar(int frames, double duration)
    : frames_(frames),
      duration_(duration),
      terminal_(isatty(fileno(stderr)) != 0),
      start_(Clock::now()),
      last_draw_(start_) {}

void ProgressBar::update(int frames_done, double time) {
  const Clock::time_point now = Clock::now();
  if (terminal_) {
    if (std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds) return;
    last_draw_ = now;
    draw(frames_done, time);
    return;
  }
  const int tenth = frames_ > 0 ? 10 * frames_done / frames_ : 10;
  if (tenth == last_tenth_) return;
  last_tenth_ = tenth;
  draw(frames_done, time);
}

void ProgressBar::finish(int frames_done, double time) {
  if (terminal_ || last_tenth_ != 10) draw(frames_done, time);
  if (terminal_) std::fputc('\n', stderr);
  std::fflush(stderr);
}

void ProgressBar::draw(int frames_done, double time) {
  const double fraction = duration_ > 0.0 ? std::clamp(time / duration_, 0.0, 1.0) : 1.0;
  const int filled = static_cast<int>(fraction * kBarWidth + 0.5);
  const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                          std::string(static_cast<std::size_t>(kBarWidth - filled), '.');
  const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
  const double speed = wall > 0.0 ? time / wall : 0.0;
  std::fprintf(stderr, "%s[%s] frame %d/%d  t = %.2f s  %.2fx real time%s", terminal_ ? "\r" : "", bar.c_str(),
               frames_done, frames_, time, speed, terminal_ ? "  " : "\n");
  std::fflush(stderr);
}

}  // namespace cubespring::app
