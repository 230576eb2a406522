#include "scheduler/vps/vps_hybrid.h"

#include <algorithm>
#include <string>

#include "scheduler/vps/face_labels.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

struct FrameContext {
  const HybridModel* model;
  HybridState* state;
};

// Counts the contact under its face pair (both on one face: what recognition reads) and
// adds it to the region of the first engaged constraint it belongs to: its voxel on the
// constraint's face of part 1 and its point on the constraint's face of part 2, or one
// of them on an edge (the rim of a face in contact lies on an edge: a peg's bottom rim
// inside the wall's voxels is the constraint's contact, not a collision to render); with
// HybridRegion::face, every contact with its voxel on the constraint's face of part 1 or
// its point on the constraint's face of part 2 (a peg's side point in the wall's interior
// voxels, a bottom point in the wall's surface voxels).
void on_contact(void* context, std::size_t voxel, std::size_t point, const Eigen::Vector3d& force,
                const Eigen::Vector3d& torque) {
  auto& c = *static_cast<FrameContext*>(context);
  const std::int16_t f1 = c.model->voxel_face[voxel], f2 = c.model->point_face[point];
  if (f1 >= 0 && f2 >= 0) ++c.state->pair_contacts[static_cast<std::size_t>(f1) * c.model->faces2.size() + f2];
  for (int k = 0; k < kMaxConstraints; ++k) {
    const ActiveConstraint& a = c.state->active[k];
    if (a.kind == ConstraintKind::none) continue;
    const bool in_region = c.model->params.region == HybridRegion::face
                               ? f1 == a.face1 || f2 == a.face2
                               : (f1 == a.face1 && (f2 == a.face2 || f2 == kEdge)) || (f1 == kEdge && f2 == a.face2);
    if (in_region) {
      c.state->region[k].force += force;
      c.state->region[k].torque += torque;
      return;  // one constraint per contact: its force is blended out once
    }
  }
}

}  // namespace

HybridModel hybrid_model(VpsModel vps, std::vector<AnalyticFace> faces1, std::vector<AnalyticFace> faces2,
                         const CouplingParams& coupling, HybridParams params) {
  if (!(params.alignment_fraction > 0 && params.alignment_fraction < 1))
    throw Error(
        "vps_hybrid: the alignment fraction must lie in (0, 1): the user stays stronger than the constraint (got " +
        std::to_string(params.alignment_fraction) + ")");
  if (!(params.x_release > 0 && params.x_release < params.x_engage && params.x_engage <= 1))
    throw Error("vps_hybrid: the engagement thresholds must satisfy 0 < release < engage <= 1 (got release " +
                std::to_string(params.x_release) + ", engage " + std::to_string(params.x_engage) + ")");
  if (!(params.rotation_fraction > 0 && params.rotation_fraction < 1))
    throw Error(
        "vps_hybrid: the rotation fraction must lie in (0, 1): the user stays stronger than the constraint (got " +
        std::to_string(params.rotation_fraction) + ")");
  if (!(params.x_full > 0 && params.x_full <= 1))
    throw Error("vps_hybrid: x_full must lie in (0, 1] (got " + std::to_string(params.x_full) + ")");
  if (!(params.ramp_s >= 0))
    throw Error("vps_hybrid: the ramp time must be >= 0 (got " + std::to_string(params.ramp_s) + ")");
  const double s = vps.voxmap.voxel_size;
  RecognitionTolerance& t = params.tolerance;
  if (!(t.radius > 0)) t.radius = 2 * s;
  if (!(t.offset > 0)) t.offset = 2 * s;
  if (!(t.angle > 0)) t.angle = 0.2;
  HybridModel m;
  m.voxel_face = label_voxmap(vps.voxmap, faces1);
  m.point_face = label_point_shell(vps.shell, faces2);
  m.vps = std::move(vps);
  m.faces1 = std::move(faces1);
  m.faces2 = std::move(faces2);
  m.params = params;
  m.k_a_n_per_m = params.alignment_fraction * coupling.stiffness;
  m.k_r_nm_per_rad = params.rotation_fraction * coupling.rot_stiffness;
  return m;
}

HybridParams hybrid_params_for(const Scene& scene) {
  constexpr double kPi = 3.14159265358979323846;
  const VpsHybridParams& h = scene.vps.hybrid;
  HybridParams p;
  p.alignment_fraction = h.alignment_fraction;
  p.rotation_fraction = h.rotation_fraction;
  p.x_engage = h.x_engage;
  p.x_release = h.x_release;
  p.x_full = h.x_full;
  p.ramp_s = h.ramp_s;
  p.region = h.region;
  if (h.radius_tolerance) p.tolerance.radius = *h.radius_tolerance;
  if (h.offset_tolerance) p.tolerance.offset = *h.offset_tolerance;
  if (h.angle_tolerance_deg) p.tolerance.angle = *h.angle_tolerance_deg * kPi / 180;
  return p;
}

HybridState hybrid_state_for(const HybridModel& model) {
  HybridState s;
  s.pair_contacts.assign(model.faces1.size() * model.faces2.size(), 0);
  return s;
}

HybridResult hybrid_wrench(const HybridModel& model, HybridState& state, const BodyState& part) {
  const HybridParams& p = model.params;
  const double s = model.vps.voxmap.voxel_size;
  const double u = model.vps.metres_per_unit;
  const double step = p.ramp_s > 0 ? model.vps.period_s / p.ramp_s : 1.0;
  std::fill(state.pair_contacts.begin(), state.pair_contacts.end(), 0u);
  for (QueryWrench& w : state.region) w = QueryWrench{};

  // First pass (seed 002 5.4): all collisions, with each contact's faces.
  FrameContext context{&model, &state};
  const VpsContactSink sink{&context, &on_contact};
  HybridResult out;
  out.vps = vps_wrench(model.vps, part, &sink);
  out.collision.force = out.vps.query.force;
  out.collision.torque = out.vps.query.torque;

  // Engaged constraints: their engagement now, hysteresis, ramps; blend (eq. 13, 14, 19).
  for (int k = 0; k < kMaxConstraints; ++k) {
    ActiveConstraint& a = state.active[k];
    if (a.kind == ConstraintKind::none) continue;
    const AnalyticFace& f1 = model.faces1[a.face1];
    const AnalyticFace& f2 = model.faces2[a.face2];
    const ConstraintOffset o = constraint_offset(a.kind, f1, f2, part.pose);
    a.x = engagement(o, s);
    const bool apart = a.kind == ConstraintKind::concentric && o.depth <= 0;
    a.releasing = a.x < p.x_release || apart ? true : (a.x >= p.x_engage ? false : a.releasing);
    a.phase = std::clamp(a.phase + (a.releasing ? -step : step), 0.0, 1.0);
    if (a.releasing && a.phase <= 0) {
      a = ActiveConstraint{};
      continue;
    }
    const double w = a.phase * std::min(1.0, a.x / p.x_full);
    const QueryWrench align = alignment_wrench(o, part.pose, model.k_a_n_per_m, model.k_r_nm_per_rad, u);
    out.vps.query.force += w * (align.force - state.region[k].force);
    out.vps.query.torque += w * (align.torque - state.region[k].torque);
    if (w > 0) ++out.engaged;
    if (w > out.x) {
      out.x = w;
      out.kind = a.kind;
    }
  }

  // Recognition (seed 002 5.3): the face pairs in contact this frame that form a
  // constraint not yet engaged; it engages at phase 0 and ramps in from the next frame.
  const std::size_t n2 = model.faces2.size();
  for (std::size_t pair = 0; pair < state.pair_contacts.size(); ++pair) {
    if (state.pair_contacts[pair] == 0) continue;
    const auto f1 = static_cast<std::int16_t>(pair / n2), f2 = static_cast<std::int16_t>(pair % n2);
    bool known = false;
    for (const ActiveConstraint& a : state.active)
      known |= a.kind != ConstraintKind::none && a.face1 == f1 && a.face2 == f2;
    if (known) continue;
    const ConstraintKind kind = recognise(model.faces1[f1], model.faces2[f2], part.pose, p.tolerance);
    if (kind == ConstraintKind::none) continue;
    const double x = engagement(constraint_offset(kind, model.faces1[f1], model.faces2[f2], part.pose), s);
    if (x < p.x_engage) continue;
    for (ActiveConstraint& a : state.active)
      if (a.kind == ConstraintKind::none) {
        a = ActiveConstraint{kind, f1, f2, x, 0.0, false};
        break;
      }
  }
  return out;
}

WrenchEvaluator hybrid_evaluator(const HybridModel& model, HybridState& state) {
  WrenchEvaluator e;
  e.evaluate = [&model](const Pose& pose) {
    BodyState s;
    s.pose = pose;
    return vps_wrench(model.vps, s).query;
  };
  e.evaluate_state = [&model, &state](const BodyState& s) {
    const HybridResult r = hybrid_wrench(model, state, s);
    QueryResult q = r.vps.query;
    q.constraint = static_cast<std::uint8_t>(r.kind);
    q.constraint_weight = r.x;
    return q;
  };
  e.set_modes = [](std::size_t) {};
  return e;
}

}  // namespace snapfit
