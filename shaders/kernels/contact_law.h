// EDEM's Hertz-Mindlin (no-slip) contact law with its options and extensions, stateless (LAMMPS
// style), written once for the three places it runs: GLSL, the CPU twin's scalar kernel and the
// twin's SIMD lanes (kernels_ref/contact_lanes.cpp). docs/engineering.md has the formulas and the
// dialect ("The contact law, written once"), in short:
//   real, real3, cond  a float, a 3-vector and a bool per contact (in lanes: one per lane);
//                      `bool` and `uint` (the flags) are the same for every contact of a batch
//   + - * /, unary -, comparisons, && || !, sqrt, abs, min, max, dot3, cross3, length3, scale3
//   pick(c, yes, no)   selection per contact: every branch on a real is a pick, never an `if`
//                      (an `if` on a cond does not compile in the lanes)
// Conventions:
//   n        unit normal from j to i (the force on i along +n is repulsive)
//   overlap  > 0 in contact
//   v_rel    velocity of i's surface relative to j's at the contact point
//   ri, rj   distances from the body centres to the contact point (rj = 0 for a wall)
// No include guard: the lanes include it again inside their own struct; all.h includes it once.

struct ContactOut {
  real3 force_i;   // on i; j receives -force_i
  real3 torque_i;
  real3 torque_j;
  real normal_force;  // signed scalar normal force (negative = attractive)
  real grip_force;    // what friction, rolling and spinning resistance scale with (kFlagCohesionContactFriction)
  real3 n_x_ft;       // n x Ft: the tangential force's moment per unit lever arm
  real roll_arm;      // mu_r |Fn| when a rolling torque applies, else -1
  real normal_stiffness;  // Hertz secant stiffness Fn_elastic / overlap = 4/3 E* sqrt(R* dn)
};

// Where two surfaces touch, as the contact kernel measured it (contacts.h, the lanes).
struct ContactGeometry {
  real3 n;            // unit normal from j to i
  real overlap;       // > 0
  real radius_star;   // R* (a wall: R_i)
  real mass_star;     // m* of the two bodies (a wall: m_i)
  real ri;            // i's centre to the contact point (the tangential force's moment arm)
  real rj;            // j's (0 for a wall)
  real lever_i;       // the EDEM rolling torque's levers (body_torque)
  real lever_j;
  real cohesion_lens; // kFlagCohesionIntersection: the sphere surfaces' intersection area / pi
};

// One sphere of a pair as the contact kernel loads it.
struct SphereState {
  real3 x;        // centre
  real radius;
  real3 v;        // velocity
  real inv_mass;  // 1 / its body's mass (0: fixed)
  real3 w;        // angular velocity
};

// A spin with its components of at most kSpinFloor (rad/s) left out, for a rolling torque's
// direction w / |w|: the torque's share along a small component shrinks that component step after
// step once a roll has stopped, which would walk it into the denormals that a GPU without
// DenormPreserve flushes (the large heap's grains on its mat, about the vertical, on an H200).
real3 spin_above_floor(real3 w) {
  return real3(pick(abs(w.x) > kSpinFloor, w.x, real(0.0f)), pick(abs(w.y) > kSpinFloor, w.y, real(0.0f)),
               pick(abs(w.z) > kSpinFloor, w.z, real(0.0f)));
}

// Torque on one body of a contact: the tangential force's moment about its sphere's centre (r
// from that centre to the contact point), plus EDEM's standard rolling torque mu_r |Fn| x lever
// against the body's own spin when roll_arm >= 0 (lw = |w|, passed in so a gather computes it once
// per body; the spin's components below kSpinFloor get none). The lever is r for a sphere; for a clump, |contact point - centre of mass| (EDEM) or
// r (rolling_lever = "sphere"; centre_of_mass_lever()). The lean gather calls it again on stored
// (n x Ft, mu_r |Fn|), so stored and recomputed torques are the same bits.
real3 body_torque(real3 n_x_ft, real r, real roll_arm, real lever, real3 w, real lw) {
  precise real3 t = scale3(n_x_ft, -r);
  precise real k = div_rn(-(roll_arm * lever), lw);
  precise real3 rolled = t + scale3(spin_above_floor(w), k);
  return pick(roll_arm >= 0.0f && lw > 0.0f, rolled, t);
}

// The contact point: i's surface point along -n (ri = its radius less half the overlap).
real3 contact_point(real3 xi, real3 n, real ri) {
  precise real3 cp = xi - scale3(n, ri);
  return cp;
}

// Whether a rolling torque's lever must be measured from a clump's centre of mass: EDEM's
// constant torque against each body's own spin (the relative torque of LIGGGHTS uses R*).
bool centre_lever(uint flags) {
  uint need = kFlagRollingConstTorque | kFlagBodies;
  uint never = kFlagRollingRelativeOmega | kFlagRollingLeverSphere;
  return (flags & need) == need && (flags & never) == 0u;
}

// The rolling lever of a body at contact point cp (centre_lever()): the distance from cp to its
// centre of mass when it has more than one sphere, else r (its sphere's centre to cp, so a lone
// sphere keeps its bytes).
real centre_of_mass_lever(real3 cp, real3 centre, real r, cond lone) {
  precise real3 d = cp - centre;
  precise real lever = length3(d);
  return pick(lone, r, lever);
}

// LIGGGHTS cdt (rolling_model_cdt.h) rolling torque on i (j receives minus it), exactly as
// LIGGGHTS writes it: mu_r Fn_el lever w / |w| with w = w_i - w_j (a wall's spin is not
// counted), then its component along n removed (the torque has no twist part, but |w| keeps
// the twist spin). roll_arm = mu_r Fn_el, the elastic normal force kn dn; lever = R* for two
// spheres, r_i - dn/2 for a wall. False (and tr zero) when the two spins are equal; the relative
// spin's components below kSpinFloor get no torque (spin_above_floor()).
cond relative_rolling(real3 w_i, real3 w_j, real roll_arm, real lever, real3 n, OUT(real3) tr) {
  precise real3 w = w_i - w_j;
  precise real lw = length3(w);
  precise real k = div_rn(-(roll_arm * lever), lw);
  precise real3 t = scale3(spin_above_floor(w), k);
  precise real3 rolled = t - scale3(n, dot3(t, n));
  cond rolls = lw > 0.0f;
  tr = pick(rolls, rolled, real3(0.0f));
  return rolls;
}

// Extension restitution_velocity (docs/diagnosis.md): the viscoelastic damping of Brilliantov et
// al. / Kuwabara-Kono, F = -A Sn vn with A a material time (s), added to EDEM's damping. Its
// damping grows with the overlap faster than EDEM's, so restitution falls with impact speed
// (1 - e ~ v^(1/5)). Returns 0 when off, leaving EDEM's bytes unchanged.
real viscoelastic_damping(real time_a, real sn, real vn) {
  precise real f = (time_a * sn) * vn;
  return pick(time_a > 0.0f, f, 0.0f);
}

// Extension cohesion: EDEM's linear cohesion F = k A on the Hertz contact area A = pi R* dn,
// attractive; pi_k = pi k with k the cohesion energy density (J/m^3). With lens >= 0 the area is
// pi lens instead (LIGGGHTS sjkr, cohesion_intersection_area()). 0 when off.
real linear_cohesion(real pi_k, real radius_star, real overlap, real lens) {
  precise real f_lens = pi_k * lens;
  precise real f_hertz = (pi_k * radius_star) * overlap;
  return pick(pi_k > 0.0f, pick(lens >= 0.0f, f_lens, f_hertz), 0.0f);
}

// LIGGGHTS sjkr's cohesion area over pi (cohesion_model_sjkr.h): the disc where the two sphere
// surfaces intersect, a^2 = -(d-r1-r2)(d+r1-r2)(d-r1+r2)(d+r1+r2) / (4 d^2) at centre distance
// d = r1 + r2 - dn, written with r1 + r2 - d = dn; against a wall r^2 - (r - dn)^2 = dn (2r - dn).
// About 2 R* dn for small overlaps: twice EDEM's Hertz area R* dn.
real cohesion_intersection_area(real r1, real r2, real dist, real overlap, bool wall) {
  if (wall) {
    precise real a_wall = overlap * (2.0f * r1 - overlap);
    return a_wall;
  }
  precise real q = ((overlap * ((dist + r1) - r2)) * ((dist - r1) + r2)) * ((dist + r1) + r2);
  precise real a = div_rn(q, (4.0f * dist) * dist);
  return a;
}

// The area cohesion pulls on, over pi, when it is LIGGGHTS sjkr's intersection disc; -1 (EDEM's
// Hertz area R* dn, in linear_cohesion()) otherwise.
real cohesion_lens(uint flags, real r1, real r2, real dist, real overlap, bool wall) {
  if ((flags & kFlagCohesionIntersection) == 0u) return real(-1.0f);
  return cohesion_intersection_area(r1, r2, dist, overlap, wall);
}

// Spheres i and j: where they touch and how fast (ContactGeometry, v_rel), whether they do
// (overlap and distance positive; otherwise g and v_rel hold no contact). The levers are the
// spheres' own; the kernel measures a clump's from its centre of mass (centre_of_mass_lever()).
cond touching_spheres(SphereState i, SphereState j, uint flags, OUT(ContactGeometry) g, OUT(real3) v_rel) {
  precise real3 d = i.x - j.x;
  precise real dist = length3(d);
  precise real overlap = i.radius + j.radius - dist;
  precise real3 n = real3(div_rn(d.x, dist), div_rn(d.y, dist), div_rn(d.z, dist));
  precise real radius_star = div_rn(i.radius * j.radius, i.radius + j.radius);
  precise real mass_star = div_rn(1.0f, i.inv_mass + j.inv_mass);
  precise real ri = i.radius - 0.5f * overlap;
  precise real rj = j.radius - 0.5f * overlap;
  precise real3 spin = scale3(i.w, ri) + scale3(j.w, rj);
  precise real3 surface_velocity = (i.v - j.v) - cross3(spin, n);
  v_rel = surface_velocity;
  g.n = n;
  g.overlap = overlap;
  g.radius_star = radius_star;
  g.mass_star = mass_star;
  g.ri = ri;
  g.rj = rj;
  g.lever_i = ri;
  g.lever_j = rj;
  g.cohesion_lens = cohesion_lens(flags, i.radius, j.radius, dist, overlap, false);
  return overlap > 0.0f && dist > 0.0f;
}

// A sphere (centre x, radius r) against the plane through `point` with unit normal `normal`
// (walls.h, a plane wall): its overlap, and whether its centre lies within r + margin of the
// plane on either side.
cond plane_contact(real3 x, real r, real3 point, real3 normal, float margin, OUT(real) overlap) {
  precise real3 rel = x - point;
  precise real dist = dot3(rel, normal);
  overlap = r - dist;
  return dist < r + margin && dist > -r - margin;
}

// A sphere (centre x, radius r) against a cylinder's inner surface (walls.h): base centre `base`,
// unit `axis`, `radius`, `height` along the axis from the base. Its overlap and unit normal (from
// the surface towards the axis), and whether its centre lies along the cylinder (margin beyond
// either end while margin > 0) and off the axis within radius + margin of it, and it is within
// margin of touching. Outside the surface (d >= R) a sphere never touches it.
cond cylinder_contact(real3 x, real r, real3 base, real3 axis, real radius, real height, float margin,
                      OUT(real3) n, OUT(real) overlap) {
  precise real3 rel = x - base;
  precise real s = dot3(rel, axis);
  precise real3 q = rel - scale3(axis, s);
  precise real d = length3(q);
  precise real inv_d = div_rn(-1.0f, d);
  n = scale3(q, inv_d);
  overlap = r + d - radius;
  cond along = !(s < -margin || s > height + margin);
  cond inside = d > 0.0f && d < radius + margin;  // a candidate may move inside
  cond beyond_ends = margin == 0.0f && (s < 0.0f || s > height);
  return along && inside && !beyond_ends && overlap > -margin;
}

// Sphere i against a wall that it touches at unit normal n (from the wall towards i) with this
// overlap, as touching_spheres() gives a pair: R* = R_i, m* = m_i, rj = 0. The wall's surface
// moves at vel + omega x (p - centre), its prescribed motion (WallState).
void wall_geometry(SphereState i, real3 n, real overlap, real3 vel, real3 omega, real3 centre, uint flags,
                   OUT(ContactGeometry) g, OUT(real3) v_rel) {
  precise real ri = i.radius - 0.5f * overlap;
  precise real mass_star = div_rn(1.0f, i.inv_mass);
  precise real3 arm = contact_point(i.x, n, ri) - centre;
  precise real3 v_wall = vel + cross3(omega, arm);
  precise real3 surface_velocity = (i.v - v_wall) - cross3(scale3(i.w, ri), n);
  v_rel = surface_velocity;
  g.n = n;
  g.overlap = overlap;
  g.radius_star = i.radius;
  g.mass_star = mass_star;
  g.ri = ri;
  g.rj = 0.0f;
  g.lever_i = ri;
  g.lever_j = 0.0f;
  g.cohesion_lens = cohesion_lens(flags, i.radius, 0.0f, 0.0f, overlap, true);
}

// A stored spring (tangential or rolling) turned into the current tangent plane, its length kept.
real3 turn_into_tangent_plane(real3 s, real3 n) {
  precise real old_sq = dot3(s, s);
  precise real3 p = s - scale3(n, dot3(s, n));
  precise real new_sq = dot3(p, p);
  precise real keep = sqrt_rn(div_rn(old_sq, new_sq));
  precise real3 kept = scale3(p, keep);
  return pick(new_sq > 0.0f, kept, p);
}

// EDEM's type C rolling resistance (elastic-plastic spring-dashpot, Ai et al. 2011 model C; the
// EPSD of LIGGGHTS): a rolling spring torque, built from the relative rolling rotation (twist
// about n excluded) with stiffness k_r = 2.25 k_n (mu_r R*)^2, capped at mu_r R* |Fn| (full
// mobilisation), plus a dashpot of eta_r times critical damping, 2 sqrt(I_r k_r), while the
// spring is below the cap (fully mobilised, the spring slips at the cap undamped: Ai et al.'s
// f = 0). `spring` is the contact's stored torque, turned into the current tangent plane with
// its length kept (as the tangential spring). Returns the torque on i (j receives minus it).
real3 epsd_rolling_torque(real3 n, real3 w_i, real3 w_j, real radius_star, real normal_force,
                          real normal_stiffness, real mu_r, real inertia_r, float eta_r, float dt,
                          INOUT(real3) spring) {
  precise real3 w = w_i - w_j;
  precise real3 w_roll = w - scale3(n, dot3(w, n));
  precise real3 m = turn_into_tangent_plane(spring, n);
  precise real arm = mu_r * radius_star;
  precise real k_r = (2.25f * normal_stiffness) * (arm * arm);
  precise real k_r_dt = -(k_r * dt);
  m = m + scale3(w_roll, k_r_dt);
  precise real m_max = arm * abs(normal_force);
  precise real len = length3(m);
  precise real ratio = div_rn(m_max, len);
  precise real3 capped = scale3(m, ratio);
  precise real c_r = -((2.0f * eta_r) * sqrt_rn(inertia_r * k_r));
  precise real3 damped = m + scale3(w_roll, c_r);
  cond slips = len > m_max;
  spring = pick(slips, capped, m);
  return pick(slips, capped, damped);
}

// Spinning (twisting) friction, as in Chrono's SMC contact: a torque about the contact normal
// against the relative spin s = (w_i - w_j) . n, of magnitude mu_spin R* |Fn|. It is limited so
// that it never reverses the spin within a step: over one step the kick changes a spin by
// dt T / I (integrate.h), so the torque is at most |s| / (2 dt D), with D = sum over the two
// bodies of (its touching contacts) x (1 / its moment of inertia about n) (the caller's
// `stop_share`, 0 for a wall). Each of a body's contacts then takes at most half its share of
// the stopping torque, so even all of them together cannot turn the spin over. Returns the
// torque on i (j receives minus it); zero without spin, and below kSpinFloor: the limiter's
// halving would otherwise reach denormals, which a GPU without DenormPreserve reads as zero.
real3 spinning_friction_torque(real3 n, real3 w_i, real3 w_j, real mu_spin, real radius_star,
                               real normal_force, real stop_share, float dt) {
  precise real3 w = w_i - w_j;
  precise real s = dot3(w, n);
  precise real t_cap = (mu_spin * radius_star) * abs(normal_force);
  precise real t_stop = div_rn(abs(s), (2.0f * dt) * stop_share);
  precise real t = min(t_cap, t_stop);
  precise real k = pick(s > 0.0f, -t, t);
  return pick(abs(s) > kSpinFloor, scale3(n, k), real3(0.0f));
}

// The torques of a full contact entry (the lean gather derives the same from the stored entry):
// the tangential force's moment about each sphere's centre, and the rolling torque, EDEM's
// against each body's own spin (lever lever_i, lever_j) or LIGGGHTS cdt's against the relative
// spin (relative_rolling()).
void contact_torques(ContactGeometry g, real3 w_i, real3 w_j, cond j_is_wall, uint flags, INOUT(ContactOut) o) {
  bool relative = (flags & kFlagRollingRelativeOmega) != 0u;
  real arm = o.roll_arm;
  real own_arm = relative ? real(-1.0f) : arm;
  real arm_j = pick(j_is_wall, real(-1.0f), own_arm);
  precise real lw_i = pick(own_arm >= 0.0f, length3(w_i), 0.0f);
  precise real lw_j = pick(arm_j >= 0.0f, length3(w_j), 0.0f);
  o.torque_i = body_torque(o.n_x_ft, g.ri, own_arm, g.lever_i, w_i, lw_i);
  o.torque_j = body_torque(o.n_x_ft, g.rj, arm_j, g.lever_j, w_j, lw_j);
  if (!relative) return;
  real lever = pick(j_is_wall, g.ri, g.radius_star);
  real3 tr;
  cond rolls = relative_rolling(w_i, w_j, arm, lever, g.n, tr) && arm >= 0.0f;
  precise real3 rolled_i = o.torque_i + tr;
  precise real3 rolled_j = o.torque_j - tr;
  o.torque_i = pick(rolls, rolled_i, o.torque_i);
  o.torque_j = pick(rolls && !j_is_wall, rolled_j, o.torque_j);
}

// The tangential force: the stored spring turned into the tangent plane and stretched by v_t dt,
// with its damper, capped at ft_max: on spring and damper together, the spring then keeping the
// capped force (EDEM, DEM-Engine), or with kFlagCoulombSpringOnly on the spring alone, damping
// dropped while sliding (LIGGGHTS). Updates the spring; returns Ft.
real3 tangential_force(real3 v_t, real3 n, real st, real gamma_t, real ft_max, float dt, uint flags,
                       INOUT(real3) shear) {
  precise real3 spring = turn_into_tangent_plane(shear, n) + scale3(v_t, dt);
  precise real3 f_spring = scale3(spring, -st);
  precise real3 f_damp = scale3(v_t, -gamma_t);
  precise real3 ft = f_spring + f_damp;
  if ((flags & kFlagCoulombSpringOnly) != 0u) {
    precise real fs = length3(f_spring);
    cond slips = fs > ft_max;
    precise real ratio = div_rn(ft_max, fs);
    precise real3 capped = scale3(spring, ratio);
    precise real3 capped_force = scale3(capped, -st);
    shear = pick(slips, capped, spring);
    return pick(slips, capped_force, ft);
  }
  precise real f = length3(ft);
  cond slips = f > ft_max;
  precise real ratio = div_rn(ft_max, f);
  precise real3 capped = scale3(ft, ratio);
  precise real inv_st = div_rn(-1.0f, st);
  precise real3 capped_spring = scale3(capped, inv_st);
  shear = pick(slips, capped_spring, spring);
  return pick(slips, capped, ft);
}

ContactOut hertz_mindlin(ContactGeometry g, real3 v_rel, real3 w_i, real3 w_j, cond j_is_wall, PairParams pp,
                         float dt, uint flags, INOUT(real3) shear) {
  ContactOut o;
  real3 n = g.n;
  precise real sqrt_rd = sqrt_rn(g.radius_star * g.overlap);
  precise real sn = 2.0f * pp.e_star * sqrt_rd;
  precise real st = 8.0f * pp.g_star * sqrt_rd;
  // Fn = 4/3 E* sqrt(R*) dn^(3/2), written as dn * sqrt(R* dn)
  precise real fn_elastic = div_rn(4.0f * pp.e_star * sqrt_rd * g.overlap, 3.0f);
  // pp.damping = -2 sqrt(5/6) beta >= 0
  precise real gamma_n = pp.damping * sqrt_rn(sn * g.mass_star);
  // The tangential dashpot, unless the pair has it off (LIGGGHTS's `tangential_damping off`).
  precise real dashpot_t = pp.damping * sqrt_rn(st * g.mass_star);
  precise real gamma_t = pick(pp.tangential_damping > 0.0f, dashpot_t, 0.0f);

  precise real vn = dot3(v_rel, n);
  precise real3 v_t = v_rel - scale3(n, vn);

  precise real fn = fn_elastic - gamma_n * vn;
  fn = fn - viscoelastic_damping(pp.viscoelastic_time, sn, vn);
  if ((flags & kFlagClipAttraction) != 0u) fn = max(fn, 0.0f);
  // What friction and the rolling lever see: the net force, or the repulsion before cohesion.
  precise real fn_grip = fn;
  fn = fn - linear_cohesion(pp.cohesion_pi_k, g.radius_star, g.overlap, g.cohesion_lens);
  if ((flags & kFlagCohesionContactFriction) == 0u) fn_grip = fn;

  precise real ft_max = pp.static_friction * abs(fn_grip);
  precise real3 ft = tangential_force(v_t, n, st, gamma_t, ft_max, dt, flags, shear);

  o.n_x_ft = cross3(n, ft);
  o.force_i = scale3(n, fn) + ft;
  o.normal_force = fn;
  o.grip_force = fn_grip;
  cond rolling = (flags & kFlagRollingConstTorque) != 0u && pp.rolling_friction > 0.0f;
  // EDEM scales the rolling torque with |Fn|; LIGGGHTS cdt with the elastic force kn dn.
  bool relative = (flags & kFlagRollingRelativeOmega) != 0u;
  precise real roll_force = relative ? fn_elastic : abs(fn_grip);
  o.roll_arm = pick(rolling, pp.rolling_friction * roll_force, -1.0f);
  o.normal_stiffness = div_rn(4.0f * pp.e_star * sqrt_rd, 3.0f);
  o.torque_i = real3(0.0f);
  o.torque_j = real3(0.0f);
  if ((flags & kFlagLeanContacts) == 0u) contact_torques(g, w_i, w_j, j_is_wall, flags, o);
  return o;
}
