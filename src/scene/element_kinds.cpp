// camdyn — the element kinds as data (element_kinds.hpp): every key of every element kind,
// with the ElementSpec member it sets, its type, unit, documentation and own rule.
#include "scene/element_kinds.hpp"

#include <map>
#include <stdexcept>

#include "scene/key_table.hpp"

namespace camdyn::scene_detail {

namespace {

using F = ElementField;
using R = ElementField::Rule;

F real(const char* key, double ElementSpec::*m, const char* unit, const char* doc, R rule = R::Finite,
       double lo = 0.0) {
  F f{key, F::Type::Real, unit, doc, rule, lo};
  f.real = m;
  return f;
}
F ge0(const char* key, double ElementSpec::*m, const char* unit, const char* doc) {
  return real(key, m, unit, doc, R::Ge, 0.0);
}
F gt0(const char* key, double ElementSpec::*m, const char* unit, const char* doc) {
  return real(key, m, unit, doc, R::Gt, 0.0);
}
F integer(const char* key, int ElementSpec::*m, const char* doc, long long imin, long long imax) {
  F f{key, F::Type::Int, "—", doc, R::IntRange};
  f.imin = imin;
  f.imax = imax;
  f.integer = m;
  return f;
}
F reals(const char* key, std::vector<double> ElementSpec::*m, const char* unit, const char* doc,
        const char* rule_text) {
  F f{key, F::Type::Reals, unit, doc, R::Custom};
  f.rule_text = rule_text;
  f.reals = m;
  return f;
}
F custom(F f, const char* rule_text) {
  f.rule = R::Custom;
  f.rule_text = rule_text;
  return f;
}
/// A checked rule that the validator completes with a rule between keys: its full wording.
F worded(F f, const char* rule_text) {
  f.rule_text = rule_text;
  return f;
}
F with_default(F f, const char* fixed_default) {
  f.fixed_default = fixed_default;
  return f;
}
F written_if(F f, bool (*written)(const ElementSpec&)) {
  f.written = written;
  return f;
}

bool coil_clash_on(const ElementSpec& e) { return e.solid_length > 0; }
bool coil_gaps_given(const ElementSpec& e) { return e.solid_length > 0 && !e.coil_gaps.empty(); }
bool has_check_ball(const ElementSpec& e) { return e.check_ball_mass > 0; }

std::vector<ElementKindInfo> make_kinds() {
  std::vector<ElementKindInfo> k;
  F coil_restitution{"coil_restitution", F::Type::OptionalReal, "—",
                     "restitution of the coil-to-coil impacts when its coils clash", R::Custom};
  coil_restitution.optional = &ElementSpec::coil_restitution;
  coil_restitution.rule_text = "must be >= 0 and <= 1";
  coil_restitution.fixed_default = "contact.restitution";
  coil_restitution.written = coil_clash_on;
  F mass_matrix{"mass_matrix", F::Type::MassMatrix, "—", "`lumped` or `consistent`", R::Custom};
  mass_matrix.mass_matrix = &ElementSpec::mass_matrix;
  mass_matrix.rule_text = "must be one of \"lumped\", \"consistent\"";

  k.push_back({ElementKind::Spring, "spring",
               {ge0("stiffness", &ElementSpec::stiffness, "force/length", "stiffness k"),
                real("preload", &ElementSpec::preload, "force",
                     "compressive force P at q = 0 (> 0 pushes the ends apart)"),
                ge0("damping", &ElementSpec::damping, "force·time/length", "parallel viscous damper c"),
                ge0("mass", &ElementSpec::mass, "mass", "the coil's own mass (surge)"),
                integer("masses", &ElementSpec::masses, "internal surge masses N (N ≥ 1 exactly when mass > 0)", 0,
                        100000),
                with_default(written_if(custom(real("free_length", &ElementSpec::free_length, "length",
                                                    "free length when its coils clash (the installed length is "
                                                    "free_length − preload/stiffness)"),
                                               "finite, > solid_length + preload/stiffness"),
                                        coil_clash_on),
                             "(none)"),
                with_default(written_if(custom(real("solid_length", &ElementSpec::solid_length, "length",
                                                    "solid length; > 0 turns on coil clash: one unilateral "
                                                    "coil-to-coil contact per segment of the coil chain (contacts "
                                                    "`<spring>_coil<k>`)"),
                                               "> 0 when any coil-clash key is set"),
                                        coil_clash_on),
                             "0 (no coil clash)"),
                with_default(written_if(reals("coil_gaps", &ElementSpec::coil_gaps, "length",
                                              "installed gap of each segment of the coil chain when its coils "
                                              "clash, lower → upper (variable pitch)",
                                              "masses + 1 entries, each >= 0, adding up to free_length − "
                                              "preload/stiffness − solid_length"),
                                        coil_gaps_given),
                             "equal gaps (uniform pitch)"),
                coil_restitution}});
  k.push_back({ElementKind::Dashpot,
               "dashpot",
               {gt0("damping", &ElementSpec::damping, "force·time/length", "viscous damping c")}});
  k.push_back({ElementKind::Bar,
               "bar",
               {gt0("mass", &ElementSpec::mass, "mass", "total mass"),
                gt0("youngs_modulus", &ElementSpec::youngs_modulus, "force/length²", "Young's modulus E"),
                gt0("area", &ElementSpec::area, "length²", "cross-section area A"),
                gt0("length", &ElementSpec::length, "length", "length L"),
                integer("elements", &ElementSpec::elements, "number of two-node elements", 1, 100000), mass_matrix,
                ge0("rayleigh_alpha", &ElementSpec::rayleigh_alpha, "1/time", "Rayleigh α (C = αM + βK)"),
                ge0("rayleigh_beta", &ElementSpec::rayleigh_beta, "time", "Rayleigh β")}});
  k.push_back({ElementKind::Lever,
               "lever",
               {custom(real("ratio", &ElementSpec::ratio, "—",
                            "q_output = ratio · q_input (the output moves the same way as the input); with a pivot "
                            "node q_output = ratio · q_input + (1 − ratio) · q_pivot, ratio = output arm / input arm "
                            "(signed distances from the pivot along the lever: negative when the pivot lies between "
                            "them)"),
                       "finite and > 0 (two nodes); finite, != 0 and != 1 (with a pivot node)")}});
  k.push_back({ElementKind::ProgressiveSpring,
               "progressive_spring",
               {reals("deflections", &ElementSpec::deflections, "length",
                      "the table's deflections δ (compression of [lower, upper])",
                      "at least 2, finite, strictly increasing"),
                reals("forces", &ElementSpec::forces, "force",
                      "the table's forces F(δ), one per deflection; F between them is the monotone cubic (PCHIP) "
                      "through the points, beyond them the end slope's line",
                      "as many as deflections, finite, non-decreasing, last > first"),
                real("installed_deflection", &ElementSpec::installed_deflection, "length",
                     "the deflection at q = 0; the preload is F there"),
                ge0("damping", &ElementSpec::damping, "force·time/length", "parallel viscous damper c")}});
  k.push_back({ElementKind::GuideFriction,
               "guide_friction",
               {ge0("friction_coefficient", &ElementSpec::friction_coefficient, "—", "Coulomb coefficient μ"),
                ge0("normal_load", &ElementSpec::normal_load, "force", "constant normal load N on the guide"),
                gt0("velocity_scale", &ElementSpec::velocity_scale, "length/time",
                    "regularisation speed v_s of −μN tanh(v/v_s) (the stick phase is regularised: a steep damper "
                    "μN/v_s below v_s)")}});
  k.push_back({ElementKind::GasLoad,
               "gas_load",
               {reals("crank_angles_deg", &ElementSpec::crank_angles_deg, "deg",
                      "the pressure table's crank angles φ (periodic over one engine cycle, 360·crank_ratio deg)",
                      "at least 1, strictly increasing, in [0, 360·crank_ratio)"),
                reals("pressures", &ElementSpec::pressures, "force/length²",
                      "cylinder pressure p(φ) at each crank angle (gauge: minus the port's pressure), linear "
                      "between the points",
                      "as many as crank_angles_deg, finite"),
                gt0("area", &ElementSpec::area, "length²", "the valve head's area"),
                gt0("crank_ratio", &ElementSpec::crank_ratio, "—",
                    "crank angle per cam angle (2: four-stroke); φ = crank_ratio·θ + crank_offset_deg"),
                real("crank_offset_deg", &ElementSpec::crank_offset_deg, "deg", "crank angle at cam angle 0")}});
  k.push_back(
      {ElementKind::HydraulicLashAdjuster,
       "hydraulic_lash_adjuster",
       {gt0("area", &ElementSpec::area, "length²", "the plunger's pressure area A"),
        ge0("stiffness", &ElementSpec::stiffness, "force/length", "its plunger spring's stiffness"),
        real("preload", &ElementSpec::preload, "force", "its plunger spring's compressive force at q = 0"),
        gt0("chamber_volume", &ElementSpec::chamber_volume, "length³",
            "high-pressure chamber volume V₀ at q = 0; V(δ) = V₀ − Aδ"),
        gt0("bulk_modulus", &ElementSpec::bulk_modulus, "force/length²", "bulk modulus β of the air-free oil"),
        worded(ge0("air_fraction", &ElementSpec::air_fraction, "—",
                   "entrained-air volume fraction α at air_reference_pressure; β_eff(p) = (v_l + v_g)/(v_l/β + "
                   "v_g/p_abs), v_l = 1 − α, v_g = α p_ref/p_abs (isothermal air in oil, Merritt 1967)"),
               "must be >= 0 and < 1"),
        gt0("air_reference_pressure", &ElementSpec::air_reference_pressure, "force/length²",
            "absolute pressure p_ref at which air_fraction is given (the atmosphere; the default is in Pa); gauge "
            "pressures are relative to it"),
        gt0("plunger_diameter", &ElementSpec::plunger_diameter, "length",
            "plunger diameter d of the leak-down clearance"),
        ge0("leak_clearance", &ElementSpec::leak_clearance, "length",
            "radial clearance c between plunger and body; leak-down Q = π d c³ (p − p_s)/(12 μ L); 0: no leak"),
        gt0("leak_length", &ElementSpec::leak_length, "length", "length L of the leak-down clearance"),
        gt0("viscosity", &ElementSpec::viscosity, "force·time/length²", "dynamic viscosity μ of the oil"),
        ge0("supply_pressure", &ElementSpec::supply_pressure, "force/length²",
            "oil gallery (supply) gauge pressure p_s, behind the check valve and at the leak's exit"),
        ge0("check_opening_pressure", &ElementSpec::check_opening_pressure, "force/length²",
            "check valve opening pressure difference Δp_open (the valve opens for p < p_s − Δp_open; with a check "
            "ball its spring's preload is Δp_open·A_s)"),
        ge0("check_area", &ElementSpec::check_area, "length²",
            "check valve flow area A_v; Q = C_d A_v √(2/ρ) Δ/(Δ² + Δ_t²)^¼, Δ = p_s − p − Δp_open > 0; 0: no check "
            "valve. With a check ball: its full-open flow area, which the curtain area π d_s x reaches at the lift "
            "A_v/(π d_s) (0: the seat bore's area A_s = π d_s²/4)"),
        worded(gt0("check_discharge_coefficient", &ElementSpec::check_discharge_coefficient, "—",
                   "check valve discharge coefficient C_d"),
               "must be > 0 and <= 1"),
        gt0("check_transition_pressure", &ElementSpec::check_transition_pressure, "force/length²",
            "check valve regularisation Δ_t: the flow is the orifice law above it, linear (laminar) below it "
            "(default in Pa)"),
        gt0("oil_density", &ElementSpec::oil_density, "mass/length³",
            "oil density ρ of the check valve's orifice law (default in kg/m³)"),
        worded(real("initial_pressure", &ElementSpec::initial_pressure, "force/length²",
                    "chamber gauge pressure at t = 0 (the internal state's start)"),
               "must be finite and > -air_reference_pressure"),
        written_if(worded(ge0("check_ball_mass", &ElementSpec::check_ball_mass, "mass",
                              "the check valve as a ball of this mass m_b (0: the orifice law of check_area), "
                              "typically 3e-5 to 1e-4 kg (a 2 to 3 mm steel ball); its lift x off the seat and its "
                              "speed are internal states, m_b ẍ = (p_s − p)A_s − Δp_open·A_s − k_b x − c_b ẋ + "
                              "k_s·max(−x, 0), Q_check = C_d π d_s x √(2/ρ) Δ/(Δ² + Δ_t²)^¼ for 0 < x up to full "
                              "open, Δ = p_s − p (history columns force_<name>_ball_lift, force_<name>_check_flow)"),
                          "must be >= 0"),
                   has_check_ball),
        written_if(worded(ge0("check_ball_stiffness", &ElementSpec::check_ball_stiffness, "force/length",
                              "the check ball's spring stiffness k_b, typically 100 to 2000 N/m (the ball rings "
                              "at √(k_b/m_b) off its seat)"),
                          "must be >= 0; > 0 with a check ball, 0 without"),
                   has_check_ball),
        written_if(worded(ge0("check_ball_damping", &ElementSpec::check_ball_damping, "force·time/length",
                              "the check ball's viscous damping c_b (the oil's drag on it; critical is "
                              "2√(k_b m_b), about 0.2 N·s/m for 3.3e-5 kg on 300 N/m)"),
                          "must be >= 0; 0 without a check ball"),
                   has_check_ball),
        written_if(worded(ge0("check_seat_diameter", &ElementSpec::check_seat_diameter, "length",
                              "the check ball's seat bore d_s, typically 1 to 2 mm: pressure area A_s = π d_s²/4, "
                              "curtain (flow) area π d_s x"),
                          "must be >= 0; > 0 with a check ball, 0 without"),
                   has_check_ball),
        written_if(worded(ge0("check_seat_stiffness", &ElementSpec::check_seat_stiffness, "force/length",
                              "the check ball's seat as a regularised elastic stop, force k_s·(−x) while x < 0; "
                              "1e5 to 1e6 N/m keeps the ball's seat penetration below a micrometre at chamber "
                              "pressures of some MPa (its mode √(k_s/m_b) is stiff: an implicit engine)"),
                          "must be >= 0; > 0 with a check ball, 0 without"),
                   has_check_ball)}});
  return k;
}

}  // namespace

std::string ElementField::rule_words() const {
  if (rule_text) return rule_text;
  switch (rule) {
    case Rule::Finite: return "must be finite";
    case Rule::Ge: return "must be >= " + detail::format_number(lo);
    case Rule::Gt: return "must be > " + detail::format_number(lo);
    case Rule::IntRange:
      return "must be >= " + std::to_string(imin) + " and <= " + std::to_string(imax);
    case Rule::Custom: break;
  }
  return "";
}

const char* ElementField::type_name() const {
  switch (type) {
    case Type::Real:
    case Type::OptionalReal: return "real";
    case Type::Int: return "integer";
    case Type::Reals: return "array of reals";
    case Type::MassMatrix: return "enum";
  }
  return "";
}

const std::vector<ElementKindInfo>& element_kinds() {
  static const std::vector<ElementKindInfo> k = make_kinds();
  return k;
}

const ElementKindInfo& element_kind(ElementKind kind) {
  for (const ElementKindInfo& k : element_kinds())
    if (k.kind == kind) return k;
  throw std::logic_error("element kind without a descriptor in src/scene/element_kinds.cpp");
}

const ElementField* element_field(ElementKind kind, const std::string& key) {
  for (const ElementField& f : element_kind(kind).fields)
    if (key == f.key) return &f;
  return nullptr;
}

bool element_fields_equal(const ElementSpec& a, const ElementSpec& b) {
  for (const ElementKindInfo& k : element_kinds())
    for (const ElementField& f : k.fields) {
      const bool same = f.real         ? a.*f.real == b.*f.real
                        : f.integer    ? a.*f.integer == b.*f.integer
                        : f.reals      ? a.*f.reals == b.*f.reals
                        : f.optional   ? a.*f.optional == b.*f.optional
                        : f.mass_matrix ? a.*f.mass_matrix == b.*f.mass_matrix
                                       : true;
      if (!same) return false;
    }
  return true;
}

std::vector<ElementKeyDoc> element_key_docs() {
  std::vector<ElementKeyDoc> out;
  std::map<std::string, std::size_t> at;
  // Per key: the kinds' texts and rules, merged as "kind: text; kind: text" when they differ.
  std::vector<std::vector<std::pair<std::string, std::string>>> texts, rules;
  for (const ElementKindInfo& k : element_kinds())
    for (const ElementField& f : k.fields) {
      auto [it, fresh] = at.emplace(f.key, out.size());
      if (fresh) {
        ElementKeyDoc d;
        d.key = std::string("elements.") + f.key;
        d.unit = f.unit;
        d.type = f.type_name();
        if (f.fixed_default) d.fixed_default = f.fixed_default;
        out.push_back(std::move(d));
        texts.emplace_back();
        rules.emplace_back();
      }
      ElementKeyDoc& d = out[it->second];
      if (d.unit != f.unit || d.type != f.type_name())
        throw std::logic_error("element key '" + std::string(f.key) +
                               "' has different units or types in two kinds (src/scene/element_kinds.cpp)");
      d.applies_to.push_back(k.name);
      texts[it->second].emplace_back(k.name, f.doc);
      rules[it->second].emplace_back(k.name, f.rule_words());
    }
  // One text for all the kinds that take a key ("kind, kind: text"), or one per kind.
  auto merge = [](const std::vector<std::pair<std::string, std::string>>& v, bool name_kinds) {
    bool all_same = true;
    for (const auto& p : v) all_same = all_same && p.second == v.front().second;
    std::string s;
    if (all_same) {
      if (!name_kinds) return v.front().second;
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i].first;
      return s + ": " + v.front().second;
    }
    for (const auto& p : v) s += (s.empty() ? "" : "; ") + p.first + ": " + p.second;
    return s;
  };
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].text = merge(texts[i], true) + ".";
    out[i].rule = merge(rules[i], false);
  }
  return out;
}

}  // namespace camdyn::scene_detail
