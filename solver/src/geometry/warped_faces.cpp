#include "geometry/warped_faces.hpp"

#include "geometry/interface_detection.hpp"

#include <sstream>

namespace rbla::geometry {

namespace {

void warn_group(const std::vector<WarpedFace>& group, const std::string& what, model::Model& m) {
  if (group.empty()) return;
  const WarpedFace* worst = &group.front();
  for (const WarpedFace& w : group) {
    if (w.deviation > worst->deviation) worst = &w;
  }
  std::ostringstream message;
  message.precision(2);
  message << group.size() << (group.size() == 1 ? " face is" : " faces are") << " not planar, by up to "
          << model::length_text(worst->deviation, m.units) << " (" << 100.0 * worst->deviation / worst->size
          << " % of its size; block '" << m.blocks[worst->block].id << "', face " << worst->face << "); " << what;
  m.warnings.push_back({"non_planar_face", message.str(),
                        "/blocks/" + std::to_string(worst->block) + "/faces/" + std::to_string(worst->face),
                        worst->deviation});
}

}  // namespace

void warn_warped_faces(const std::vector<WarpedFace>& warped, model::Model& m) {
  const DetectionTolerances tol = DetectionTolerances::of(m);
  std::vector<WarpedFace> within, beyond;
  for (const WarpedFace& w : warped) (w.deviation <= tol.distance(w.size, w.size) ? within : beyond).push_back(w);
  warn_group(within, "within the joint tolerance: detection uses their fitted planes", m);
  warn_group(beyond, "more than the joint tolerance: contacts on them are approximate", m);
}

}  // namespace rbla::geometry
