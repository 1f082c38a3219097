// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "scene_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cubespring/render/force_plot.h"
#include "cubespring/render/image.h"
#include "cubespring/scene/scene_frames.h"
#include "cubespring/scene/scene_world.h"
#include "frame_writer.h"
#include "progress_bar.h"

namespace cubespring::app {

const char* const kToolForceCsvHeader =
    "time_s,tool,force_x_N,force_y_N,force_z_N,force_magnitude_N,torque_x_Nm,torque_y_Nm,torque_z_Nm,contacts,"
    "penetration_m,cells_removed";

namespace {

namespace fs = std::filesystem;

// The number of a file named as frame_name() names frames (frame_ and 4 or more digits, .png), or
// -1 for any other name; numbers past 9 digits read as the largest int.
long frame_number(const std::string& name) {
  const std::string prefix = "frame_", suffix = ".png";
  if (name.size() < prefix.size() + 4 + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return -1;
  }
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return digits.size() > 9 ? std::numeric_limits<int>::max() : std::stol(digits);
}

// Frames of an earlier, longer run would read as part of this one: remove those past the last.
void remove_stale_frames(const fs::path& folder, int frames) {
  std::error_code ignored;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ignored)) {
    if (frame_number(entry.path().filename().string()) >= frames) fs::remove(entry.path(), ignored);
  }
}

void print_summary(const scene::Scene& scene, const scene::SceneWorld& world, int steps, int frames) {
  const scene::OrganSummary& s = world.summary();
  std::fprintf(stderr, "scene %s: organ %s, %d cells of %.1f mm, %d nodes (%d fixed), sub-step %.3f ms\n",
               scene.source.c_str(), scene.organ.mesh.c_str(), s.cells, 1000.0 * s.cell_size, s.nodes, s.fixed_nodes,
               1000.0 * s.sub_step);
  for (const std::string& note : s.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
  std::fprintf(stderr, "%.2f s in %d steps of %.2f ms after %.2f s of settling; %d frames of %dx%d\n", scene.duration,
               steps, 1000.0 * scene.time_step, scene.settle_time, frames, scene.render.width, scene.render.height);
}

// The step at which each frame is taken: the one nearest its time.
std::vector<int> frame_steps(const std::vector<double>& times, double dt) {
  std::vector<int> steps;
  for (const double t : times) steps.push_back(static_cast<int>(std::lround(t / dt)));
  return steps;
}

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", t);
  return text;
}

// One CSV row per tool for the step that ended at t, and the magnitudes for the plot.
void record_forces(scene::SceneWorld& world, double t, std::ostream& csv, std::vector<ForceSeries>& series) {
  const auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return std::string(text);
  };
  char time[32];
  std::snprintf(time, sizeof time, "%.6f", t);
  for (std::size_t i = 0; i < world.tools().size(); ++i) {
    const scene::SceneTool& tool = world.tools()[i];
    const bullet::ContactWrench w = world.world().getContactWrench(tool.body.get());
    // the plugin gives the torque about the collision body's origin; the CSV's is about the tip
    const Eigen::Isometry3d pose = world.tool_pose(tool);
    const Eigen::Vector3d torque =
        w.torque + (pose * tool.shape_offset.translation() - pose.translation()).cross(w.force);
    csv << time << ',' << tool.name << ',' << number(w.force.x()) << ',' << number(w.force.y()) << ','
        << number(w.force.z()) << ',' << number(w.force.norm()) << ',' << number(torque.x()) << ','
        << number(torque.y()) << ',' << number(torque.z()) << ',' << w.contacts << ',' << number(w.penetration) << ','
        << tool.cells_removed << '\n';
    series[i].time.push_back(t);
    series[i].magnitude.push_back(w.force.norm());
  }
}

// The cells the cutting tools reach burnt away, once the frames already queued are drawn (they
// read the organ as it was); a line on stderr for each step that cuts.
Status cut_organ(scene::SceneWorld& world, scene::SceneFrames& frames, FrameWriter& writer, double t) {
  const std::vector<scene::ToolCut> due = world.cuts_due();
  if (due.empty()) return {};
  if (Status s = writer.finish(); !s) return s;
  const auto start = std::chrono::steady_clock::now();
  Result<bullet::SoftBody::Cut> cut = world.apply_cuts(due);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!cut) return Status::error(cut.message() + " (at t = " + seconds(t) + ")");
  frames.carry_rest(cut->visual_vertex_source, scene::SceneFrames::organ_vertices(world));
  std::string tools;
  for (const scene::ToolCut& tool_cut : due) tools += (tools.empty() ? "" : ", ") + world.tools()[tool_cut.tool].name;
  std::fprintf(stderr, "t = %.3f s: %s removed %d cells (%.2f g) in %.1f ms; the organ has %d cells in %d piece%s\n", t,
               tools.c_str(), cut->removed_cells, 1e3 * cut->removed_mass, 1e3 * took,
               world.organ().model().num_cells(), cut->pieces, cut->pieces == 1 ? "" : "s");
  return {};
}

}  // namespace

Result<RunOutput> run_scene(const scene::Scene& scene, int threads) {
  Result<std::unique_ptr<scene::SceneWorld>> built = scene::SceneWorld::create(scene);
  if (!built) return built.status();
  scene::SceneWorld& world = **built;
  if (Status chosen = world.organ().set_threads(threads); !chosen) return chosen;
  Result<scene::SceneFrames> made = scene::SceneFrames::create(scene);
  if (!made) return made.status();
  scene::SceneFrames& frames = *made;

  const double dt = scene.time_step;
  const int steps = static_cast<int>(std::lround(scene.duration / dt));
  const std::vector<int> frame_at = frame_steps(scene.frame_times(), dt);
  const int frame_count = static_cast<int>(frame_at.size());
  print_summary(scene, world, steps, frame_count);

  const fs::path folder(scene.output);
  std::error_code error;
  fs::create_directories(folder, error);
  if (error || !fs::is_directory(folder)) {
    return Status::error("cannot create the output folder " + scene.output + (error ? ": " + error.message() : ""));
  }
  remove_stale_frames(folder, frame_count);
  RunOutput output;
  output.csv = (folder / "tool_forces.csv").string();
  output.plot = (folder / "tool_force.png").string();
  std::ofstream csv(output.csv);
  if (!csv) return Status::error("cannot write " + output.csv);
  csv << kToolForceCsvHeader << '\n';

  if (Status s = scene::settle(world, scene); !s) return s;
  frames.set_rest(scene::SceneFrames::organ_vertices(world));

  std::vector<ForceSeries> series(world.tools().size());
  for (std::size_t i = 0; i < series.size(); ++i) series[i].name = world.tools()[i].name;
  ProgressBar progress(frame_count, scene.duration);
  FrameWriter writer(frames, world, folder);  // the frames are drawn beside the steps
  int next_frame = 0;
  for (int n = 0; n <= steps; ++n) {
    const double t = n * dt;
    if (n > 0) {
      world.place_tools(t);  // where the step ends: Bullet derives the tools' velocities from it
      if (Status s = world.step(dt); !s) return Status::error(s.message() + " (at t = " + seconds(t) + ")");
      if (Status s = cut_organ(world, frames, writer, t); !s) return s;
      record_forces(world, t, csv, series);
    }
    while (next_frame < frame_count && frame_at[static_cast<std::size_t>(next_frame)] <= n) {
      if (Status s = writer.submit(next_frame, t, world.organ().state().positions); !s) return s;
      ++next_frame;
    }
    progress.update(writer.written(), t);
  }
  if (Status s = writer.finish(); !s) return s;
  progress.finish(writer.written(), steps * dt);
  csv.close();
  if (!csv) return Status::error("cannot write " + output.csv);
  if (Status s = write_png(plot_forces(series), output.plot); !s) return s;
  output.frames = next_frame;
  return output;
}

}  // namespace cubespring::app
