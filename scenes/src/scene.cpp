// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "json_fields.h"
#include "json_lines.h"

namespace cubespring::scene {
namespace {

// A number as a message shows it (6 significant digits).
std::string text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

// A mesh path as the scene gives it, relative to the scene's folder; the file must exist.
Status read_mesh_path(const JsonFields& fields, const std::string& key, const SceneContext& context, std::string& out) {
  if (fields.has(key)) {
    std::string given;
    if (Status status = fields.string(key, given); !status) return status;
    if (given.empty()) return fields.error(key, "must name a mesh file, got an empty string");
    const fs::path path(given);
    out = (path.is_absolute() || context.base_dir.empty() ? path : fs::path(context.base_dir) / path)
              .lexically_normal()
              .string();
  }
  std::error_code ignored;
  if (!fs::is_regular_file(out, ignored)) {
    // quoted and cut: a path of kilobytes, or with a line break in it, keeps the message one line
    const std::string shown = quote_for_message(out, 200);
    if (fields.has(key)) return fields.error(key, "names a mesh file that does not exist: " + shown);
    return fields.error_here("\"" + fields.name_of(key) + "\" is not given and its default does not exist: " + shown);
  }
  return {};
}

Status read_material(const JsonFields& fields, Material& material) {
  if (Status s = fields.check_keys({"young_modulus", "poisson_ratio", "density", "mass_damping", "stiffness_damping"});
      !s)
    return s;
  if (Status s = fields.positive("young_modulus", material.young_modulus); !s) return s;
  if (Status s = fields.number("poisson_ratio", material.poisson_ratio); !s) return s;
  if (!(material.poisson_ratio > kMinPoissonRatio && material.poisson_ratio < kMaxPoissonRatio)) {
    std::ostringstream range;
    range << "must be in (" << kMinPoissonRatio << ", " << kMaxPoissonRatio << "), got " << material.poisson_ratio;
    return fields.error("poisson_ratio", range.str());
  }
  if (Status s = fields.positive("density", material.density); !s) return s;
  if (Status s = fields.non_negative("mass_damping", material.mass_damping); !s) return s;
  return fields.non_negative("stiffness_damping", material.stiffness_damping);
}

Status read_box(const JsonFields& fields, Box& box) {
  if (Status s = fields.check_keys({"lower", "upper"}); !s) return s;
  for (const char* key : {"lower", "upper"}) {
    if (!fields.has(key))
      return fields.error_here("\"" + fields.name_of(key) + "\" is missing: a box needs lower and upper corners [m]");
  }
  if (Status s = fields.vector3("lower", box.lower); !s) return s;
  if (Status s = fields.vector3("upper", box.upper); !s) return s;
  if (!(box.lower.array() <= box.upper.array()).all())
    return fields.error("upper", "must be >= \"lower\" in x, y and z");
  box.line = fields.line();
  return {};
}

Status read_organ(const JsonFields& fields, const SceneContext& context, OrganSpec& organ) {
  if (Status s =
          fields.check_keys({"mesh", "scale", "cell_size", "cells_across", "model", "law", "materials", "fixed_regions",
                             "friction", "face_contacts", "contact_offset", "max_added_mass", "time_step_safety"});
      !s) {
    return s;
  }
  if (Status s = read_mesh_path(fields, "mesh", context, organ.mesh); !s) return s;
  if (Status s = fields.positive("scale", organ.scale); !s) return s;
  if (fields.has("cell_size") && fields.has("cells_across")) {
    return fields.error("cells_across", "and \"cell_size\" are both given: give one");
  }
  if (Status s = fields.positive("cell_size", organ.cell_size); !s) return s;
  if (Status s = fields.integer("cells_across", organ.cells_across, 1, 1000); !s) return s;
  std::string model = cell_model_name(organ.model);
  if (Status s = fields.string("model", model); !s) return s;
  Result<CellModel> parsed = parse_cell_model(model);
  if (!parsed)
    return fields.error("model", "must be \"baudet2007\" or \"exact-bending\", got " + quote_for_message(model));
  organ.model = *parsed;
  std::string law = cell_law_name(organ.law);
  if (Status s = fields.string("law", law); !s) return s;
  Result<CellLaw> parsed_law = parse_cell_law(law);
  if (!parsed_law) return fields.error("law", "must be \"neo-hookean\" or \"springs\", got " + quote_for_message(law));
  organ.law = *parsed_law;
  if (fields.has("materials")) {
    Result<JsonFields> materials = fields.object("materials");
    if (!materials) return materials.status();
    for (const std::string& name : materials->keys()) {
      Result<JsonFields> entry = materials->object(name);
      if (!entry) return entry.status();
      Material material = default_tissue();
      if (Status s = read_material(*entry, material); !s) return s;
      organ.materials[name] = material;
      organ.material_lines[name] = entry->line();
    }
  }
  if (fields.has("fixed_regions")) {
    Result<std::vector<JsonFields>> boxes = fields.objects("fixed_regions");
    if (!boxes) return boxes.status();
    for (const JsonFields& entry : *boxes) {
      Box box;
      if (Status s = read_box(entry, box); !s) return s;
      organ.fixed_regions.push_back(box);
    }
  }
  if (Status s = fields.non_negative("friction", organ.friction); !s) return s;
  if (Status s = fields.non_negative("contact_offset", organ.contact_offset); !s) return s;
  if (Status s = fields.fraction("max_added_mass", organ.max_added_mass); !s) return s;
  if (Status s = fields.positive("time_step_safety", organ.time_step_safety); !s) return s;
  if (organ.time_step_safety > 1.0) {
    std::ostringstream got;
    got << organ.time_step_safety;
    return fields.error("time_step_safety", "must be at most 1 (of the stable step), got " + got.str());
  }
  return fields.boolean("face_contacts", organ.face_contacts);
}

Status read_table(const JsonFields& fields, TableSpec& table) {
  if (Status s = fields.check_keys({"enabled", "height", "half_size"}); !s) return s;
  if (Status s = fields.boolean("enabled", table.enabled); !s) return s;
  if (Status s = fields.number("height", table.height); !s) return s;
  return fields.positive("half_size", table.half_size);
}

Status read_keyframe(const JsonFields& fields, Keyframe& keyframe) {
  if (Status s = fields.check_keys({"time", "position", "orientation", "rotation"}); !s) return s;
  if (Status s = fields.non_negative("time", keyframe.time); !s) return s;
  if (Status s = fields.vector3("position", keyframe.position); !s) return s;
  if (fields.has("orientation") && fields.has("rotation")) {
    return fields.error("rotation", "and \"orientation\" are both given: give one");
  }
  if (Status s = fields.quaternion("orientation", keyframe.orientation); !s) return s;
  if (fields.has("rotation")) {
    Result<JsonFields> rotation = fields.object("rotation");
    if (!rotation) return rotation.status();
    if (Status s = rotation->check_keys({"axis", "degrees"}); !s) return s;
    Eigen::Vector3d axis(0, 0, 1);
    double degrees = 0.0;
    if (Status s = rotation->vector3("axis", axis); !s) return s;
    if (Status s = rotation->number("degrees", degrees); !s) return s;
    if (!(axis.norm() > 1e-12)) return rotation->error("axis", "must not be zero");
    keyframe.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()));
  }
  return {};
}

Status read_tool(const JsonFields& fields, const SceneContext& context, int index, ToolSpec& tool) {
  if (Status s = fields.check_keys({"name", "mesh", "scale", "capsule", "mass", "keyframes", "cut"}); !s) return s;
  tool.name = "tool" + std::to_string(index);
  if (Status s = fields.string("name", tool.name); !s) return s;
  if (tool.name.empty() || tool.name.find_first_of(",\"\n") != std::string::npos) {
    return fields.error("name", "must be a non-empty name without commas, quotes or line breaks (it is a CSV field)");
  }
  // the mesh is what is drawn; the capsule, when given or when there is no mesh, is what touches
  if (fields.has("mesh")) {
    if (Status s = read_mesh_path(fields, "mesh", context, tool.mesh); !s) return s;
  }
  if (fields.has("capsule") || !fields.has("mesh")) {
    CapsuleSpec spec;
    if (fields.has("capsule")) {
      Result<JsonFields> capsule = fields.object("capsule");
      if (!capsule) return capsule.status();
      if (Status s = capsule->check_keys({"radius", "length"}); !s) return s;
      if (Status s = capsule->positive("radius", spec.radius); !s) return s;
      if (Status s = capsule->positive("length", spec.length); !s) return s;
      if (spec.length < 2.0 * spec.radius) return capsule->error("length", "must be at least twice the radius");
    }
    tool.capsule = spec;
  }
  if (Status s = fields.positive("scale", tool.scale); !s) return s;
  if (Status s = fields.positive("mass", tool.mass); !s) return s;
  constexpr double kMaxToolMass = 100.0;  // [kg]
  constexpr double kMinToolMass = 1e-6;   // [kg]: lighter, a coupling's step would be microseconds
  if (!(tool.mass >= kMinToolMass && tool.mass <= kMaxToolMass))
    return fields.error(
        "mass", "must be from " + text(kMinToolMass) + " to " + text(kMaxToolMass) + " kg, got " + text(tool.mass));
  // a capsule of 1e308 m read fine and gave every torque as NaN
  constexpr double kMaxToolSize = 100.0;  // [m]
  if (tool.capsule && !(tool.scale * tool.capsule->length <= kMaxToolSize)) {
    Result<JsonFields> capsule = fields.object("capsule");
    const std::string size = text(tool.scale * tool.capsule->length);
    return capsule ? capsule->error(
                         "length", "times the scale is " + size + " m, more than a tool's " + text(kMaxToolSize) + " m")
                   : fields.error("scale", "makes the capsule " + size + " m long, more than a tool's " +
                                               text(kMaxToolSize) + " m");
  }
  if (fields.has("cut")) {
    Result<JsonFields> cut = fields.object("cut");
    if (!cut) return cut.status();
    if (Status s = cut->check_keys({"mode", "force_threshold"}); !s) return s;
    std::string mode = "remove";
    if (Status s = cut->string("mode", mode); !s) return s;
    if (mode == "separate") {
      return cut->error("mode",
                        "\"separate\" (a blade that splits the tissue along its path) is not built yet; "
                        "\"remove\" (a cautery that burns the cells it reaches) is");
    }
    if (mode != "remove") return cut->error("mode", "must be \"remove\", got \"" + mode + "\"");
    if (!tool.capsule) return fields.error("cut", "needs the tool's capsule: a cautery cuts with its round tip");
    CutSpec spec;
    if (Status s = cut->non_negative("force_threshold", spec.force_threshold); !s) return s;
    tool.cut = spec;
  }
  if (fields.has("keyframes")) {
    Result<std::vector<JsonFields>> keyframes = fields.objects("keyframes");
    if (!keyframes) return keyframes.status();
    for (const JsonFields& entry : *keyframes) {
      Keyframe keyframe;
      if (Status s = read_keyframe(entry, keyframe); !s) return s;
      if (!tool.keyframes.empty() && !(keyframe.time > tool.keyframes.back().time)) {
        return entry.error("time", "must be later than the key frame before it (" +
                                       std::to_string(tool.keyframes.back().time) + " s)");
      }
      tool.keyframes.push_back(keyframe);
    }
  }
  return {};
}

Status read_lights(const JsonFields& fields, RenderSpec& render) {
  if (fields.has("lights")) {
    Result<std::vector<JsonFields>> lights = fields.objects("lights");
    if (!lights) return lights.status();
    if (lights->size() > 8) {
      return fields.error("lights",
                          "has " + std::to_string(lights->size()) + " lights: at most 8 (OpenGL's fixed pipeline)");
    }
    render.lights.clear();
    for (const JsonFields& entry : *lights) {
      if (Status s = entry.check_keys({"direction", "colour"}); !s) return s;
      Light light;
      if (Status s = entry.vector3("direction", light.direction); !s) return s;
      if (!(light.direction.norm() > 0.0)) return entry.error("direction", "must not be zero");
      Eigen::Vector3d colour = light.colour.cast<double>();
      if (Status s = entry.vector3("colour", colour); !s) return s;
      if ((colour.array() < 0.0).any()) return entry.error("colour", "must have no negative channel");
      light.colour = colour.cast<float>();
      render.lights.push_back(light);
    }
  }
  return fields.fraction("ambient", render.ambient);
}

Status read_render(const JsonFields& fields, RenderSpec& render) {
  if (Status s = fields.check_keys({"width", "height", "supersampling", "camera", "lights", "ambient", "wireframe",
                                    "colour_map", "colour_range", "strain_range"});
      !s) {
    return s;
  }
  if (Status s = fields.integer("width", render.width, 1, 8192); !s) return s;
  if (Status s = fields.integer("height", render.height, 1, 8192); !s) return s;
  if (Status s = fields.integer("supersampling", render.supersampling, 1, 8); !s) return s;
  if (fields.has("camera")) {
    Result<JsonFields> camera = fields.object("camera");
    if (!camera) return camera.status();
    if (Status s = camera->check_keys({"position", "target", "up", "fov"}); !s) return s;
    if (Status s = camera->vector3("position", render.camera.position); !s) return s;
    if (Status s = camera->vector3("target", render.camera.target); !s) return s;
    if (Status s = camera->vector3("up", render.camera.up); !s) return s;
    if (Status s = camera->positive("fov", render.camera.vertical_fov_degrees); !s) return s;
    if (!(render.camera.vertical_fov_degrees < 180.0)) {
      std::ostringstream got;
      got << render.camera.vertical_fov_degrees;
      return camera->error("fov", "must be below 180 degrees, got " + got.str());
    }
    if (Status s = validate(render.camera); !s)
      return camera->error_here("\"" + fields.name_of("camera") + "\": " + s.message());
  }
  if (Status s = read_lights(fields, render); !s) return s;
  if (Status s = fields.boolean("wireframe", render.wireframe); !s) return s;
  std::string colour_map = "displacement";
  if (Status s = fields.string("colour_map", colour_map); !s) return s;
  if (colour_map == "displacement") {
    render.colour_map = ColourMode::kDisplacement;
  } else if (colour_map == "strain") {
    render.colour_map = ColourMode::kStrain;
  } else if (colour_map == "none") {
    render.colour_map = ColourMode::kNone;
  } else {
    return fields.error("colour_map",
                        "must be \"displacement\", \"strain\" or \"none\", got " + quote_for_message(colour_map));
  }
  if (Status s = fields.positive("colour_range", render.colour_range); !s) return s;
  return fields.positive("strain_range", render.strain_range);
}

// The run counts its steps and frames in int and lists the frames: a time step longer than the
// story, or so short or a frame rate so high that the counts pass what it can hold, is refused
// (it would give one frame of step 0 repeated, or overflow the counts).
Status check_counts(const JsonFields& fields, const Scene& scene) {
  constexpr double kMaxSteps = 1e9, kMaxFrames = 1e6;
  // a count that a defaulted time_step or frame_rate makes too large is the duration's fault
  const bool step_given = fields.has("time_step"), rate_given = fields.has("frame_rate");
  const std::string step = text(scene.time_step) + " s", rate = text(scene.frame_rate) + " frames/s";
  if (scene.time_step > scene.duration) {
    if (!step_given) {
      return fields.error("duration", "of " + text(scene.duration) + " s is shorter than the default time step of " +
                                          step + " (give a \"time_step\")");
    }
    return fields.error("time_step",
                        "of " + step + " is longer than the scene's duration of " + text(scene.duration) + " s");
  }
  if (scene.duration / scene.time_step > kMaxSteps || scene.settle_time / scene.time_step > kMaxSteps) {
    const std::string span =
        "the settle time and duration of " + text(scene.settle_time) + " s and " + text(scene.duration) + " s";
    if (!step_given) {
      return fields.error(
          scene.settle_time > scene.duration ? "settle_time" : "duration",
          "makes more than " + text(kMaxSteps) + " steps of the default time step of " + step + " (" + span + ")");
    }
    return fields.error("time_step", "of " + step + " gives more than " + text(kMaxSteps) + " steps over " + span);
  }
  if (scene.frames == 0 && scene.duration * scene.frame_rate + 1.0 > kMaxFrames) {
    if (!rate_given) {
      return fields.error("duration", "of " + text(scene.duration) + " s makes more than " + text(kMaxFrames) +
                                          " frames at the default frame rate of " + rate);
    }
    return fields.error("frame_rate", "of " + rate + " gives more than " + text(kMaxFrames) +
                                          " frames over the duration of " + text(scene.duration) + " s");
  }
  return {};
}
Status read_scene(const JsonFields& fields, const SceneContext& context, Scene& scene) {
  if (Status s = fields.check_keys({"organ", "table", "tools", "gravity", "integrator", "time_step", "settle_time",
                                    "duration", "frame_rate", "frames", "render", "output"});
      !s) {
    return s;
  }
  if (fields.has("organ")) {
    Result<JsonFields> organ = fields.object("organ");
    if (!organ) return organ.status();
    if (Status s = read_organ(*organ, context, scene.organ); !s) return s;
  } else if (Status s = read_mesh_path(fields, "organ.mesh", context, scene.organ.mesh); !s) {
    return s;
  }
  if (fields.has("table")) {
    Result<JsonFields> table = fields.object("table");
    if (!table) return table.status();
    if (Status s = read_table(*table, scene.table); !s) return s;
  }
  if (fields.has("tools")) {
    Result<std::vector<JsonFields>> tools = fields.objects("tools");
    if (!tools) return tools.status();
    for (std::size_t i = 0; i < tools->size(); ++i) {
      ToolSpec tool;
      if (Status s = read_tool((*tools)[i], context, static_cast<int>(i), tool); !s) return s;
      for (const ToolSpec& other : scene.tools) {
        if (other.name == tool.name)
          return (*tools)[i].error("name", quote_for_message(tool.name) + " is already a tool's name");
      }
      scene.tools.push_back(tool);
    }
  }
  if (Status s = fields.vector3("gravity", scene.gravity); !s) return s;
  // 1e308 read fine and stopped the organ with the API's name for it, loads.gravity
  constexpr double kMaxGravity = 1e3;  // [m/s^2], a hundred g
  if (!(scene.gravity.norm() <= kMaxGravity)) {
    return fields.error("gravity", "of (" + text(scene.gravity.x()) + ", " + text(scene.gravity.y()) + ", " +
                                       text(scene.gravity.z()) + ") m/s^2 is stronger than " + text(kMaxGravity) +
                                       " m/s^2");
  }
  std::string integrator = "symplectic-euler";
  if (Status s = fields.string("integrator", integrator); !s) return s;
  if (integrator == "symplectic-euler") {
    scene.integrator = Integrator::kSymplecticEuler;
  } else if (integrator == "implicit-euler") {
    scene.integrator = Integrator::kImplicitEuler;
  } else {
    return fields.error("integrator",
                        "must be \"symplectic-euler\" or \"implicit-euler\", got " + quote_for_message(integrator));
  }
  if (Status s = fields.positive("time_step", scene.time_step); !s) return s;
  if (Status s = fields.non_negative("settle_time", scene.settle_time); !s) return s;
  // the story lasts until the last key frame unless the scene says otherwise
  scene.duration = 0.0;
  for (const ToolSpec& tool : scene.tools) {
    if (!tool.keyframes.empty()) scene.duration = std::max(scene.duration, tool.keyframes.back().time);
  }
  if (scene.duration <= 0.0) scene.duration = 1.0;
  if (Status s = fields.positive("duration", scene.duration); !s) return s;
  if (fields.has("frames") && fields.has("frame_rate"))
    return fields.error("frames", "and \"frame_rate\" are both given: give one");
  if (Status s = fields.positive("frame_rate", scene.frame_rate); !s) return s;
  if (Status s = fields.integer("frames", scene.frames, 1, 1000000); !s) return s;
  if (Status s = check_counts(fields, scene); !s) return s;
  if (fields.has("render")) {
    Result<JsonFields> render = fields.object("render");
    if (!render) return render.status();
    if (Status s = read_render(*render, scene.render); !s) return s;
  }
  if (Status s = fields.string("output", scene.output); !s) return s;
  if (scene.output.empty()) return fields.error("output", "must name a folder, got an empty string");
  return {};
}

}  // namespace

Material default_tissue() { return soft_tissue(8e3); }

std::vector<double> Scene::frame_times() const {
  std::vector<double> times;
  if (frames > 0) {
    for (int f = 0; f < frames; ++f) times.push_back(frames > 1 ? duration * f / (frames - 1) : 0.0);
    return times;
  }
  const int count = static_cast<int>(std::floor(duration * frame_rate + 1e-9)) + 1;
  for (int f = 0; f < count; ++f) times.push_back(f / frame_rate);
  return times;
}

Result<Scene> parse_scene(const std::string& text, const SceneContext& context) {
  Result<JsonWithLines> document = parse_json_with_lines(text, context.source);
  if (!document) return document.status();
  Scene scene;
  scene.source = context.source;
  scene.organ.mesh =
      context.data_dir.empty() ? std::string("liver.obj") : (fs::path(context.data_dir) / "liver.obj").string();
  // the default organ, the liver, from the front and above
  scene.render.camera.position = Eigen::Vector3d(0.06, -0.20, 0.21);
  scene.render.camera.target = Eigen::Vector3d(0.01, 0.0, 0.03);
  scene.render.camera.vertical_fov_degrees = 35.0;
  const JsonFields fields(*document, context.source, "", "");
  if (Status status = read_scene(fields, context, scene); !status) return status;
  return scene;
}

Result<Scene> load_scene(const std::string& path, const std::string& data_dir) {
  std::error_code error;
  if (fs::is_directory(path, error)) return Status::error(path + " is a folder, not a scene file (JSON)");
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (!error && bytes > kMaxSceneBytes) {
    return Status::error(path + " is " + std::to_string(bytes / 1000000) + " MB: a scene file is at most " +
                         std::to_string(kMaxSceneBytes / 1000000) + " MB (its meshes are files of their own)");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status::error("cannot open the scene file " + path);
  std::ostringstream text;
  text << file.rdbuf();
  SceneContext context;
  context.source = path;
  context.base_dir = fs::path(path).parent_path().string();
  context.data_dir = data_dir;
  return parse_scene(text.str(), context);
}

}  // namespace cubespring::scene
