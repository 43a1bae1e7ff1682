//! The generator's hidden mechanisms, each in a published form DIFFERENT from the detector's
//! (table in `docs/concealed.md`), and the decoys. A mechanism acts either inside the forward model
//! (through [`Mods`]) or on its outputs (edge, wear land, channel matrix).
//!
//! | id | generator form (here) | detector form |
//! |---|---|---|
//! | edge_ploughing | Albrecht 1960: pressure p = (1 + pi/2) k and friction m_e k on the rounded edge below the stagnation point | Waldorf, DeVor & Kapoor 1998 slip-line, and the chord effective rake from the stagnation point |
//! | flank_wear | uniform normal and shear stress on the land (Teitenberg, Bayoumi & Yucesan 1992), VB growing with cumulative cut length at a Taylor-type speed exponent | Smithey, Kapoor & DeVor 2001, VB linear in order |
//! | tool_chip_friction | Zorev 1963 stick-slip with a power-law normal stress and a sliding-speed dependent mu (family c: replacing its Coulomb-Tresca law, Zorev's a = 0) | m_f0 (V/V_ref)^-p_v on k_chip, or as a hybrid Coulomb-Tresca cap over the baseline's F/N |
//! | thermal_softening | extra Zerilli-Armstrong exponential thermal factor exp(-c3 (T - Tr)) | kappa_T on (T - T_w) and a scale on the JC m |
//! | heat_partition | family a: Loewen & Shaw 1954 shear-plane partition and tool share of the frictional heat blended in; family b: Boothroyd 1963 and all frictional heat to the chip blended in; family c: Boothroyd 1963 (from Weiner 1955) and the Loewen-Shaw tool share blended in | scale on Boothroyd beta and a constant interface share |
//! | size_effect | Kienzle 1952 power law (h / h_ref)^-m_s on the flow stress | Nix-Gao sqrt(1 + l/h), the share w_ref of it at the dataset's mean thickness held by the simulation (thirty-second session) |
//! | built_up_edge | rake shift gated by the interface temperature (Trent & Wright 2000) | rake shift gated by the interface temperature (logistic below an onset, or a band above a floor as well, or above a floor alone, thirty-sixth session), or by the speed where it orders the tests otherwise (thirty-fifth session) |
//! | force_crosstalk | full 2x2 channel matrix (dynamometer cross-sensitivity) | Ft += c Fc |

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::forms_d::{self, HybridFriction, TanhSoftening};
use super::material::{Cond, Solution};
use super::Family;

/// The eight library ids (exact spelling of the detector's report).
pub const MECHANISMS: [&str; 8] = [
    "edge_ploughing",
    "flank_wear",
    "tool_chip_friction",
    "thermal_softening",
    "heat_partition",
    "size_effect",
    "built_up_edge",
    "force_crosstalk",
];

/// The decoys: not physics a library mechanism describes; the right answer is no mechanism.
pub const DECOYS: [&str; 4] = ["decoy:gain", "decoy:channel_gain", "decoy:outlier", "decoy:drift"];

/// Zorev (1963) stick-slip contact: normal stress sigma_n(x) = sigma_max (1 - x/l_c)^a with
/// sigma_max = (a + 1) sigma_N (mean sigma_N), shear tau = min(k, mu sigma_n); mu(V_c) =
/// mu0 (V_c / 1 m/s)^-q (sliding-speed dependent friction, e.g. Rech, Claudin & D'Eramo 2009).
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Zorev {
    /// mu at a chip speed of 1 m/s.
    pub mu0: f64,
    /// Speed exponent.
    pub q: f64,
    /// Normal-stress exponent a.
    pub a: f64,
}

impl Zorev {
    /// Mean interface shear stress over k_chip, for a mean normal stress `sn_over_k` k_chip and chip
    /// speed `vc` m/s. Closed form: with r = mu (a + 1) sigma_N / k, r <= 1 (all sliding): r / (a + 1);
    /// otherwise sticking up to x/l_c = 1 - r^(-1/a), giving 1 - a r^(-1/a) / (a + 1).
    pub fn factor(&self, sn_over_k: f64, vc: f64) -> f64 {
        let mu = self.mu0 * vc.max(0.05).powf(-self.q);
        let r = mu * (self.a + 1.0) * sn_over_k.max(0.0);
        if r <= 1.0 {
            r / (self.a + 1.0)
        } else {
            1.0 - self.a * r.powf(-1.0 / self.a) / (self.a + 1.0)
        }
    }
}

/// Hooks inside a forward model, per condition.
#[derive(Debug, Clone, Copy)]
pub struct Mods {
    /// Multiplier on every flow stress (size effect).
    pub flow_mult: f64,
    /// Extra exponential thermal softening c3 (Tm - Tr) (thermal softening; 0 = JC's own).
    pub exp_softening: f64,
    /// Blend towards the other family's heat partition: 0 = the model's own.
    pub partition_blend: f64,
    /// Interface friction law: family a multiplies k_chip by 1 - blend (1 - its factor); families b
    /// and c replace their own law.
    pub friction: Option<Zorev>,
    /// Family a: how much of the Zorev reduction applies (0 = Oxley's full sticking).
    pub friction_blend: f64,
    /// Rake shift, rad (built-up edge; family d: also the edge's effective rake).
    pub rake_shift: f64,
    /// Family d: multiplier on the primary zone's flow stress k_AB only (size effect).
    pub primary_mult: f64,
    /// Family d: TANH strain-temperature softening on every flow stress.
    pub tanh_softening: Option<TanhSoftening>,
    /// Family d: hybrid Coulomb-Tresca interface with speed-dependent mu.
    pub hybrid_friction: Option<HybridFriction>,
    /// Family d: blend towards Weiner's shear-plane partition and the Péclet-dependent tool share.
    pub partition_d: f64,
}

impl Mods {
    /// No mechanism.
    pub const fn none() -> Self {
        Self {
            flow_mult: 1.0,
            exp_softening: 0.0,
            partition_blend: 0.0,
            friction: None,
            friction_blend: 0.0,
            rake_shift: 0.0,
            primary_mult: 1.0,
            tanh_softening: None,
            hybrid_friction: None,
            partition_d: 0.0,
        }
    }
}

/// Albrecht (1960) edge force: the work below the stagnation point flows under the rounded edge of
/// radius r; on the arc from theta_s (rake side, from the lowest point) to -theta_c (flank side,
/// elastic recovery) it presses with p = (1 + pi/2) k (Prandtl flat-punch pressure, Hill 1950) and
/// rubs with tau = m_e k. Integrating over the arc (per unit width):
/// Fc = r [p (cos th_c - cos th_s) + tau (sin th_s + sin th_c)],
/// Ft = r [p (sin th_s + sin th_c) + tau (cos th_s - cos th_c)].
/// The stagnation depth r (1 - cos th_s) is kept below h.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Edge {
    /// Stagnation angle, rad.
    pub theta_s: f64,
    /// Flank-side contact angle, rad.
    pub theta_c: f64,
    /// Friction factor on the edge.
    pub m_e: f64,
}

impl Edge {
    /// (Fc, Ft) per unit width, N/m, for radius `r` m, uncut chip thickness `h` m and shear flow
    /// stress `k` Pa.
    pub fn forces(&self, r: f64, h: f64, k: f64) -> (f64, f64) {
        if r <= 0.0 {
            return (0.0, 0.0);
        }
        let ts = self.theta_s.min((1.0 - (h / r).min(1.0)).acos());
        let tc = self.theta_c;
        let p = (1.0 + std::f64::consts::FRAC_PI_2) * k;
        let tau = self.m_e * k;
        let fc = r * (p * (tc.cos() - ts.cos()) + tau * (ts.sin() + tc.sin()));
        let ft = r * (p * (ts.sin() + tc.sin()) + tau * (ts.cos() - tc.cos()));
        (fc.max(0.0), ft.max(0.0))
    }
}

/// Per-dataset random shape of the hidden mechanism (its strength is set separately).
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Shape {
    /// Albrecht edge.
    pub edge: Edge,
    /// Wear-land normal stress over k_AB.
    pub land_sigma_over_k: f64,
    /// Wear-land friction coefficient.
    pub land_mu: f64,
    /// Taylor exponent n_T: wear per cut length grows as V^(1/n_T - 1).
    pub taylor_n: f64,
    /// Friction coefficient at 1 m/s (family a's Zorev law).
    pub zorev_mu0: f64,
    /// Friction speed exponent q (Zorev mu law).
    pub zorev_q: f64,
    /// Zorev a.
    pub zorev_a: f64,
    /// Direction of the softening change: +1 (stronger softening than JC's) or -1 (weaker).
    pub soften_sign: f64,
    /// Quantile of the base interface temperatures that sets the BUE gate.
    pub bue_quantile: f64,
    /// Width of the BUE gate, degC.
    pub bue_width: f64,
    /// Crosstalk pattern: (Fc<-Ft, Ft<-Fc, Fc gain, Ft gain) per unit strength.
    pub channel: [f64; 4],
}

impl Shape {
    /// Draws a shape.
    pub fn draw(rng: &mut ChaCha8Rng) -> Self {
        let sign = |rng: &mut ChaCha8Rng| if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        Self {
            edge: Edge {
                theta_s: rng.gen_range(50.0f64..70.0).to_radians(),
                theta_c: rng.gen_range(5.0f64..15.0).to_radians(),
                m_e: rng.gen_range(0.5..0.9),
            },
            land_sigma_over_k: rng.gen_range(0.6..1.2),
            land_mu: rng.gen_range(0.3..0.5),
            taylor_n: rng.gen_range(0.3..0.5),
            zorev_mu0: rng.gen_range(0.3..0.8),
            zorev_q: rng.gen_range(0.1..0.3),
            zorev_a: rng.gen_range(2.0..4.0),
            soften_sign: sign(rng),
            bue_quantile: rng.gen_range(0.3..0.6),
            bue_width: rng.gen_range(25.0..60.0),
            channel: [
                sign(rng) * rng.gen_range(0.2..0.6),
                sign(rng) * rng.gen_range(0.6..1.0),
                rng.gen_range(-0.3..0.3),
                rng.gen_range(-0.3..0.3),
            ],
        }
    }
}

/// Range of the strength s searched for a target effect-to-noise ratio, and its unit:
/// edge radius (m), final VB (m), friction (family a: share of the Zorev reduction; families b and
/// c: mu lowered by 60 s % and made speed-dependent, c's Zorev exponent a growing from 0), exponential
/// softening c3 (Tm - Tr), partition blend (0 = the model's own, 1 = the other partition; family c
/// to 2, as far again beyond it: its Coulomb-Tresca contact passes the interface temperature to the
/// forces only where the Tresca limit binds, and at a blend of 1 most steel datasets stayed below
/// ENR 2), Kienzle exponent, BUE rake shift (rad), channel-matrix scale.
pub fn strength_range(family: Family, id: &str) -> (f64, f64) {
    if family == Family::D {
        return forms_d::strength_range(id);
    }
    match id {
        "heat_partition" if family == Family::C => (0.02, 2.0),
        "edge_ploughing" => (2e-6, 80e-6),
        "flank_wear" => (0.01e-3, 0.4e-3),
        "tool_chip_friction" => (0.01, 1.0),
        "thermal_softening" => (0.01, 1.0),
        "heat_partition" => (0.02, 1.0),
        "size_effect" => (0.005, 0.6),
        "built_up_edge" => (0.2f64.to_radians(), 25f64.to_radians()),
        "force_crosstalk" => (0.002, 0.25),
        _ => (0.0, 0.0),
    }
}

/// Nominal friction of family b (its own Zorev contact): mu 0.6, no speed dependence, a = 3.
pub const FAMILY_B_FRICTION: Zorev = Zorev { mu0: 0.6, q: 0.0, a: 3.0 };

/// Friction coefficient of family c's hybrid Coulomb-Tresca contact, tau = min(mu sigma_N, k_chip).
pub const FAMILY_C_MU: f64 = 0.5;

/// The in-model hooks of mechanism `id` at strength `s` for one condition. `t_gate` is the BUE
/// gate temperature of the dataset and `base` the condition's solution without the mechanism.
/// Family d has its own forms ([`forms_d::mods`]) and never calls this.
pub fn mods(family: Family, id: &str, s: f64, shape: &Shape, c: &Cond, base: &Solution, t_gate: f64) -> Mods {
    let mut m = Mods::none();
    match id {
        "tool_chip_friction" => {
            m.friction = Some(match family {
                Family::A | Family::D => {
                    m.friction_blend = s;
                    Zorev { mu0: shape.zorev_mu0, q: shape.zorev_q, a: shape.zorev_a }
                }
                Family::B => {
                    Zorev { mu0: FAMILY_B_FRICTION.mu0 * (1.0 - 0.6 * s), q: shape.zorev_q * s, a: FAMILY_B_FRICTION.a }
                }
                // Zorev's law with a = 0 (uniform normal stress) is family c's own Coulomb-Tresca law
                // min(mu sigma_N, k_chip): at s = 0 the mechanism is off, at s = 1 it is Zorev's
                // stick-slip (a 2-4) with mu lowered by 60 % and speed-dependent.
                Family::C => Zorev { mu0: FAMILY_C_MU * (1.0 - 0.6 * s), q: shape.zorev_q * s, a: shape.zorev_a * s },
            });
        }
        "thermal_softening" => m.exp_softening = shape.soften_sign * s,
        "heat_partition" => m.partition_blend = s,
        "size_effect" => m.flow_mult = (c.h / 0.1e-3).powf(-s),
        "built_up_edge" => {
            let gate = 1.0 / (1.0 + ((base.t_int - t_gate) / shape.bue_width).exp());
            m.rake_shift = s * gate;
        }
        _ => {}
    }
    m
}

/// The channel matrix of `force_crosstalk` at strength s applied to (Fc, Ft).
pub fn channel(s: f64, shape: &Shape, fc: f64, ft: f64) -> (f64, f64) {
    let [c12, c21, g1, g2] = shape.channel;
    ((1.0 + s * g1) * fc + s * c12 * ft, s * c21 * fc + (1.0 + s * g2) * ft)
}

/// Wear-land forces (Fc, Ft) per unit width for land VB (m) and primary flow stress k (Pa):
/// uniform normal stress sigma_w = (sigma/k) k and shear tau_w = mu_w sigma_w over the land.
pub fn wear_land(shape: &Shape, vb: f64, k: f64) -> (f64, f64) {
    let sigma = shape.land_sigma_over_k * k;
    (shape.land_mu * sigma * vb, sigma * vb)
}

/// Normalised wear-land growth over the run (last test = 1): each test adds cut length
/// L_i = V_i t_cut; wear per unit length grows as (V_i / V_med)^(1/n_T - 1) (Taylor 1907 tool life
/// V T^n = C gives a cut length to a fixed VB proportional to V^(1 - 1/n)); VB at a test is the
/// wear accumulated before it plus half its own.
pub fn wear_profile(speeds_in_run_order: &[f64], taylor_n: f64) -> Vec<f64> {
    let mut sorted = speeds_in_run_order.to_vec();
    sorted.sort_by(f64::total_cmp);
    let vmed = sorted[sorted.len() / 2].max(1e-9);
    let inc: Vec<f64> = speeds_in_run_order.iter().map(|v| v * (v / vmed).powf(1.0 / taylor_n - 1.0)).collect();
    let total: f64 = inc.iter().sum();
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(inc.len());
    for d in &inc {
        out.push((acc + 0.5 * d) / (total - 0.5 * inc[inc.len() - 1]).max(1e-30));
        acc += d;
    }
    out
}

/// Applies decoy `hidden` to the noise-free truth `with` (rows in design order, `run_order` the run
/// position of each) and returns its parameter; `None` (nothing drawn, nothing changed) for a
/// mechanism or a null. `decoy:gain`: one factor 1 +- 5-15 % on both forces; `decoy:channel_gain`:
/// one factor 1 +- 5-15 % on one force channel, the cutting or the feed force with equal chance (the
/// parameter is the factor; forty-eighth session); `decoy:outlier`: one row's forces off by
/// +15-35 % or -9-21 %; `decoy:drift`: both forces drifting 5-15 % over the run.
pub fn decoy(hidden: &str, rng: &mut ChaCha8Rng, with: &mut [[f64; 4]], run_order: &[usize]) -> Option<f64> {
    let n = with.len();
    match hidden {
        "decoy:gain" => {
            let g = 1.0 + if rng.gen_bool(0.5) { 1.0 } else { -1.0 } * rng.gen_range(0.05..0.15);
            for y in with.iter_mut() {
                y[0] *= g;
                y[1] *= g;
            }
            Some(g)
        }
        "decoy:channel_gain" => {
            let channel = usize::from(rng.gen_bool(0.5));
            let g = 1.0 + if rng.gen_bool(0.5) { 1.0 } else { -1.0 } * rng.gen_range(0.05..0.15);
            for y in with.iter_mut() {
                y[channel] *= g;
            }
            Some(g)
        }
        "decoy:outlier" => {
            let f = 1.0 + if rng.gen_bool(0.5) { 1.0 } else { -0.6 } * rng.gen_range(0.15..0.35);
            let i = rng.gen_range(0..n);
            with[i][0] *= f;
            with[i][1] *= f;
            Some(f)
        }
        "decoy:drift" => {
            let dr = if rng.gen_bool(0.5) { 1.0 } else { -1.0 } * rng.gen_range(0.05..0.15);
            for (i, y) in with.iter_mut().enumerate() {
                let g = 1.0 + dr * run_order[i] as f64 / (n - 1).max(1) as f64;
                y[0] *= g;
                y[1] *= g;
            }
            Some(dr)
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zorev_limits_by_hand() {
        let z = Zorev { mu0: 0.5, q: 0.0, a: 3.0 };
        // r = 0.5 * 4 * 0.25 = 0.5 <= 1: all sliding, factor r / 4 = 0.125 (= mu sigma_N / k).
        assert!((z.factor(0.25, 2.0) - 0.125).abs() < 1e-12);
        // r = 0.5 * 4 * 4 = 8: 1 - 3 * 8^(-1/3) / 4 = 1 - 0.375 = 0.625.
        assert!((z.factor(4.0, 2.0) - 0.625).abs() < 1e-12);
    }

    #[test]
    fn albrecht_edge_by_hand() {
        // theta_s 60, theta_c 10 deg, m_e 0.7, k 450 MPa, r 30 um, h 0.1 mm:
        // Fc = 30e-6 * 450e6 * (2.5708 * (0.98481 - 0.5) + 0.7 * (0.86603 + 0.17365)) = 26.65 kN/m,
        // Ft = 30e-6 * 450e6 * (2.5708 * 1.03968 - 0.7 * 0.48481) = 31.50 kN/m.
        let e = Edge { theta_s: 60f64.to_radians(), theta_c: 10f64.to_radians(), m_e: 0.7 };
        let (fc, ft) = e.forces(30e-6, 0.1e-3, 450e6);
        assert!((fc / 1e3 - 26.65).abs() < 0.05, "{fc}");
        assert!((ft / 1e3 - 31.50).abs() < 0.05, "{ft}");
    }

    #[test]
    fn wear_grows_to_one_at_the_last_test() {
        let p = wear_profile(&[100.0, 100.0, 100.0], 0.5);
        // Equal increments d: 0.5 d, 1.5 d, 2.5 d over 2.5 d.
        assert!((p[0] - 0.2).abs() < 1e-12 && (p[1] - 0.6).abs() < 1e-12 && (p[2] - 1.0).abs() < 1e-12);
    }
}
