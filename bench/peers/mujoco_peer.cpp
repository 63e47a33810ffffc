// MuJoCo driver of bench/peers/peers.py: the peer scenes on MuJoCo's C API (Debian's
// libmujoco-dev), in the cam lift's frame (bench/peers/peer_models.py explains it): the cam
// contact is a fixed plane under the first body, the cam's motion a known applied force.
//
//   mujoco_peer two_mass H T_END OMEGA M1 M2 KS CS KV CV PRELOAD TIMECONST DAMPRATIO TABLE OUT
//   mujoco_peer case_a   H T_END OMEGA M K DELTA0 TIMECONST DAMPRATIO TABLE OUT
//
// TABLE: rows θ, L(θ), dL/dθ, d²L/dθ² (uniform θ over one revolution, from camdyn cam).
// OUT: CSV t,q1,q2,v1,v2,f1,f2 every step (f: normal contact force of the cam / seat pair).
// Prints "cpu=<s> steps=<n>" (CPU of the stepping loop only). Exit 2 on bad input.
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct LiftTable {
  std::vector<double> th, x, dx, d2x;
  double omega = 0;
  bool load(const char* path) {
    std::ifstream f(path);
    std::string line;
    while (std::getline(f, line)) {
      std::stringstream s(line);
      double a, b, c, d;
      char k;
      if (s >> a >> k >> b >> k >> c >> k >> d) {
        th.push_back(a);
        x.push_back(b);
        dx.push_back(c);
        d2x.push_back(d);
      }
    }
    return th.size() > 2;
  }
  // L, L̇, L̈ at t: cubic Hermite on (L, dL/dθ), linear on d²L/dθ² (as peer_models.Lift).
  void at(double t, double& L, double& dL, double& d2L) const {
    const double two_pi = 2.0 * M_PI;
    double a = std::fmod(omega * t, two_pi);
    const double d = th[1] - th[0];
    const std::size_t n = th.size() - 1;
    std::size_t i = std::size_t(a / d);
    if (i >= n) i = n - 1;
    const double s = (a - th[i]) / d;
    const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
    const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
    L = h00 * x[i] + h10 * dx[i] * d + h01 * x[i + 1] + h11 * dx[i + 1] * d;
    dL = omega * (dx[i] + s * (dx[i + 1] - dx[i]));
    d2L = omega * omega * (d2x[i] + s * (d2x[i + 1] - d2x[i]));
  }
};

std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

int usage(const char* why) {
  std::fprintf(stderr, "mujoco_peer: %s\n", why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage("first argument: two_mass or case_a");
  const std::string scene = argv[1];
  const bool two = scene == "two_mass";
  if (!two && scene != "case_a") return usage("first argument: two_mass or case_a");
  if (argc != (two ? 16 : 12)) return usage("wrong number of arguments (see the file's head)");
  std::vector<double> a;
  for (int i = 2; i < argc - 2; ++i) {
    char* end = nullptr;
    a.push_back(std::strtod(argv[i], &end));
    if (*end != '\0' || !std::isfinite(a.back())) return usage("a numeric argument is not a number");
  }
  const double h = a[0], t_end = a[1];
  LiftTable lift;
  lift.omega = a[2];
  if (!lift.load(argv[argc - 2])) return usage("lift table unreadable or too short");
  const double m1 = a[3];
  double m2 = 0, ks = 0, cs = 0, kv = 0, cv = 0, preload = 0, k = 0, delta0 = 0, tc = 0, zeta = 0;
  if (two) {
    m2 = a[4], ks = a[5], cs = a[6], kv = a[7], cv = a[8], preload = a[9], tc = a[10], zeta = a[11];
  } else {
    k = a[4], delta0 = a[5], tc = a[6], zeta = a[7];
  }

  // The model: slide joints along z, spheres of radius r resting on their planes at q = 0.
  const double r = 0.01;
  std::ostringstream x;
  x << "<mujoco><option timestep='" << fmt(h) << "' gravity='0 0 0' integrator='Euler'/>"
    << "<default><geom contype='0' conaffinity='0'/></default><worldbody>"
    << "<geom name='cam' type='plane' size='1 1 0.1'/>"
    << "<body name='b1' pos='0 0 " << r << "'><joint name='j1' type='slide' axis='0 0 1'/>"
    << "<inertial pos='0 0 0' mass='" << fmt(m1) << "' diaginertia='1e-6 1e-6 1e-6'/>"
    << "<geom name='g1' type='sphere' size='" << r << "'/></body>";
  if (two) {
    // the valve: its spring is the joint's (force −kv (q − springref) = −kv q − P)
    x << "<geom name='seat' type='plane' pos='1 0 0' size='0.5 0.5 0.1'/>"
      << "<body name='b2' pos='1 0 " << r << "'><joint name='j2' type='slide' axis='0 0 1' stiffness='"
      << fmt(kv) << "' springref='" << fmt(-preload / kv) << "' damping='" << fmt(cv) << "'/>"
      << "<inertial pos='0 0 0' mass='" << fmt(m2) << "' diaginertia='1e-6 1e-6 1e-6'/>"
      << "<geom name='g2' type='sphere' size='" << r << "'/></body>";
  } else {
    // case A's spring: stiffness k about −δ0 (force −k (u + δ0) in the lift's frame plus −k L)
    x.str("");
    x << "<mujoco><option timestep='" << fmt(h) << "' gravity='0 0 0' integrator='Euler'/>"
      << "<default><geom contype='0' conaffinity='0'/></default><worldbody>"
      << "<geom name='cam' type='plane' size='1 1 0.1'/>"
      << "<body name='b1' pos='0 0 " << r << "'><joint name='j1' type='slide' axis='0 0 1' stiffness='"
      << fmt(k) << "' springref='" << fmt(-delta0) << "'/>"
      << "<inertial pos='0 0 0' mass='" << fmt(m1) << "' diaginertia='1e-6 1e-6 1e-6'/>"
      << "<geom name='g1' type='sphere' size='" << r << "'/></body>";
  }
  x << "</worldbody>";
  // the cam contact plastic (critically damped) on the two-mass train; case A: as given
  const std::string imp = " solimp='0.99 0.99 0.001'";
  const double zeta_cam = two ? 1.0 : zeta;
  x << "<contact><pair geom1='g1' geom2='cam' condim='1' solref='" << fmt(tc) << " " << fmt(zeta_cam) << "'"
    << imp << "/>";
  if (two) x << "<pair geom1='g2' geom2='seat' condim='1' solref='" << fmt(tc) << " " << fmt(zeta) << "'" << imp << "/>";
  x << "</contact>";
  if (two)
    x << "<tendon><fixed name='stem' stiffness='" << fmt(ks) << "' damping='" << fmt(cs)
      << "' springlength='0'><joint joint='j2' coef='1'/><joint joint='j1' coef='-1'/></fixed></tendon>";
  x << "</mujoco>";
  const std::string xml = x.str();

  char err[1000] = "";
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  if (mj_makeEmptyFileVFS(&vfs, "model.xml", int(xml.size())) != 0) return usage("VFS");
  const int fi = mj_findFileVFS(&vfs, "model.xml");
  std::memcpy(vfs.filedata[fi], xml.data(), xml.size());
  mjModel* m = mj_loadXML("model.xml", &vfs, err, sizeof err);
  mj_deleteVFS(&vfs);
  if (!m) {
    std::fprintf(stderr, "mujoco_peer: model: %s\n%s\n", err, xml.c_str());
    return 2;
  }
  mjData* d = mj_makeData(m);
  const int g1 = mj_name2id(m, mjOBJ_GEOM, "g1");

  const long nsteps = long(std::llround(t_end / h));
  std::vector<double> rows;
  rows.reserve(std::size_t(nsteps + 1) * 7);
  auto record = [&] {
    double f[2] = {0, 0};
    for (int i = 0; i < d->ncon; ++i) {
      mjtNum cf[6];
      mj_contactForce(m, d, i, cf);
      const int g = d->contact[i].geom1 == g1 || d->contact[i].geom2 == g1 ? 0 : 1;
      f[g] += cf[0];
    }
    rows.insert(rows.end(), {d->time, d->qpos[0], two ? d->qpos[1] : 0.0, d->qvel[0],
                             two ? d->qvel[1] : 0.0, f[0], f[1]});
  };
  const std::clock_t c0 = std::clock();
  mj_forward(m, d);
  record();
  for (long s = 0; s < nsteps; ++s) {
    double L, dL, d2L;
    lift.at(d->time, L, dL, d2L);
    if (two) {
      const double st = ks * L + cs * dL;  // the stem's share of the cam's motion
      d->qfrc_applied[0] = -m1 * d2L - st;
      d->qfrc_applied[1] = st;
    } else {
      d->qfrc_applied[0] = -m1 * d2L - k * L;
    }
    mj_step(m, d);
    record();  // the contact forces applied over the step (computed at its start), at its end
  }
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;

  std::ofstream out(argv[argc - 1]);
  out << "t,q1,q2,v1,v2,f1,f2\n";
  for (std::size_t i = 0; i < rows.size(); i += 7) {
    for (int j = 0; j < 7; ++j) out << (j ? "," : "") << fmt(rows[i + j]);
    out << "\n";
  }
  if (!out) return usage("cannot write the output file");
  std::printf("cpu=%.6g steps=%ld\n", cpu, nsteps);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
