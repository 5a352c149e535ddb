// The 3-D model's landings: which base points touch the floor (the closing contact set), the impact
// law over them (physics/impact_3d.hpp: plastic, sticking, solved over the whole set), and the mode
// the body continues in. One routine for every landing: the base coming back flat from an edge or
// a vertex, a neighbour vertex touching down while the base is tilted.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/frictional_impact.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {

void Rocking3DModel::record_impact(double tau, double energy_before) {
  if (report_.impacts == 0) report_.first_impact_time = t_ + tau;
  ++report_.impacts;
  ++outcome_.impacts;
  const double after = kinetic_energy();
  if (energy_before > 0.0)
    outcome3_.max_impact_energy_ratio = std::max(outcome3_.max_impact_energy_ratio, after / energy_before);
}

// At rest on hull face `face` in pose `rotation` (item frame) with hull vertex `vertex` at `point` on
// the floor: the footprint from the pose (the face lies flat, the vertex keeps its place).
void Rocking3DModel::capture_rest(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point, int face) {
  place_flat(rotation, vertex, point, face);
  go_to_rest();
  landing_reason_ = Transition3D::RestCapture;
  report_.rest_capture = true;
  ++outcome_.rest_captures;
  if (face != 0) ++outcome3_.rests_off_base;
}

// Flat on hull face `face`: the footprint (yaw, shift) from the pose, the vertex keeping its place.
void Rocking3DModel::place_flat(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point, int face) {
  set_face(face);
  const Eigen::Matrix3d rf = face == 0 ? rotation : Eigen::Matrix3d(rotation * fc().rotation.transpose());
  yaw_ = std::atan2(rf(1, 0), rf(0, 0));
  const Eigen::Vector3d placed = face == 0 ? Eigen::Vector3d(yaw_matrix() * hv(vertex).position)
                                           : Eigen::Vector3d(yaw_matrix() * (fc().rotation * hv(vertex).position + fc().offset));
  shift_ = Eigen::Vector2d(point.x() - placed.x(), point.y() - placed.y());
}

// The landing leaves the body flat on `face` with the horizontal velocity u of its centre of mass and
// the spin (friction at the landing could not stop them): SLIDE from here (REST if nothing moves).
void Rocking3DModel::slide_after_landing(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point,
                                         int face, const Eigen::Vector2d& u, double spin, double tau) {
  place_flat(rotation, vertex, point, face);
  if (u.squaredNorm() == 0.0 && spin == 0.0) {
    go_to_rest();
    return;
  }
  mode_ = Mode3D::Slide;
  contact_ = -1;
  theta_ = omega_ = 0.0;
  slide_ << u.x(), u.y(), spin, shift_.x(), shift_.y(), yaw_;
  slide_stepper_.reset(sample_dt_);
  ++outcome3_.landing_slides;
  landing_reason_ = Transition3D::LandingSlides;
  if (std::isnan(outcome3_.first_slip_time)) outcome3_.first_slip_time = t_ + tau;
  lip_held_ = -1;
  if (!body_.parameters().support_lips.empty()) {  // (it slides on against a lip it moves into)
    const int k = lip_touched(u);
    if (k >= 0) hold_on_lip(k);
  }
}

// A landing from flight on one corner that friction could not stop: the body pivots on that corner with
// the frictional impact's angular velocity, the corner slipping on with its velocity after the impact.
void Rocking3DModel::slip_after_landing(const LandingScene& sc) {
  const FrictionalLanding& f = sc.friction;
  const Eigen::Vector3d& p = sc.set.point[0];
  enter_vertex(sc.hull_index[0], p, sc.r, f.omega);
  const Eigen::Vector3d u = point_velocity(f.omega, f.velocity, sc.body->centre, p);
  ys_ << y_, p.x(), p.y(), u.x(), u.y();
  slip_dir_ = u.head<2>().normalized();
  pivot_slipping_ = true;
  slip_stepper_.invalidate();
  ++outcome3_.corner_slip_landings;
  landing_reason_ = Transition3D::LandingCornerSlips;
}

// Friction decides the landing (issue 51 part 3) where the sticking law needs more than mu_s or has
// no solution: the frictional plastic impact (physics/frictional_impact.hpp), solved by
// solve_friction() where its answer can change what follows.
bool Rocking3DModel::friction_decides(const Landing& law, double demand) const {
  const double mu_s = body_.parameters().mu_s;
  return std::isfinite(mu_s) && (law.violation > 0.0 || demand > mu_s);
}

bool Rocking3DModel::keeps_loaded_pivot(const LandingScene& sc) const {
  const Landing& law = *sc.law;
  const int pivot[2] = {law.first, law.second};
  const int count = law.mode == LandingMode::Vertex ? 1 : law.mode == LandingMode::Edge ? 2 : 0;
  return count > 0 && law.violation == 0.0 && keeps_pivot(*sc.body, sc.set, pivot, count);
}

// Solves the frictional impact of the scene; its answer is followed where it converged.
void Rocking3DModel::solve_friction(LandingScene& sc) {
  // (tried first on the contacts the sticking answer loads: most landings keep them, and the whole
  // set's redundant contacts converge slowly)
  const Landing& law = *sc.law;
  const int first[2] = {law.first, law.second};
  const int first_count = law.mode == LandingMode::Vertex ? 1 : law.mode == LandingMode::Edge ? 2 : 0;
  sc.friction = frictional_landing(*sc.body, sc.set, ImpactFriction{body_.parameters().mu_s, mu_k()}, first, first_count);
  sc.solved = true;
  sc.frictional = sc.friction.converged;
  if (!sc.friction.converged) ++outcome3_.unresolved_landings;
}

// Angle of hull face `face` from the floor in pose `rotation` (item frame), rad.
double Rocking3DModel::face_tilt(const Eigen::Matrix3d& rotation, int face) const {
  const Eigen::Vector3d down = rotation * (hull().faces[static_cast<std::size_t>(face)].rotation.transpose() * -Eigen::Vector3d::UnitZ());
  return std::acos(std::clamp(-down.z(), -1.0, 1.0));
}

// The energy below which a landing puts the body at rest: that of rest_capture_ratio * p * alpha about
// the vertex (for a planar motion exactly the planar engine's rule on omega), J/kg.
double Rocking3DModel::capture_energy(const BaseVertex& v) const {
  const double r = settings_.rest_capture_ratio;
  return 0.5 * r * r * kGravity * v.radius * v.alpha * v.alpha;
}

// The pose at a landing and the angular velocity before (the centre's: centre_velocity()); EDGE: the
// face that comes flat (else null). `touching` as for land().
const std::vector<int>* Rocking3DModel::landing_pose(int touching, Eigen::Matrix3d& r, Eigen::Vector3d& t,
                                                     Eigen::Vector3d& omega) {
  if (mode_ == Mode3D::Flight) {
    flight_pose(r, t);
    omega = yf_.segment<3>(4);
    ++outcome3_.flight_landings;
    return nullptr;
  }
  if (mode_ != Mode3D::Edge) {
    r = vertex_rotation(y_);
    t = pivot_world_ - r * hv(contact_).position;
    omega = y_.tail<3>();
    ++outcome3_.vertex_impacts;
    return nullptr;
  }
  // Back to flat: the pose is the footprint exactly (theta = 0 is the event), every face vertex on
  // the floor. Onto the face across: the pose at the event. (The event is located on theta to the
  // integrator's tolerance: the pose is put exactly there.)
  const bool flat_edge = touching == -1;
  const int across = fc().across[static_cast<std::size_t>(contact_)];
  theta_ = flat_edge ? 0.0 : fc().fold[static_cast<std::size_t>(contact_)];
  r = rotation();
  t = translation();
  omega = angular_velocity();
  ++outcome3_.flat_impacts;
  return flat_edge ? &fc().hull_vertex : &hull().faces[static_cast<std::size_t>(across)].hull_vertex;
}

// The closing contact set: every hull point on the floor at this instant, to floor_tol_ (far below
// any physical scale, above the dense output's error in the pose at the event), in the order whose
// consecutive points are the contact polygon's edges; hull_index[k]: contact k's hull vertex.
void Rocking3DModel::closing_contacts(int touching, const Eigen::Matrix3d& r, const Eigen::Vector3d& t,
                                      const std::vector<int>* landing_face, LandingContacts& set, int* hull_index) const {
  set.count = 0;
  const int nh = static_cast<int>(hull().vertices.size());
  for (int i = 0; i < nh; ++i) {
    Eigen::Vector3d p = r * hv(i).position + t;
    const bool on = landing_face ? std::find(landing_face->begin(), landing_face->end(), i) != landing_face->end()
                                 : std::abs(p.z()) <= floor_tol_ || i == touching || i == contact_;
    if (!on) continue;
    p.z() = 0.0;
    set.point[set.count] = p;
    set.vertex[set.count] = i;
    hull_index[set.count] = i;
    ++set.count;
  }
  if (!hull().from_hull) {
    set.base_vertex_count = body_.vertex_count();  // the base's own order (edge k joins k and k + 1)
    return;
  }
  // Hull points in counter-clockwise order about their centre on the floor: consecutive ones are the
  // contact polygon's edges (a hull edge or face on the floor).
  Eigen::Vector3d mid = Eigen::Vector3d::Zero();
  for (int k = 0; k < set.count; ++k) mid += set.point[k] / set.count;
  auto angle = [&](int k) { return std::atan2(set.point[k].y() - mid.y(), set.point[k].x() - mid.x()); };
  for (int k = 1; k < set.count; ++k)  // insertion sort: a few points, no allocation
    for (int m = k; m > 0 && angle(m) < angle(m - 1); --m) {
      std::swap(set.point[m], set.point[m - 1]);
      std::swap(hull_index[m], hull_index[m - 1]);
    }
  for (int k = 0; k < set.count; ++k) set.vertex[k] = k;
  set.base_vertex_count = set.count;
}

// The Zeno rule of a see-saw on a tilted edge: pivoting on its two ends in turn, the body loses a
// fixed fraction of the wobble across the edge at each landing, infinitely often in finite time,
// converging to rocking about the edge. Once the wobble's energy is below the rest capture's energy
// (rest_capture_ratio * p * alpha, as for rest), it rocks about the edge (chosen, w updated).
// So too where the end the law lets go leaves the floor too slowly to rise by the contact tolerance
// under gravity (v^2 < 2 g floor_tol_): a hop no touchdown search resolves, which landed again at
// the same instant, without an impulse, until the events bound put the body down flat (a spin about
// the vertical, which the landings on the edge's ends do not take, kept the wobble's energy up).
void Rocking3DModel::see_saw_rule(const LandingBody& lb, const LandingContacts& set, const int* hull_index,
                                  double kappa, Landing& chosen, Eigen::Vector3d& w) {
  const int n = set.base_vertex_count;
  if (chosen.mode != LandingMode::Vertex || set.count != 2 ||
      !((set.vertex[0] + 1) % n == set.vertex[1] || (set.vertex[1] + 1) % n == set.vertex[0]))
    return;
  const int a = (set.vertex[0] + 1) % n == set.vertex[1] ? 0 : 1;
  const Eigen::Vector3d& pa = set.point[a];
  const Eigen::Vector3d w_edge = rotation_about_line(lb, pa, (set.point[1 - a] - pa).normalized());
  const Eigen::Matrix3d j = inertia_about(lb.central_inertia, lb.centre, pa);
  const int other = 1 - chosen.first;  // the end the law lets go (the pivot sticks: it turns about it)
  const double leaves = chosen.omega.cross(set.point[other] - set.point[chosen.first]).z();
  const bool grazing = leaves * leaves < 2.0 * kGravity * floor_tol_;
  if (grazing || kappa * kappa * (chosen.energy_after - rotation_energy(j, w_edge)) <
                     capture_energy(hv(hull_index[chosen.first]))) {
    chosen.mode = LandingMode::Edge;
    chosen.first = a;
    chosen.second = 1 - a;
    w = kappa * w_edge;
    ++outcome3_.edge_captures;
  }
}

// `touching`: the hull vertex whose touchdown was located (VERTEX); EDGE: -1 back flat on the face,
// -2 the face across the edge comes flat (a hull).
void Rocking3DModel::land(int touching, double tau) {
  const double before = kinetic_energy();
  landing_reason_ = Transition3D::Landing;
  const bool flat_edge = mode_ == Mode3D::Edge && touching == -1;
  const int face_before = face_;
  Eigen::Matrix3d r;
  Eigen::Vector3d t, omega;
  const std::vector<int>* landing_face = landing_pose(touching, r, t, omega);
  // One per thread, not per item: 3.6 KB that only a landing uses (no allocation per sample).
  static thread_local LandingContacts set;
  static thread_local int hull_index[LandingContacts::kMax];
  static_assert(LandingContacts::kMax == kMaxBaseVertices, "a contact for every hull vertex");
  closing_contacts(touching, r, t, landing_face, set, hull_index);
  LandingBody lb;
  lb.central_inertia = r * body_.central_inertia_per_mass() * r.transpose();
  lb.centre = r * body_.centre_of_mass() + t;
  lb.omega = omega;
  lb.velocity = centre_velocity();
  pivot_slipping_ = false;
  const Landing law = plastic_landing(lb, set);
  outcome3_.max_landing_violation = std::max(outcome3_.max_landing_violation, law.violation);
  double demand = 0.0;
  if (law.normal_impulse > 0.0) {
    demand = law.tangential_impulse / law.normal_impulse;
    outcome3_.max_friction_demand = std::max(outcome3_.max_friction_demand, demand);
    // (mu_s = +inf when the item does not give it: never counted)
    if (demand > body_.parameters().mu_s) ++outcome3_.slipping_landings;
  }
  LandingScene scene{r, set, hull_index, hull().from_hull ? hull().face_down(r) : 0, flat_edge, face_before, tau, &law, &lb};
  scene.needs_friction = friction_decides(law, demand);
  if (scene.needs_friction) ++outcome3_.frictional_landings;
  // Only three or more contacts can keep the base on the floor: the answer is needed now there; on a
  // corner or an edge only where the landing ends in a rest capture (continue_after_landing).
  // A pivot that both ends of the friction range keep, the rest of the base leaving (the sticking
  // answer and the frictionless one), is taken as a slipping pivot: not solved (the sticking answer
  // is followed there anyway; rocking_benchmarks and monitor_benchmarks: the solve would cost 20 us).
  // Where the sticking law stops the body (a rest capture's landing) the capture's rule decides.
  // Onto one corner (only from flight: pivoting, the pivot is in the set too) the frictional impact is
  // that corner's (Routh's): solved, and where the corner slips on it is followed slide-rocking (the
  // planar contact model's corner impact from flight).
  const bool one_corner = set.count == 1;
  if (scene.needs_friction && ((set.count >= 3 && law.mode != LandingMode::Rest && !keeps_loaded_pivot(scene)) || one_corner))
    solve_friction(scene);
  if (one_corner && scene.frictional && scene.friction.stay == 1 && scene.friction.slipping == 1) {
    slip_after_landing(scene);
  } else if (scene.frictional && scene.friction.stay >= 3) {
    // The base stays on the floor: friction could not stop it; it slides on (exactly).
    slide_after_landing(r, hull_index[0], set.point[0], scene.down, scene.friction.velocity.head<2>(),
                        scene.friction.omega.z(), tau);
  } else {
    const double kappa = body_.restitution_factor();
    Eigen::Vector3d w = kappa * law.omega;
    Landing chosen = law;
    see_saw_rule(lb, set, hull_index, kappa, chosen, w);
    continue_after_landing(scene, chosen, w, kappa);
  }
  if (hull().from_hull && (mode_ == Mode3D::Rest || mode_ == Mode3D::Edge || mode_ == Mode3D::Slide) && face_ != face_before)
    ++outcome3_.hull_landings;
  record_impact(tau, before);
}

// The mode after a landing whose contacts stick (issue 40's law, restitution and the Zeno rules).
// Where friction decided the landing and its pivot slips (slide-rock in 3-D, not modelled), the
// sticking answer is followed and counted; a rest capture there keeps the slip (the planar rule).
void Rocking3DModel::continue_after_landing(LandingScene& sc, const Landing& chosen, const Eigen::Vector3d& w,
                                            double kappa) {
  const Eigen::Matrix3d& r = sc.r;
  const LandingContacts& set = sc.set;
  // The planar engine's rest capture (its Zeno rule) needs an almost flat face.
  const bool near_flat = set.count >= 3 ||
                         face_tilt(r, sc.down) < settings_.rest_capture_ratio *
                                                     hull().faces[static_cast<std::size_t>(sc.down)].body->min_alpha();
  // (on a face the centre of mass overhangs, the shaking may hold the body: REST there lifts off
  // again as soon as the acceleration lets it, rocking_3d_edge.cpp)
  // A rest capture collapses the rest of a Zeno sequence of landings. Where friction cannot stop the
  // base at once it slides on: with the frictional answer's slip where that was solved, else by the
  // flat landing's rule (the planar contact model's): the normal impulse stops the fall, friction
  // takes up to mu_s of it, else mu_k of it off the slip (the rotation is what the capture drops).
  auto rest = [&](int k) {
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    double spin = 0.0;
    if (sc.frictional && sc.friction.slipping > 0) {
      u = sc.friction.velocity.head<2>();
      spin = sc.friction.omega.z();
    } else if (sc.needs_friction && !sc.solved) {
      const Eigen::Vector2d v = sc.body->velocity.head<2>();
      const double pn = std::max(-sc.body->velocity.z(), 0.0), speed = v.norm();
      if (speed > body_.parameters().mu_s * pn) u = v * (1.0 - std::min(1.0, mu_k() * pn / speed));
    }
    if (u.squaredNorm() > 0.0 || spin != 0.0) slide_after_landing(r, sc.hull_index[k], set.point[k], sc.down, u, spin, sc.tau);
    else capture_rest(r, sc.hull_index[k], set.point[k], sc.down);
  };
  // An edge: the face it is rocked on and its index there (without a hull: base edge k joins base
  // vertices k and k + 1).
  int face = 0, edge = chosen.mode == LandingMode::Edge ? sc.hull_index[chosen.first] : -1;
  const bool on_hull_edge = chosen.mode != LandingMode::Edge || !hull().from_hull ||
                            hull().face_with_edge(sc.hull_index[chosen.first], sc.hull_index[chosen.second], r, face, edge);
  if (chosen.mode == LandingMode::Rest || kappa <= 0.0) {
    rest(0);
  } else if (!on_hull_edge) {
    // Two floor points joined by no hull edge (a face's diagonal within the floor tolerance): the
    // body turns about their line, which no face's edge mode carries; it pivots on the first point
    // with that angular velocity, and the second point's touchdown is the next landing.
    enter_vertex(sc.hull_index[chosen.first], set.point[chosen.first], r, w);
  } else if (chosen.mode == LandingMode::Edge) {
    const int u = sc.hull_index[chosen.first];
    const HullFace& hf = hull().faces[static_cast<std::size_t>(face)];
    const BaseEdge& e = hf.body->edge(edge);
    const Eigen::Matrix3d rf = face == 0 ? r : Eigen::Matrix3d(r * hf.rotation.transpose());
    const double w_axis = w.dot(rf * e.axis);
    const int pivot = hf.hull_vertex[static_cast<std::size_t>(e.a)] == u ? chosen.first : chosen.second;
    // almost no energy left: w below rest_capture_ratio * p * alpha of the edge
    if (!(w_axis > 0.0) || (w_axis < settings_.rest_capture_ratio * e.pivot.p * e.pivot.alpha && near_flat)) {
      rest(chosen.first);
    } else if (sc.flat_edge && face == sc.face_before) {
      mode_ = Mode3D::Edge;
      contact_ = edge;
      theta_ = 0.0;
      omega_ = w_axis;
      dopri5_.invalidate();
    } else {
      enter_edge_from_pose(face, edge, r, set.point[pivot], e.a, w_axis);
    }
  } else {
    const int vertex = sc.hull_index[chosen.first];
    const BaseVertex& v = hv(vertex);
    if (rotation_energy(r * v.inertia * r.transpose(), w) < capture_energy(v) && near_flat) {
      rest(chosen.first);
    } else {
      enter_vertex(vertex, set.point[chosen.first], r, w);
    }
  }
  // (unsolved on a corner or an edge: the sticking answer needs more than mu_s there, so a contact
  // of the real answer slips)
  if (sc.needs_friction && (mode_ == Mode3D::Edge || mode_ == Mode3D::Vertex) &&
      (!sc.solved || (sc.frictional && (sc.friction.slipping > 0 || sc.friction.stay == 0)))) {
    ++outcome3_.pivot_slip_landings;
    landing_reason_ = Transition3D::LandingPivotSlips;
  }
}

}  // namespace rocking_monitor::core
