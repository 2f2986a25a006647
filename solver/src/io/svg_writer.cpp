#include "io/svg_writer.hpp"

#include "io/number_text.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace rbla::io {
namespace {

using analysis::AnalysisResult;
using analysis::BlockMotion;
using analysis::InterfaceState;
using analysis::Verdict;
using model::Vec3;

// Largest drawn vertex displacement as a fraction of the bounding-box diagonal: big enough to
// read the mechanism, small enough that blocks stay recognisable next to their outlines.
constexpr double kAutoAmplitudeFraction = 0.08;
constexpr double kMargin = 20.0;
constexpr double kLegendItemWidth = 150.0;
constexpr int kLegendItems = 7;

constexpr const char* kOpeningColour = "#d62728";
constexpr const char* kSlidingColour = "#1f77b4";
constexpr const char* kOpeningSlidingColour = "#9467bd";
constexpr const char* kHingeColour = "#ff7f0e";
constexpr const char* kGhostColour = "#b4b4b4";
constexpr int kMovingRgb = 0xf4b183;
constexpr int kRestingRgb = 0xdcd7cd;
constexpr int kSupportRgb = 0x5a5a5a;
// The joints whose friction coefficient moves the result most (result.sensitivities), marked and
// listed under the drawing: enough to point at the ones to inspect, few enough to read.
constexpr std::size_t kInfluentialJoints = 5;
constexpr const char* kInfluenceColour = "#111111";
constexpr double kFooterLine = 18.0;

std::string escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 forbids most control characters even when escaped; ids from CAD may carry them.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += '?';
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string printf_string(const char* format, double value) { return number_text(value, format); }

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

// Five significant digits in fixed notation (881.75, 12.346, 0.88175): readable for reactions
// whatever the force unit.
std::string significant5(double value) {
  if (value == 0.0 || !std::isfinite(value)) return fixed(value, 2);
  const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(value))));
  return fixed(value, std::clamp(4 - magnitude, 0, 10));
}

// Page coordinates to 0.1 px: finer than any screen shows, and it keeps a 2000-block wall small.
void append_coordinate(std::string& out, double value) {
  double rounded = std::round(value * 10.0) / 10.0;
  if (rounded == 0.0) rounded = 0.0;  // no "-0"
  char buffer[32];
  int n = std::snprintf(buffer, sizeof buffer, "%.1f", rounded);
  if (n >= 2 && buffer[n - 1] == '0' && buffer[n - 2] == '.') n -= 2;
  out.append(buffer, static_cast<std::size_t>(n));
}

std::string coordinate(double value) {
  std::string out;
  append_coordinate(out, value);
  return out;
}

std::string rgb_hex(int rgb) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%06x", rgb & 0xffffff);
  return buffer;
}

// Lambert-like shading so faces turned away from the viewer read as sides of a solid.
std::string shaded(int rgb, double brightness) {
  auto channel = [&](int shift) {
    const double c = ((rgb >> shift) & 0xff) * brightness;
    return std::clamp(static_cast<int>(std::lround(c)), 0, 255);
  };
  return rgb_hex((channel(16) << 16) | (channel(8) << 8) | channel(0));
}

const char* verdict_words(Verdict verdict) {
  switch (verdict) {
    case Verdict::Collapse: return "collapse";
    case Verdict::NoMechanism: return "no mechanism";
    case Verdict::CannotStand: return "cannot stand";
    case Verdict::SolverFailure: return "solver failure";
    case Verdict::TimeLimit: return "time limit";
    case Verdict::IterationLimit: return "iteration limit";
    case Verdict::Cancelled: return "cancelled";
  }
  return "?";
}

const char* state_colour(InterfaceState state) {
  switch (state) {
    case InterfaceState::Closed: return nullptr;
    case InterfaceState::Opening: return kOpeningColour;
    case InterfaceState::Sliding: return kSlidingColour;
    case InterfaceState::OpeningSliding: return kOpeningSlidingColour;
    case InterfaceState::Hinge: return kHingeColour;
  }
  return nullptr;
}

const char* state_words(InterfaceState state) {
  switch (state) {
    case InterfaceState::Closed: return "closed";
    case InterfaceState::Opening: return "opening";
    case InterfaceState::Sliding: return "sliding";
    case InterfaceState::OpeningSliding: return "opening + sliding";
    case InterfaceState::Hinge: return "hinge";
  }
  return "?";
}

const char* friction_words(model::FrictionModel friction) {
  switch (friction) {
    case model::FrictionModel::Associative: return "associative";
    case model::FrictionModel::NonAssociative: return "non-associative";
  }
  return "?";
}

std::string cone_words(const AnalysisResult& result) {
  switch (result.cone) {
    case model::ConeKind::Exact: return "exact";
    case model::ConeKind::PyramidInscribed:
      return "inscribed pyramid (" + std::to_string(result.pyramid_faces) + " faces)";
    case model::ConeKind::PyramidCircumscribed:
      return "circumscribed pyramid (" + std::to_string(result.pyramid_faces) + " faces)";
  }
  return "?";
}

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

bool has_mechanism(const AnalysisResult& result) {
  return result.verdict == Verdict::Collapse || result.verdict == Verdict::CannotStand;
}

const BlockMotion* motion_of(const AnalysisResult& result, std::size_t block) {
  return block < result.mechanism.blocks.size() ? &result.mechanism.blocks[block] : nullptr;
}

/// p -> g + R (p - g) + t, the exact rigid motion of a block for a finite amplitude.
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 centre = Vec3::Zero();
  Vec3 shift = Vec3::Zero();
  Vec3 apply(const Vec3& p) const { return centre + rotation * (p - centre) + shift; }
};

RigidMotion rigid_motion(const model::Block& block, const BlockMotion* motion, double amplitude) {
  RigidMotion out;
  out.centre = block.centroid;
  if (!motion || amplitude == 0.0) return out;
  out.shift = amplitude * motion->translation;
  const double angle = amplitude * motion->rotation.norm();
  if (angle > 0.0) {
    out.rotation = Eigen::AngleAxisd(angle, motion->rotation.normalized()).toRotationMatrix();
  }
  return out;
}

int vertical_axis(const model::Model& model) {
  int axis = 2;
  model.gravity.cwiseAbs().maxCoeff(&axis);
  return axis;
}

int auto_view_axis(const model::Model& model, const AnalysisResult& result) {
  if (result.planar && result.planar_axis >= 0 && result.planar_axis < 3) return result.planar_axis;
  const int vertical = vertical_axis(model);
  const model::BoundingBox box = model.bounding_box();
  const Vec3 extent = model.blocks.empty() ? Vec3::Zero() : Vec3(box.max - box.min);
  Vec3 translation_sq = Vec3::Zero();
  for (const BlockMotion& motion : result.mechanism.blocks) {
    translation_sq += motion.translation.cwiseAbs2();
  }
  const double total = translation_sq.sum();
  int best = -1;
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == vertical) continue;
    if (best < 0) {
      best = axis;
      continue;
    }
    const double difference = translation_sq[axis] - translation_sq[best];
    // Translations equal up to round-off (no mechanism, or a symmetric one): a wall is still best
    // seen face-on, i.e. along its thinnest horizontal extent.
    if (std::abs(difference) <= 1e-9 * total) {
      if (extent[axis] < extent[best]) best = axis;
    } else if (difference < 0.0) {
      best = axis;
    }
  }
  return best;
}

void view_frame(const model::Model& model, int axis, SvgView& view) {
  const Vec3 along = Vec3::Unit(axis);
  Vec3 gravity = model.gravity;
  if (gravity.norm() == 0.0) gravity = -Vec3::UnitZ();
  gravity.normalize();
  const Vec3 up = -gravity - (-gravity.dot(along)) * along;
  if (up.norm() < 1e-6) {
    // A plan view: look down from above with the next-but-one axis up (y up when looking along z).
    view.up = Vec3::Unit((axis + 2) % 3);
    view.toward = gravity.dot(along) < 0.0 ? along : Vec3(-along);
  } else {
    view.up = up.normalized();
    view.toward = along;
    // Of the two sides, the one from which the remaining axis points right (the usual elevations).
    if (view.up.cross(view.toward).sum() < 0.0) view.toward = -along;
  }
  view.right = view.up.cross(view.toward);
}

double max_vertex_speed(const model::Model& model, const AnalysisResult& result) {
  double speed = 0.0;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const BlockMotion* motion = motion_of(result, b);
    if (!motion) continue;
    const model::Block& block = model.blocks[b];
    for (const Vec3& p : block.vertices) {
      const Vec3 v = motion->translation + motion->rotation.cross(p - block.centroid);
      speed = std::max(speed, v.norm());
    }
  }
  return speed;
}

int legend_rows(double width) {
  const int per_row = std::max(1, static_cast<int>((width - 2 * kMargin) / kLegendItemWidth));
  return (kLegendItems + per_row - 1) / per_row;
}

double header_height(double width) { return 70.0 + 22.0 * legend_rows(width) + 10.0; }

/// (interface, d value / d mu) of the most influential joints, largest magnitude first, as the
/// result JSON lists them; empty without sensitivities.
std::vector<std::pair<int, double>> influential_joints(const model::Model& model, const AnalysisResult& result) {
  if (!result.sensitivities) return {};
  std::vector<std::pair<int, double>> joints;
  for (const auto& entry : result.sensitivities->interface_friction) {
    if (entry.first >= 0 && static_cast<std::size_t>(entry.first) < model.interfaces.size()) joints.push_back(entry);
  }
  std::stable_sort(joints.begin(), joints.end(),
                   [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  if (joints.size() > kInfluentialJoints) joints.resize(kInfluentialJoints);
  return joints;
}

/// The list of influential joints under the drawing: a heading and one line per joint.
double footer_height(std::size_t num_joints) { return num_joints == 0 ? 0.0 : kFooterLine * (num_joints + 1) + 6.0; }

struct Scene {
  SvgView view;
  std::vector<RigidMotion> motions;             // per block
  std::vector<std::vector<Vec3>> displaced;     // per block, per vertex
};

Scene build_scene(const model::Model& model, const AnalysisResult& result, const SvgOptions& options) {
  Scene scene;
  SvgView& view = scene.view;
  view.view_axis = (options.view_axis >= 0 && options.view_axis < 3) ? options.view_axis
                                                                     : auto_view_axis(model, result);
  view_frame(model, view.view_axis, view);

  if (has_mechanism(result)) {
    if (options.amplitude >= 0.0) {
      view.amplitude = options.amplitude;
    } else {
      const double speed = max_vertex_speed(model, result);
      const double diagonal = model.blocks.empty() ? 0.0 : model.bounding_box().diagonal();
      view.amplitude = speed > 0.0 ? kAutoAmplitudeFraction * diagonal / speed : 0.0;
    }
  }

  const std::size_t n = model.blocks.size();
  scene.motions.resize(n);
  scene.displaced.resize(n);
  const double inf = std::numeric_limits<double>::infinity();
  double x_min = inf, x_max = -inf, y_min = inf, y_max = -inf;
  auto extend = [&](const Vec3& p) {
    const double x = view.right.dot(p), y = view.up.dot(p);
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
  };
  for (std::size_t b = 0; b < n; ++b) {
    const model::Block& block = model.blocks[b];
    scene.motions[b] = rigid_motion(block, motion_of(result, b), view.amplitude);
    scene.displaced[b].reserve(block.vertices.size());
    for (const Vec3& p : block.vertices) {
      scene.displaced[b].push_back(scene.motions[b].apply(p));
      extend(p);
      extend(scene.displaced[b].back());
    }
  }
  if (!(x_min <= x_max)) x_min = x_max = y_min = y_max = 0.0;

  view.width = std::max(300, options.width_px);
  const double header = header_height(view.width);
  const double drawing_width = view.width - 2.0 * kMargin;
  // A tower seen side-on would otherwise give a page many screens tall.
  const double max_drawing_height = 1.25 * view.width;
  const double tiny = 1e-12;
  const double extent_x = std::max(x_max - x_min, tiny), extent_y = std::max(y_max - y_min, tiny);
  view.scale = std::min(drawing_width / extent_x, max_drawing_height / extent_y);
  if (!std::isfinite(view.scale) || view.scale <= 0.0) view.scale = 1.0;
  view.origin_x = kMargin + 0.5 * (drawing_width - (x_max - x_min) * view.scale) - x_min * view.scale;
  view.origin_y = header + y_max * view.scale;
  view.height = header + (y_max - y_min) * view.scale + kMargin +
                footer_height(influential_joints(model, result).size());
  return scene;
}

// Newell's normal: robust for slightly non-planar faces; its length is twice the area.
Vec3 newell_normal(const std::vector<Vec3>& vertices, const std::vector<int>& face) {
  Vec3 normal = Vec3::Zero();
  const std::size_t k = face.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = vertices[static_cast<std::size_t>(face[i])];
    const Vec3& b = vertices[static_cast<std::size_t>(face[(i + 1) % k])];
    normal += a.cross(b);
  }
  return normal;
}

bool valid_face(const std::vector<int>& face, std::size_t num_vertices) {
  if (face.size() < 3) return false;
  for (int i : face) {
    if (i < 0 || static_cast<std::size_t>(i) >= num_vertices) return false;
  }
  return true;
}

void append_point(std::string& out, const SvgView& view, const Vec3& p) {
  const Eigen::Vector2d q = view.to_page(p);
  append_coordinate(out, q.x());
  out += ',';
  append_coordinate(out, q.y());
}

void append_polygon_path(std::string& out, const SvgView& view, const std::vector<Vec3>& vertices,
                         const std::vector<int>& face) {
  for (std::size_t i = 0; i < face.size(); ++i) {
    out += i == 0 ? 'M' : 'L';
    append_point(out, view, vertices[static_cast<std::size_t>(face[i])]);
  }
  out += 'Z';
}

void append_text(std::string& out, double x, double y, const std::string& text, const std::string& attributes) {
  out += "<text x=\"" + coordinate(x) + "\" y=\"" + coordinate(y) + "\"" + (attributes.empty() ? "" : " ") +
         attributes + ">" + escape(text) + "</text>\n";
}

/// A non-associative state that did not pass the fixed-point test is drawn, but not as a collapse
/// state (the verdict sentence says why).
std::string certification_words(const AnalysisResult& result) {
  const bool uncertified =
      result.friction_model == model::FrictionModel::NonAssociative && !result.non_associative_converged;
  return uncertified ? " — non-associative, not certified" : "";
}

std::string collapse_title(const model::Model& model, const AnalysisResult& result) {
  if (result.base_reaction && (result.type == model::AnalysisType::Settlement || !result.load_multiplier)) {
    const double factor = model.units.force_to_kN > 0.0 ? model.units.force_to_kN : 1.0;
    std::string title = "Collapse under settlement — base reaction R = " +
                        significant5(*result.base_reaction / factor) + " " + model.units.force_name;
    if (result.initial_base_reaction)
      title += " (R₀ = " + significant5(*result.initial_base_reaction / factor) + " before settlement)";
    return title;
  }
  if (result.load_multiplier) return "Collapse mechanism — α = " + fixed(*result.load_multiplier, 4);
  return result.type == model::AnalysisType::Settlement ? "Collapse under settlement" : "Collapse mechanism";
}

std::string title_text(const model::Model& model, const AnalysisResult& result) {
  switch (result.verdict) {
    case Verdict::Collapse: return collapse_title(model, result) + certification_words(result);
    case Verdict::NoMechanism: return "No mechanism: α unbounded";
    case Verdict::CannotStand: return "Cannot stand under dead load — falling blocks highlighted";
    case Verdict::SolverFailure: return "No mechanism drawn: the conic solver failed";
    case Verdict::TimeLimit: return "No mechanism drawn: the time limit ran out";
    case Verdict::IterationLimit: return "No mechanism drawn: the iteration limit ran out";
    case Verdict::Cancelled: return "No mechanism drawn: the run was cancelled";
  }
  return "?";
}

std::string subtitle_text(const model::Model& model, const AnalysisResult& result, const SvgView& view) {
  std::string text;
  if (!model.title.empty()) {
    // Long CAD titles would run off the picture: keep the first 40 bytes, cut at a UTF-8
    // character boundary.
    std::string title = model.title;
    if (title.size() > 40) {
      std::size_t cut = 40;
      while (cut > 0 && (static_cast<unsigned char>(title[cut]) & 0xC0) == 0x80) --cut;
      title = title.substr(0, cut) + "…";
    }
    text += title + " · ";
  }
  text += std::string("friction ") + friction_words(result.friction_model) + " · cone " + cone_words(result) +
          " · formulation " + (result.planar ? std::string("planar") : std::string("3d")) + " · view along " +
          axis_name(view.view_axis);
  if (has_mechanism(result)) {
    std::size_t moving = 0;
    for (const BlockMotion& motion : result.mechanism.blocks) moving += motion.moving ? 1 : 0;
    text += " · " + std::to_string(moving) + (result.verdict == Verdict::CannotStand ? " falling" : " moving") +
            " of " + std::to_string(model.blocks.size()) + " blocks";
  }
  if (view.amplitude > 0.0) {
    text += " · displacements ×" + printf_string("%.3g", view.amplitude) + " (virtual)";
  } else {
    text += " · blocks undisplaced";
  }
  return text;
}

void append_legend(std::string& out, double width, double top) {
  const int per_row = std::max(1, static_cast<int>((width - 2 * kMargin) / kLegendItemWidth));
  struct Item {
    const char* colour;
    const char* label;
    bool swatch_is_block;
  };
  const Item items[kLegendItems] = {
      {kOpeningColour, "opening", false},        {kSlidingColour, "sliding", false},
      {kOpeningSlidingColour, "opening + sliding", false}, {kHingeColour, "hinge", false},
      {nullptr, "moving block", true},           {nullptr, "block at rest", true},
      {nullptr, "support", true}};
  const int block_rgb[3] = {kMovingRgb, kRestingRgb, kSupportRgb};
  out += "<g font-size=\"12\">\n";
  for (int i = 0; i < kLegendItems; ++i) {
    const double x = kMargin + (i % per_row) * kLegendItemWidth;
    const double y = top + 22.0 * (i / per_row);
    if (items[i].swatch_is_block) {
      out += "<rect x=\"" + coordinate(x) + "\" y=\"" + coordinate(y - 9) + "\" width=\"22\" height=\"12\" fill=\"" +
             rgb_hex(block_rgb[i - 4]) + "\" stroke=\"#333\" stroke-width=\"0.6\"/>";
    } else {
      out += "<line x1=\"" + coordinate(x) + "\" y1=\"" + coordinate(y - 3) + "\" x2=\"" + coordinate(x + 22) +
             "\" y2=\"" + coordinate(y - 3) + "\" stroke=\"" + items[i].colour + "\" stroke-width=\"4\"/>";
    }
    append_text(out, x + 28, y + 1, items[i].label, "");
  }
  out += "</g>\n";
}

void append_svg_open(std::string& out, double width, double height, const std::string& title) {
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + coordinate(width) + "\" height=\"" +
         coordinate(height) + "\" viewBox=\"0 0 " + coordinate(width) + " " + coordinate(height) +
         "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  out += "<title>" + escape(title) + "</title>\n";
  out += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
}

/// Undisplaced outlines under everything, as one path: a thin reference, not a second model.
void append_ghost_outlines(std::string& out, const model::Model& model, const SvgView& view) {
  if (!(view.amplitude > 0.0)) return;
  std::string d;
  for (const model::Block& block : model.blocks) {
    for (const std::vector<int>& face : block.faces) {
      if (!valid_face(face, block.vertices.size())) continue;
      const Vec3 normal = newell_normal(block.vertices, face);
      if (normal.dot(view.toward) <= 1e-9 * normal.norm()) continue;
      append_polygon_path(d, view, block.vertices, face);
    }
  }
  if (!d.empty()) {
    out += "<path fill=\"none\" stroke=\"" + std::string(kGhostColour) +
           "\" stroke-width=\"0.6\" stroke-linejoin=\"round\" d=\"" + d + "\"/>\n";
  }
}

struct FaceToDraw {
  double depth;
  std::size_t block;
  std::size_t face;
  double facing;  // cosine between the face normal and the direction to the viewer
};

/// The displaced blocks' faces that face the viewer, farthest first.
std::vector<FaceToDraw> front_faces_back_to_front(const model::Model& model, const Scene& scene) {
  const SvgView& view = scene.view;
  std::vector<FaceToDraw> faces;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const model::Block& block = model.blocks[b];
    const std::vector<Vec3>& vertices = scene.displaced[b];
    for (std::size_t f = 0; f < block.faces.size(); ++f) {
      const std::vector<int>& face = block.faces[f];
      if (!valid_face(face, vertices.size())) continue;
      const Vec3 normal = newell_normal(vertices, face);
      const double length = normal.norm();
      const double facing = normal.dot(view.toward);
      if (length == 0.0 || facing <= 1e-9 * length) continue;
      double depth = 0.0;
      for (int i : face) depth += view.toward.dot(vertices[static_cast<std::size_t>(i)]);
      faces.push_back({depth / static_cast<double>(face.size()), b, f, facing / length});
    }
  }
  std::stable_sort(faces.begin(), faces.end(),
                   [](const FaceToDraw& a, const FaceToDraw& b) { return a.depth < b.depth; });
  return faces;
}

/// Painter's algorithm over front faces only: with back faces culled, sorting by mean depth is
/// right for convex blocks that do not interpenetrate, which is what a rigid-block model is.
void append_blocks(std::string& out, const model::Model& model, const AnalysisResult& result, const Scene& scene) {
  out += "<g stroke=\"#333333\" stroke-width=\"0.6\" stroke-linejoin=\"round\">\n";
  for (const FaceToDraw& item : front_faces_back_to_front(model, scene)) {
    const model::Block& block = model.blocks[item.block];
    const BlockMotion* motion = motion_of(result, item.block);
    const int rgb = block.is_support() ? kSupportRgb : (motion && motion->moving ? kMovingRgb : kRestingRgb);
    out += "<path fill=\"" + shaded(rgb, 0.7 + 0.3 * item.facing) + "\" d=\"";
    append_polygon_path(out, scene.view, scene.displaced[item.block], block.faces[item.face]);
    out += "\"><title>" + escape(block.id) + "</title></path>\n";
  }
  out += "</g>\n";
}

/// Cracked interfaces on top so hinges show even where a block face would hide them; moved
/// with block_a, whose face they lie on.
void append_cracks(std::string& out, const model::Model& model, const AnalysisResult& result, const Scene& scene) {
  std::string cracks;
  for (int index : result.mechanism.cracked_interfaces) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.interfaces.size()) continue;
    if (static_cast<std::size_t>(index) >= result.mechanism.interfaces.size()) continue;
    const model::ContactInterface& contact = model.interfaces[static_cast<std::size_t>(index)];
    const InterfaceState state = result.mechanism.interfaces[static_cast<std::size_t>(index)].state;
    const char* colour = state_colour(state);
    if (!colour || contact.polygon.size() < 2) continue;
    RigidMotion motion;
    if (contact.block_a >= 0 && static_cast<std::size_t>(contact.block_a) < scene.motions.size()) {
      motion = scene.motions[static_cast<std::size_t>(contact.block_a)];
    }
    cracks += "<path stroke=\"" + std::string(colour) + "\" fill=\"" + colour + "\" d=\"";
    for (std::size_t i = 0; i < contact.polygon.size(); ++i) {
      cracks += i == 0 ? 'M' : 'L';
      append_point(cracks, scene.view, motion.apply(contact.polygon[i]));
    }
    cracks += "Z\"><title>" + escape(contact.id) + ": " + state_words(state) + "</title></path>\n";
  }
  if (!cracks.empty()) {
    out += "<g stroke-width=\"3\" fill-opacity=\"0.3\" stroke-linejoin=\"round\">\n" + cracks + "</g>\n";
  }
}

/// The displaced polygon of an interface, moved with block_a (as the cracks are).
std::vector<Vec3> displaced_polygon(const model::ContactInterface& contact, const Scene& scene) {
  RigidMotion motion;
  if (contact.block_a >= 0 && static_cast<std::size_t>(contact.block_a) < scene.motions.size()) {
    motion = scene.motions[static_cast<std::size_t>(contact.block_a)];
  }
  std::vector<Vec3> polygon;
  for (const Vec3& p : contact.polygon) polygon.push_back(motion.apply(p));
  return polygon;
}

/// "dα/dμ = 0.42" or "dR/dμ = -3.1 kN": the derivative in the model's units.
std::string derivative_words(const model::Model& model, const AnalysisResult& result, double value) {
  if (result.sensitivities->quantity == analysis::SensitivityOf::BaseReaction) {
    const double factor = model.units.force_to_kN > 0.0 ? model.units.force_to_kN : 1.0;
    return "dR/dμ = " + printf_string("%.4g", value / factor) + " " + model.units.force_name;
  }
  return "dα/dμ = " + printf_string("%.4g", value);
}

/// The most influential joints: a dashed outline and a numbered marker on each, and the numbers
/// with their ids and derivatives listed under the drawing.
void append_influential_joints(std::string& out, const model::Model& model, const AnalysisResult& result,
                               const Scene& scene) {
  const std::vector<std::pair<int, double>> joints = influential_joints(model, result);
  if (joints.empty()) return;
  std::string marks;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const model::ContactInterface& contact = model.interfaces[static_cast<std::size_t>(joints[i].first)];
    const std::vector<Vec3> polygon = displaced_polygon(contact, scene);
    if (polygon.empty()) continue;
    marks += "<path d=\"";
    Vec3 centre = Vec3::Zero();
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      marks += k == 0 ? 'M' : 'L';
      append_point(marks, scene.view, polygon[k]);
      centre += polygon[k] / static_cast<double>(polygon.size());
    }
    marks += "Z\"><title>" + escape(contact.id) + ": " + derivative_words(model, result, joints[i].second) +
             "</title></path>\n";
    const Eigen::Vector2d c = scene.view.to_page(centre);
    marks += "<circle cx=\"" + coordinate(c.x()) + "\" cy=\"" + coordinate(c.y()) + "\" r=\"8\" fill=\"" +
             kInfluenceColour + "\" stroke=\"none\"/>";
    append_text(marks, c.x(), c.y() + 4, std::to_string(i + 1),
                "text-anchor=\"middle\" font-size=\"11\" fill=\"#ffffff\" stroke=\"none\"");
  }
  out += "<g stroke=\"" + std::string(kInfluenceColour) +
         "\" fill=\"none\" stroke-width=\"1.5\" stroke-dasharray=\"5 3\">\n" + marks + "</g>\n";
  double y = scene.view.height - footer_height(joints.size()) + kFooterLine;
  append_text(out, kMargin, y, "Most influential joints (friction, from the sensitivities):",
              "font-size=\"13\" font-weight=\"bold\"");
  for (std::size_t i = 0; i < joints.size(); ++i) {
    y += kFooterLine;
    const std::string& id = model.interfaces[static_cast<std::size_t>(joints[i].first)].id;
    append_text(out, kMargin, y, std::to_string(i + 1) + "  " + id + ": " + derivative_words(model, result, joints[i].second),
                "font-size=\"12\"");
  }
}

}  // namespace

SvgView mechanism_view(const model::Model& model, const AnalysisResult& result, const SvgOptions& options) {
  return build_scene(model, result, options).view;
}

std::string mechanism_svg(const model::Model& model, const AnalysisResult& result, const SvgOptions& options) {
  const Scene scene = build_scene(model, result, options);
  const SvgView& view = scene.view;
  const std::string title = title_text(model, result);

  std::string out;
  out.reserve(4096 + model.blocks.size() * 400);
  append_svg_open(out, view.width, view.height, title);
  if (!result.verdict_text.empty()) out += "<desc>" + escape(result.verdict_text) + "</desc>\n";
  append_text(out, kMargin, 32, title, "font-size=\"20\" font-weight=\"bold\"");
  append_text(out, kMargin, 56, subtitle_text(model, result, view), "font-size=\"13\" fill=\"#444\"");
  append_legend(out, view.width, 84);
  append_ghost_outlines(out, model, view);
  append_blocks(out, model, result, scene);
  append_cracks(out, model, result, scene);
  append_influential_joints(out, model, result, scene);
  out += "</svg>\n";
  return out;
}

// ---------------------------------------------------------------------------------------------
// Convergence picture

namespace {

struct PlotArea {
  double left, top, right, bottom;
  double width() const { return right - left; }
  double height() const { return bottom - top; }
};

struct Range {
  double lo, hi;
  double map(double v, double a, double b) const { return a + (v - lo) / (hi - lo) * (b - a); }
};

// Ticks at 1, 2 or 5 times a power of ten, about `count` of them, with the range widened to them.
std::vector<double> nice_ticks(Range& range, int count) {
  double span = range.hi - range.lo;
  // A span within rounding of the values (a converged sequence: 36 kN, then 36 kN plus one ulp)
  // is drawn as a flat line: ticks finer than the values' spacing cannot be stepped through.
  if (!(span > 1e-9 * std::max(std::abs(range.lo), std::abs(range.hi)))) {
    const double pad = range.lo != 0.0 ? 0.1 * std::abs(range.lo) : 1.0;
    range.lo -= pad;
    range.hi += pad;
    span = range.hi - range.lo;
  }
  const double raw = span / std::max(1, count);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double step = (fraction <= 1.0 ? 1.0 : fraction <= 2.0 ? 2.0 : fraction <= 5.0 ? 5.0 : 10.0) * power;
  range.lo = std::floor(range.lo / step + 1e-9) * step;
  range.hi = std::ceil(range.hi / step - 1e-9) * step;
  std::vector<double> ticks;
  const double steps = (range.hi - range.lo) / step;  // about `count`; not finite only for absurd ranges
  if (!(std::isfinite(steps) && steps < 1000.0)) return {range.lo, range.hi};
  const long num_steps = std::lround(steps);
  for (long k = 0; k <= num_steps; ++k) {
    const double t = range.lo + static_cast<double>(k) * step;
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

std::string tick_label(double value) { return printf_string("%.6g", value); }

// "10⁻⁸": superscripts read as powers of ten in every browser font without markup.
std::string power_of_ten_label(int exponent) {
  static const char* digits[10] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string label = "10";
  if (exponent < 0) label += "⁻";
  const std::string number = std::to_string(std::abs(exponent));
  for (char c : number) label += digits[c - '0'];
  return label;
}

void append_frame(std::string& out, const PlotArea& area) {
  out += "<rect x=\"" + coordinate(area.left) + "\" y=\"" + coordinate(area.top) + "\" width=\"" +
         coordinate(area.width()) + "\" height=\"" + coordinate(area.height()) +
         "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";
}

void append_x_ticks(std::string& out, const PlotArea& area, Range& range, const std::vector<double>& ticks) {
  for (double t : ticks) {
    const double x = range.map(t, area.left, area.right);
    out += "<line x1=\"" + coordinate(x) + "\" y1=\"" + coordinate(area.bottom) + "\" x2=\"" + coordinate(x) +
           "\" y2=\"" + coordinate(area.bottom + 5) + "\" stroke=\"#333333\"/>\n";
    append_text(out, x, area.bottom + 18, tick_label(t), "font-size=\"11\" text-anchor=\"middle\"");
  }
}

void append_horizontal_grid(std::string& out, const PlotArea& area, double y, const std::string& label) {
  out += "<line x1=\"" + coordinate(area.left) + "\" y1=\"" + coordinate(y) + "\" x2=\"" + coordinate(area.right) +
         "\" y2=\"" + coordinate(y) + "\" stroke=\"#e4e4e4\"/>\n";
  out += "<line x1=\"" + coordinate(area.left - 5) + "\" y1=\"" + coordinate(y) + "\" x2=\"" +
         coordinate(area.left) + "\" y2=\"" + coordinate(y) + "\" stroke=\"#333333\"/>\n";
  append_text(out, area.left - 8, y + 4, label, "font-size=\"11\" text-anchor=\"end\"");
}

void append_axis_labels(std::string& out, const PlotArea& area, const std::string& x_label,
                        const std::string& y_label) {
  append_text(out, 0.5 * (area.left + area.right), area.bottom + 38, x_label,
              "font-size=\"12\" text-anchor=\"middle\"");
  const double x = area.left - 58, y = 0.5 * (area.top + area.bottom);
  append_text(out, x, y, y_label,
              "font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 " + coordinate(x) + " " +
                  coordinate(y) + ")\"");
}

void append_note(std::string& out, const PlotArea& area, const std::string& note) {
  append_text(out, 0.5 * (area.left + area.right), 0.5 * (area.top + area.bottom), note,
              "font-size=\"14\" fill=\"#666666\" text-anchor=\"middle\"");
}

void append_non_associative_panel(std::string& out, const AnalysisResult& result, const PlotArea& area) {
  const bool settlement = result.type == model::AnalysisType::Settlement;
  std::string heading = "Non-associative iterations";
  if (!result.non_associative.empty()) {
    heading += result.non_associative_converged ? " (converged)" : " (not converged)";
  }
  append_text(out, area.left, area.top - 12, heading, "font-size=\"14\" font-weight=\"bold\"");
  append_frame(out, area);
  if (result.non_associative.empty()) {
    std::string note = result.friction_model == model::FrictionModel::Associative
                           ? "associative: one conic solve"
                           : "no non-associative iterations recorded";
    append_note(out, area, note);
    if (result.load_multiplier) {
      append_text(out, 0.5 * (area.left + area.right), 0.5 * (area.top + area.bottom) + 22,
                  "α = " + fixed(*result.load_multiplier, 4), "font-size=\"13\" fill=\"#666666\" text-anchor=\"middle\"");
    } else if (result.base_reaction) {
      append_text(out, 0.5 * (area.left + area.right), 0.5 * (area.top + area.bottom) + 22,
                  "R = " + significant5(*result.base_reaction) + " kN",
                  "font-size=\"13\" fill=\"#666666\" text-anchor=\"middle\"");
    }
    return;
  }
  std::vector<std::pair<double, double>> points;
  for (const analysis::NonAssociativeStep& step : result.non_associative) {
    if (std::isfinite(step.value)) points.emplace_back(step.iteration, step.value);
  }
  if (points.empty()) {
    append_note(out, area, "no finite values to plot");
    return;
  }
  Range xs{points.front().first, points.front().first}, ys{points.front().second, points.front().second};
  for (const auto& [x, y] : points) {
    xs.lo = std::min(xs.lo, x);
    xs.hi = std::max(xs.hi, x);
    ys.lo = std::min(ys.lo, y);
    ys.hi = std::max(ys.hi, y);
  }
  const std::vector<double> x_ticks = nice_ticks(xs, std::min(8, std::max(1, static_cast<int>(points.size()) - 1)));
  const std::vector<double> y_ticks = nice_ticks(ys, 5);
  for (double t : y_ticks) append_horizontal_grid(out, area, ys.map(t, area.bottom, area.top), tick_label(t));
  append_x_ticks(out, area, xs, x_ticks);
  append_axis_labels(out, area, "iteration", settlement ? "base reaction R (kN)" : "load multiplier α");

  std::string polyline = "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.8\" points=\"";
  std::string markers = "<g fill=\"#1f77b4\">\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = xs.map(points[i].first, area.left, area.right);
    const double y = ys.map(points[i].second, area.bottom, area.top);
    if (i) polyline += ' ';
    polyline += coordinate(x) + "," + coordinate(y);
    markers += "<circle cx=\"" + coordinate(x) + "\" cy=\"" + coordinate(y) + "\" r=\"3.5\"><title>" +
               std::to_string(result.non_associative[i].iteration) + ": " + printf_string("%.6g", points[i].second) +
               "</title></circle>\n";
  }
  out += polyline + "\"/>\n" + markers + "</g>\n";
}

/// One curve of the interior-point panel: a column of the iteration log.
struct IterationSeries {
  const char* name;
  const char* colour;
  double conic::IterationRow::*field;
};
const IterationSeries kIterationSeries[3] = {{"relative gap", "#1f77b4", &conic::IterationRow::gap_rel},
                                             {"primal residual", "#d62728", &conic::IterationRow::res_primal},
                                             {"dual residual", "#2ca02c", &conic::IterationRow::res_dual}};

/// log10 of a value, with what cannot be drawn on a log axis (<= 1e-16, including 0) at the
/// floor; false for NaN or +inf, which are left out.
bool log_value(double v, double& out_log) {
  constexpr double kFloor = 1e-16;
  if (std::isnan(v) || v == std::numeric_limits<double>::infinity()) return false;
  out_log = std::log10(std::max(v, kFloor));
  return true;
}

/// Decades from below the lowest to above the highest log value, at most about 8 gridlines:
/// the range of the log axis and the step between its labelled decades.
Range decade_range(double log_lo, double log_hi, int& decade_step) {
  int decade_lo = static_cast<int>(std::floor(log_lo + 1e-9));
  int decade_hi = static_cast<int>(std::ceil(log_hi - 1e-9));
  if (decade_hi <= decade_lo) decade_hi = decade_lo + 1;
  decade_step = std::max(1, (decade_hi - decade_lo + 7) / 8);
  decade_lo = static_cast<int>(std::floor(static_cast<double>(decade_lo) / decade_step)) * decade_step;
  decade_hi = static_cast<int>(std::ceil(static_cast<double>(decade_hi) / decade_step)) * decade_step;
  return Range{static_cast<double>(decade_lo), static_cast<double>(decade_hi)};
}

void append_iteration_curves(std::string& out, const std::vector<conic::IterationRow>& history, const PlotArea& area,
                             const Range& xs, const Range& ys) {
  for (const IterationSeries& s : kIterationSeries) {
    std::string points;
    for (const conic::IterationRow& row : history) {
      double l;
      if (!log_value(row.*(s.field), l)) continue;
      if (!points.empty()) points += ' ';
      points += coordinate(xs.map(row.iteration, area.left, area.right)) + "," +
                coordinate(ys.map(l, area.bottom, area.top));
    }
    out += "<polyline fill=\"none\" stroke=\"" + std::string(s.colour) + "\" stroke-width=\"1.8\" points=\"" + points +
           "\"><title>" + s.name + "</title></polyline>\n";
  }
}

/// Legend in the top right corner, where residuals have usually fallen away from.
void append_iteration_legend(std::string& out, const PlotArea& area) {
  out += "<g font-size=\"12\">\n";
  out += "<rect x=\"" + coordinate(area.right - 150) + "\" y=\"" + coordinate(area.top + 6) +
         "\" width=\"144\" height=\"62\" fill=\"#ffffff\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>\n";
  for (int i = 0; i < 3; ++i) {
    const double y = area.top + 22 + 18 * i;
    out += "<line x1=\"" + coordinate(area.right - 142) + "\" y1=\"" + coordinate(y - 4) + "\" x2=\"" +
           coordinate(area.right - 120) + "\" y2=\"" + coordinate(y - 4) + "\" stroke=\"" + kIterationSeries[i].colour +
           "\" stroke-width=\"2\"/>\n";
    append_text(out, area.right - 114, y, kIterationSeries[i].name, "");
  }
  out += "</g>\n";
}

void append_interior_point_panel(std::string& out, const AnalysisResult& result, const PlotArea& area) {
  append_text(out, area.left, area.top - 12, "Interior-point iterations (last conic solve)",
              "font-size=\"14\" font-weight=\"bold\"");
  append_frame(out, area);
  const auto& history = result.interior_point_history;
  if (history.empty()) {
    append_note(out, area, "no interior-point iterations recorded");
    return;
  }
  Range xs{static_cast<double>(history.front().iteration), static_cast<double>(history.front().iteration)};
  double log_lo = std::numeric_limits<double>::infinity(), log_hi = -log_lo;
  for (const conic::IterationRow& row : history) {
    xs.lo = std::min(xs.lo, static_cast<double>(row.iteration));
    xs.hi = std::max(xs.hi, static_cast<double>(row.iteration));
    for (const IterationSeries& s : kIterationSeries) {
      double l;
      if (log_value(row.*(s.field), l)) {
        log_lo = std::min(log_lo, l);
        log_hi = std::max(log_hi, l);
      }
    }
  }
  if (!(log_lo <= log_hi)) {
    append_note(out, area, "no finite values to plot");
    return;
  }
  int decade_step = 1;
  const Range ys = decade_range(log_lo, log_hi, decade_step);
  for (int d = static_cast<int>(ys.lo); d <= static_cast<int>(ys.hi); d += decade_step) {
    append_horizontal_grid(out, area, ys.map(d, area.bottom, area.top), power_of_ten_label(d));
  }
  const std::vector<double> x_ticks = nice_ticks(xs, std::min(8, std::max(1, static_cast<int>(history.size()) - 1)));
  append_x_ticks(out, area, xs, x_ticks);
  append_axis_labels(out, area, "interior-point iteration", "relative gap, residuals (log scale)");
  append_iteration_curves(out, history, area, xs, ys);
  append_iteration_legend(out, area);
}

}  // namespace

std::string convergence_svg(const AnalysisResult& result) {
  constexpr double kWidth = 1000.0, kHeight = 420.0;
  const std::string title = std::string("Convergence — ") + verdict_words(result.verdict);
  // The history may be all a caller filled in; row 0 is the starting point, not an iteration.
  const int interior_point_iterations = result.interior_point_history.empty()
                                            ? result.solver_info.iterations
                                            : std::max(result.solver_info.iterations,
                                                       result.interior_point_history.back().iteration);
  std::string out;
  append_svg_open(out, kWidth, kHeight, title);
  append_text(out, kMargin, 30, title, "font-size=\"18\" font-weight=\"bold\"");
  std::string subtitle = std::string("friction ") + friction_words(result.friction_model) + " · cone " +
                         cone_words(result) + " · " + std::to_string(interior_point_iterations) +
                         " interior-point iterations in the last solve";
  append_text(out, kMargin, 50, subtitle, "font-size=\"12\" fill=\"#444444\"");
  const PlotArea left{95, 90, 480, kHeight - 60}, right{595, 90, 980, kHeight - 60};
  append_non_associative_panel(out, result, left);
  append_interior_point_panel(out, result, right);
  out += "</svg>\n";
  return out;
}

}  // namespace rbla::io
