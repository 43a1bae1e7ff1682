//! Family `d` of the generator: family `a`'s Oxley closure (`oxley.rs`: same solver, materials,
//! nuisance, noise, designs, ENR bisection and decoys) with EVERY hidden mechanism in a published
//! form that differs from both family `a`'s form (`mechanism.rs`) and the detector's. It measures how
//! the detector copes with a mechanism whose functional form it has never seen, on the closure an
//! external Oxley-based test suite uses. Where a paper's exact constants are not reproduced here the
//! form is said to be "after" it, and what is derived here is labelled.
//!
//! | id | family d (here) | family a | detector |
//! |---|---|---|---|
//! | edge_ploughing | effective rake of the rounded edge's chord (after Manjunathaiah & Endres 2000, Kountanya & Endres 2001) inside the solve, plus a small flank rubbing force | Albrecht's additive arc forces | Waldorf slip-line plus the chord effective rake from the stagnation point |
//! | flank_wear | land stress decaying exponentially behind the edge, hybrid Coulomb-Tresca shear; VB growing by Usui's wear rate sigma V exp(-lambda / T) | uniform land stress, Taylor growth | Smithey land, VB linear in order |
//! | tool_chip_friction | tau = min(mu sigma_N, k_chip), mu = mu0 / (1 + V_c / V_0), blended in (strength beyond 1 lowers mu) | Zorev stick-slip, mu0 V_c^-q | m_f0 (V/V_ref)^-p_v on k_chip, or as a hybrid Coulomb-Tresca cap over the baseline's F/N |
//! | thermal_softening | TANH strain-temperature softening (Calamaz, Coupard & Girot 2008) | Zerilli-Armstrong exp(-c3 T*) | kappa_T and JC m scale |
//! | heat_partition | Weiner's shear-plane partition and a Péclet-dependent tool share (after Tian & Kennedy 1994) | Loewen-Shaw R1 and 1 - R2 | Boothroyd-beta scale, constant share |
//! | size_effect | primary zone only, k_AB (1 + h_s / h) (after Backer, Marshall & Shaw 1952) | Kienzle power law on every flow stress | Nix-Gao sqrt(1 + l/h), the share w_ref of it at the dataset's mean thickness held by the simulation (thirty-second session) |
//! | built_up_edge | a speed window (peak speed falling with feed; after Trent & Wright 2000, Childs et al. 2000), rake increase and edge radius | interface-temperature logistic gate | interface-temperature logistic gate or band, or the same on the speed |
//! | force_crosstalk | dynamometer turned by an angle (rotation) plus a feed-into-cutting leakage | full 2x2 matrix | Ft += c Fc |

use std::f64::consts::{FRAC_PI_2, PI};

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::material::{Cond, Consts, Solution};
use super::mechanism::Mods;
use super::oxley;

/// Hybrid Coulomb-Tresca interface with a sliding-speed-dependent friction coefficient:
/// tau = min(mu(V_c) sigma_N, k_chip), mu(V_c) = mu0 / (1 + V_c / V_0). Rech, Claudin & D'Eramo 2009
/// (Tribol. Int. 42, 738) measured an apparent friction coefficient falling with sliding speed; the
/// rational law (finite at V_c = 0, ~ 1/V_c at high speed) is a form after their data, not their fit,
/// and its constants are drawn (mu0 0.5-1.0, V_0 0.5-3 m/s). The strength `blend` s: up to 1 the share
/// of the contact that follows the law (0 = Oxley's full sticking tau = k_chip); beyond 1 (to 2) the
/// whole contact follows it with mu lowered by 50 (s - 1) % (a lubricated or coated contact; where the
/// Tresca limit binds, as in Ti6Al4V's slow cuts, the law alone leaves Oxley's sticking unchanged).
#[derive(Debug, Clone, Copy)]
pub struct HybridFriction {
    /// mu at V_c = 0.
    pub mu0: f64,
    /// Speed scale V_0, m/s.
    pub v0: f64,
    /// Strength s: 0 = off, 1 = the full hybrid law, to 2 with mu lowered.
    pub blend: f64,
}

impl HybridFriction {
    /// Target interface shear stress, Pa, for chip flow stress `k_chip`, mean normal stress `sigma_n`
    /// and chip speed `vc` m/s.
    pub fn target(&self, k_chip: f64, sigma_n: f64, vc: f64) -> f64 {
        let lowered = 1.0 - 0.5 * (self.blend - 1.0).max(0.0);
        let mu = lowered * self.mu0 / (1.0 + vc.max(0.0) / self.v0);
        let factor = (mu * sigma_n.max(0.0) / k_chip).min(1.0);
        k_chip * (1.0 - self.blend.min(1.0) * (1.0 - factor))
    }
}

/// TANH softening multiplier of Calamaz, Coupard & Girot 2008 (Int. J. Mach. Tools Manuf. 48, 275):
/// D + (1 - D) tanh(1 / (eps + S)^c), D = 1 - (T/Tm)^d, S = (T/Tm)^b, temperatures in kelvin; near
/// 1 at small strain, falling towards D at large strain, so it acts mostly in the secondary zone. Only
/// this multiplier is used (their hardening term's 1 / exp(eps^a) is left out); b, c, d are drawn
/// around their Ti6Al4V set (b 0.3-0.5, c 2-6, d 0.8-1.2). Softening only (the model cannot harden);
/// `s` blends it in: factor 1 - s (1 - multiplier).
#[derive(Debug, Clone, Copy)]
pub struct TanhSoftening {
    /// Strength, 0-1.
    pub s: f64,
    /// Exponent b of S.
    pub b: f64,
    /// Exponent c.
    pub c: f64,
    /// Exponent d of D.
    pub d: f64,
}

impl TanhSoftening {
    /// Multiplier on the flow stress at strain `eps`, temperature `t_c` degC, melting `tm_c` degC.
    pub fn factor(&self, eps: f64, t_c: f64, tm_c: f64) -> f64 {
        let x = ((t_c + 273.15) / (tm_c + 273.15)).clamp(1e-3, 1.0);
        let (d_big, s_big) = (1.0 - x.powf(self.d), x.powf(self.b));
        let m = d_big + (1.0 - d_big) * (1.0 / (eps.max(0.0) + s_big).powf(self.c)).tanh();
        1.0 - self.s * (1.0 - m)
    }
}

/// Stationary-limit constant of the Péclet interpolation in [`tool_share`]: (2 / 0.946)^2 / pi, so that
/// the moving source's mean rise 2 q l / (K sqrt(pi (c0 + Pe))) equals the stationary square source's
/// mean 0.946 q l / K at Pe = 0 (derived here).
const TK_C0: f64 = 1.422_747_548_077_319_7;

/// Tool share of the tool-chip frictional heat: Blok's postulate (equal mean flash temperatures)
/// between the stationary tool (uniform square source of half-side l, mean rise 0.946 q l / K_tool)
/// and the moving chip (mean rise 2 q l / (K_chip sqrt(pi (c0 + Pe))), Pe = V_c l / (2 kappa), a Péclet
/// interpolation after Tian & Kennedy 1994, ASME J. Tribol. 116, 167; c0 derived here), l = l_c / 2:
/// share = 1 / (1 + 0.946 K_chip sqrt(pi (c0 + Pe)) / (2 K_tool)). Unlike Loewen & Shaw's R2 (family
/// a) it has no pre-heating term; unlike the detector's it is not constant.
pub fn tool_share(k_chip: f64, k_tool: f64, vc: f64, l_c: f64, kappa: f64) -> f64 {
    let pe = vc * 0.5 * l_c / (2.0 * kappa);
    1.0 / (1.0 + 0.946 * k_chip * (PI * (TK_C0 + pe.max(0.0))).sqrt() / (2.0 * k_tool))
}

/// Effective rake, rad, of a tool of rake `rake` with edge radius `r` at uncut thickness `h`: the
/// angle of the chord from the edge's lowest point to the point of the tool at the free-surface
/// height h (after Manjunathaiah & Endres 2000, ASME J. Manuf. Sci. Eng. 122, 384, and Kountanya &
/// Endres 2001, ASME IMECE, whose effective rake of an edge-radiused tool depends on r/h; the chord
/// geometry is derived here). On the arc (h <= r (1 + sin a)): -(pi/2 - theta/2), cos theta = 1 - h/r;
/// above it: atan(x / h), x = -r cos a + t sin a, t = (h - r (1 + sin a)) / cos a. -> a as r/h -> 0.
pub fn effective_rake(h: f64, r: f64, rake: f64) -> f64 {
    if r <= 0.0 {
        return rake;
    }
    let top = r * (1.0 + rake.sin());
    if h <= top {
        let theta = (1.0 - h / r).clamp(-1.0, 1.0).acos();
        -(FRAC_PI_2 - 0.5 * theta)
    } else {
        let t = (h - top) / rake.cos();
        ((-r * rake.cos() + t * rake.sin()) / h).atan()
    }
}

/// Lowest effective rake passed to the Oxley solve (the closure has no solution far below it).
const RAKE_FLOOR: f64 = -35.0 * PI / 180.0;

/// Land forces (Fc, Ft) per unit width, N/m: normal stress p0 k exp(-x / x0) decaying behind the
/// edge (x from the edge, over the land VB), shear tau = min(mu sigma, k) (sticking near the edge
/// when mu p0 > 1). A form after the plastic-then-elastic land of Waldorf (1996, PhD thesis, Univ.
/// Illinois), here a smooth exponential decay (derived), so the land force saturates with VB:
/// F_n = p0 k x0 (1 - e^(-VB/x0)), F_f = k x_s + mu p0 k x0 (e^(-x_s/x0) - e^(-VB/x0)),
/// x_s = clamp(x0 ln(mu p0), 0, VB).
pub fn land(vb: f64, k: f64, p0: f64, mu: f64, x0: f64) -> (f64, f64) {
    if vb <= 0.0 {
        return (0.0, 0.0);
    }
    let fn_ = p0 * k * x0 * (1.0 - (-vb / x0).exp());
    let xs = (x0 * (mu * p0).ln()).clamp(0.0, vb);
    let ff = k * xs + mu * p0 * k * x0 * ((-xs / x0).exp() - (-vb / x0).exp());
    (ff, fn_)
}

/// Normalised land growth over the run (last test = 1) by Usui's wear-rate law (Usui, Shirakashi &
/// Kitagawa 1984, Wear 100, 129): dW/dt = C sigma_n V_s exp(-lambda / theta). Per test of equal cutting
/// time the increment is k_AB V exp(-lambda / T) (sigma_n ~ k_AB; the flank temperature taken as the
/// primary zone's T_AB, degC, an assumption here; lambda drawn 2000-6000 K, the order of their
/// low-temperature constant); VB at a test is the wear before it plus half its own (as family a).
pub fn usui_profile(speeds: &[f64], k_ab: &[f64], t_c: &[f64], lambda: f64) -> Vec<f64> {
    let inc: Vec<f64> =
        speeds.iter().zip(k_ab).zip(t_c).map(|((v, k), t)| k * v * (-lambda / (t + 273.15)).exp()).collect();
    let total: f64 = inc.iter().sum();
    let denom = (total - 0.5 * inc[inc.len() - 1]).max(1e-300);
    let mut acc = 0.0;
    inc.iter()
        .map(|d| {
            let p = (acc + 0.5 * d) / denom;
            acc += d;
            p
        })
        .collect()
}

/// Family d's random shape of the hidden mechanism (drawn only for family d).
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct ShapeD {
    /// Hybrid friction mu0 and V_0 (m/s).
    pub fr_mu0: f64,
    /// Friction speed scale, m/s.
    pub fr_v0: f64,
    /// TANH exponents b, c, d.
    pub tanh: [f64; 3],
    /// Flank rubbing of the rounded edge: normal force q_r k r per unit width.
    pub rub_q: f64,
    /// Land: edge stress p0 (over k_AB), friction mu, decay length x0 (m), Usui lambda (K).
    pub land: [f64; 4],
    /// BUE window: peak's quantile in the design's ln-speed span, width (in ln V), feed exponent of
    /// the peak speed, edge radius per radian of BUE rake (m).
    pub bue: [f64; 4],
    /// Crosstalk: rotation sense (+-1) and feed-into-cutting leakage per radian of rotation.
    pub xt: [f64; 2],
}

impl ShapeD {
    /// Draws a shape.
    pub fn draw(rng: &mut ChaCha8Rng) -> Self {
        let sign = |rng: &mut ChaCha8Rng| if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        Self {
            fr_mu0: rng.gen_range(0.5..1.0),
            fr_v0: rng.gen_range(0.5..3.0),
            tanh: [rng.gen_range(0.3..0.5), rng.gen_range(2.0..6.0), rng.gen_range(0.8..1.2)],
            rub_q: rng.gen_range(0.2..0.5),
            land: [
                rng.gen_range(1.5..2.57),
                rng.gen_range(0.3..0.8),
                rng.gen_range(40e-6..120e-6),
                rng.gen_range(2000.0..6000.0),
            ],
            bue: [
                rng.gen_range(0.2..0.8),
                rng.gen_range(0.25..0.5),
                rng.gen_range(0.3..0.7),
                rng.gen_range(10e-6..35e-6),
            ],
            xt: [sign(rng), sign(rng) * rng.gen_range(0.2..0.6)],
        }
    }
}

/// Family d's strength ranges: edge radius (m), final VB (m), friction strength (to 2: see
/// [`HybridFriction`]), TANH blend, partition blend (to 2, as family c), h_s (m), BUE rake at the window's peak (rad), rotation angle (rad).
pub fn strength_range(id: &str) -> (f64, f64) {
    match id {
        "edge_ploughing" => (2e-6, 80e-6),
        "flank_wear" => (0.01e-3, 0.4e-3),
        "tool_chip_friction" => (0.01, 2.0),
        "thermal_softening" => (0.01, 1.0),
        "heat_partition" => (0.02, 2.0),
        "size_effect" => (0.1e-6, 40e-6),
        "built_up_edge" => (0.2f64.to_radians(), 25f64.to_radians()),
        "force_crosstalk" => (0.002, 0.25),
        _ => (0.0, 0.0),
    }
}

/// BUE window in speed at feed h: exp(-(ln(V / V_p))^2 / (2 w^2)), V_p = V_q (h / 0.1 mm)^-e, V_q at
/// the drawn quantile of the design's ln-speed span `v_span` (m/s). After Trent & Wright 2000 (Metal
/// Cutting, 4th ed.) and Childs et al. 2000 (Metal Machining): a BUE grows at low speed and vanishes
/// at higher speed, the more so the larger the feed; the log-normal window is chosen here.
pub fn bue_window(sd: &ShapeD, v: f64, h: f64, v_span: (f64, f64)) -> f64 {
    let [q, w, e, _] = sd.bue;
    let vq = (v_span.0.ln() + q * (v_span.1 / v_span.0).ln()).exp();
    let vp = vq * (h / 0.1e-3).powf(-e);
    (-(v / vp).ln().powi(2) / (2.0 * w * w)).exp()
}

/// The in-model hooks of mechanism `id` at strength `s` for one condition. Size effect: k_AB (1 + h_s
/// / h) on the primary zone only, s = h_s (Backer, Marshall & Shaw 1952, Trans. ASME 74, 61: the
/// specific energy rising as h falls, which they traced to the primary shear zone; the 1/h form is
/// chosen here). Edge: the effective rake of radius s ([`effective_rake`], floor -35 deg). BUE: rake
/// + g and edge radius g rho, g = s times the speed window ([`bue_window`]).
pub fn mods(id: &str, s: f64, sd: &ShapeD, c: &Cond, v_span: (f64, f64)) -> Mods {
    let mut m = Mods::none();
    match id {
        "tool_chip_friction" => m.hybrid_friction = Some(HybridFriction { mu0: sd.fr_mu0, v0: sd.fr_v0, blend: s }),
        "thermal_softening" => {
            m.tanh_softening = Some(TanhSoftening { s, b: sd.tanh[0], c: sd.tanh[1], d: sd.tanh[2] });
        }
        "heat_partition" => m.partition_d = s,
        "size_effect" => m.primary_mult = 1.0 + s / c.h,
        "edge_ploughing" => m.rake_shift = effective_rake(c.h, s, c.rake).max(RAKE_FLOOR.min(c.rake)) - c.rake,
        "built_up_edge" => {
            let g = s * bue_window(sd, c.v, c.h, v_span);
            m.rake_shift = effective_rake(c.h, g * sd.bue[3], c.rake + g).max(RAKE_FLOOR.min(c.rake)) - c.rake;
        }
        _ => {}
    }
    m
}

/// One noise-free row (Fc, Ft, t_c, T_int) of family d's truth with mechanism `hidden` at strength
/// `s`: the in-model mechanisms are solved on the branch of `base` (the row without the mechanism);
/// `edge` adds the dataset's background tool edge as family a does; `wear` is the row's share of the
/// final VB.
#[allow(clippy::too_many_arguments)]
pub fn truth_row(
    hidden: &str,
    s: f64,
    sd: &ShapeD,
    c: &Cond,
    k: &Consts,
    base: &Solution,
    wear: f64,
    v_span: (f64, f64),
    edge: &dyn Fn(&Solution) -> [f64; 4],
) -> Result<[f64; 4], String> {
    let in_model =
        ["tool_chip_friction", "thermal_softening", "heat_partition", "size_effect", "edge_ploughing", "built_up_edge"];
    let sol = if in_model.contains(&hidden) {
        oxley::solve_near(c, k, &mods(hidden, s, sd, c, v_span), Some(base.phi))?
    } else {
        *base
    };
    let mut y = edge(&sol);
    match hidden {
        "edge_ploughing" => {
            // Flank rubbing of the rounded edge (elastic recovery): normal q_r k r, friction 0.3 of it.
            let n = sd.rub_q * sol.k_ab * s;
            y[0] += 0.3 * n;
            y[1] += n;
        }
        "flank_wear" => {
            let (fc, ft) = land(s * wear, sol.k_ab, sd.land[0], sd.land[1], sd.land[2]);
            y[0] += fc;
            y[1] += ft;
        }
        "force_crosstalk" => {
            let (fc, ft) = channel(s, sd, y[0], y[1]);
            if fc <= 0.0 || ft <= 0.0 {
                return Err("crosstalk made a force negative".into());
            }
            y[0] = fc;
            y[1] = ft;
        }
        _ => {}
    }
    Ok(y)
}

/// Dynamometer turned by angle theta = s about the tool's axis (the measured vector rotated; sense
/// drawn) plus a feed-into-cutting leakage c s Ft (a cross-sensitivity): Fc' = cos(theta) Fc +
/// sin(theta) Ft + c s Ft, Ft' = -sin(theta) Fc + cos(theta) Ft. Geometric form derived here; the
/// leakage after the cross-talk a piezoelectric dynamometer's data sheet states as a share of range.
pub fn channel(s: f64, sd: &ShapeD, fc: f64, ft: f64) -> (f64, f64) {
    let th = sd.xt[0] * s;
    (th.cos() * fc + th.sin() * ft + sd.xt[1] * s * ft, -th.sin() * fc + th.cos() * ft)
}

#[cfg(test)]
mod tests {
    use super::super::dataset;
    use super::super::material::{Consts, MATERIALS};
    use super::super::mechanism::MECHANISMS;
    use super::super::Family;
    use super::*;

    fn close(x: f64, y: f64, tol: f64) -> bool {
        (x - y).abs() <= tol * y.abs().max(1e-12)
    }

    #[test]
    fn hybrid_friction_and_tanh_by_hand() {
        // mu0 0.8, V_0 2 m/s, V_c 1 m/s: mu = 0.8 / 1.5 = 0.53333; sigma_N / k = 1.2: mu sigma_N / k =
        // 0.64 < 1 (sliding); blend 0.5: tau / k = 1 - 0.5 (1 - 0.64) = 0.82.
        let hf = HybridFriction { mu0: 0.8, v0: 2.0, blend: 0.5 };
        assert!(close(hf.target(400e6, 480e6, 1.0), 0.82 * 400e6, 1e-12));
        // Tresca-bound (mu sigma_N >= k): tau = k whatever the blend.
        assert!(close(hf.target(400e6, 4000e6, 1.0), 400e6, 1e-12));
        // Strength 1.5: whole contact, mu lowered by 25 %: 0.4; sigma_N / k = 2: 0.8 (sliding).
        let hf = HybridFriction { blend: 1.5, ..hf };
        assert!(close(hf.target(400e6, 800e6, 1.0), 0.8 * 400e6, 1e-12));
        // eps 2, T 700 degC, Tm 1460 degC: T/Tm = 973.15 / 1733.15 = 0.561492; b 0.4: S = 0.793848;
        // d 1: D = 0.438508; c 6: 1 / (2.793848)^6 = 0.0021017, tanh = 0.0021017;
        // multiplier 0.438508 + 0.561492 * 0.0021017 = 0.439689; s 0.5: 1 - 0.5 * 0.560311 = 0.719844.
        let ts = TanhSoftening { s: 1.0, b: 0.4, c: 6.0, d: 1.0 };
        assert!(close(ts.factor(2.0, 700.0, 1460.0), 0.439_689, 1e-5), "{}", ts.factor(2.0, 700.0, 1460.0));
        assert!(close(TanhSoftening { s: 0.5, ..ts }.factor(2.0, 700.0, 1460.0), 0.719_844, 1e-5));
        // Small strain at room temperature: 1 / (0 + 0.5)^6 = 64, tanh = 1: no softening.
        assert!(close(ts.factor(0.0, 25.0, 1460.0), 1.0, 1e-9));
    }

    #[test]
    fn tool_share_and_effective_rake_by_hand() {
        // K_chip 40, K_tool 50, V_c 1 m/s, l_c 0.4 mm, kappa 1e-5: Pe = 1 * 0.2e-3 / 2e-5 = 10;
        // sqrt(pi (1.42275 + 10)) = 5.99047; 0.946 * 40 * 5.99047 / 100 = 2.26679; share 1 / 3.26679
        // = 0.306111.
        assert!(close(tool_share(40.0, 50.0, 1.0, 0.4e-3, 1e-5), 0.306_111, 1e-5));
        // r 20 um, h 10 um, rake 0: on the arc, cos theta = 0.5, theta 60 deg: -(90 - 30) = -60 deg.
        assert!(close(effective_rake(10e-6, 20e-6, 0.0).to_degrees(), -60.0, 1e-9));
        // h 40 um: x = -20 um, atan(-20 / 40) = -26.5651 deg.
        assert!(close(effective_rake(40e-6, 20e-6, 0.0).to_degrees(), -26.565_05, 1e-6));
        // rake 10 deg: top = 23.4730 um, t = 16.5270 / 0.984808 = 16.7820 um,
        // x = -19.6962 + 2.9142 = -16.7820 um, atan(-16.782 / 40) = -22.7605 deg.
        assert!(close(effective_rake(40e-6, 20e-6, 10f64.to_radians()).to_degrees(), -22.760_48, 1e-5));
        // Sharp tool or r/h -> 0: the nominal rake.
        assert_eq!(effective_rake(40e-6, 0.0, 0.1).to_bits(), 0.1f64.to_bits());
        assert!(close(effective_rake(1.0, 1e-9, 0.1), 0.1, 1e-6));
    }

    #[test]
    fn land_usui_window_and_channel_by_hand() {
        // p0 2, k 400 MPa, x0 50 um, VB 100 um: F_n = 2 * 400e6 * 50e-6 (1 - e^-2) = 34586.59 N/m;
        // mu 0.4 (mu p0 = 0.8 < 1, all sliding): F_f = 0.4 F_n = 13834.64 N/m.
        let (ff, fn_) = land(100e-6, 400e6, 2.0, 0.4, 50e-6);
        assert!(close(fn_, 34_586.59, 1e-6) && close(ff, 13_834.64, 1e-6), "{ff} {fn_}");
        // mu 0.75 (mu p0 = 1.5): sticking to x_s = 50 um * ln 1.5 = 20.273 um; F_f = 400e6 * 20.273e-6
        // + 0.75 * 2 * 400e6 * 50e-6 * (1 / 1.5 - e^-2) = 8109.30 + 15939.94 = 24049.24 N/m.
        assert!(close(land(100e-6, 400e6, 2.0, 0.75, 50e-6).0, 24_049.24, 1e-6));
        // Usui: V 1 and 2 m/s, equal k, T 526.85 and 726.85 degC (800 and 1000 K), lambda 4000 K:
        // increments e^-5 = 0.0067379 and 2 e^-4 = 0.0366313; first test 0.5 * 0.0067379 /
        // (0.0433692 - 0.0183156) = 0.134471, last 1.
        let p = usui_profile(&[1.0, 2.0], &[1.0, 1.0], &[526.85, 726.85], 4000.0);
        assert!(close(p[0], 0.134_471, 1e-5) && close(p[1], 1.0, 1e-12), "{p:?}");
        // BUE window: span 1-4 m/s, quantile 0.5: V_q = 2 m/s; h 0.1 mm: V_p = 2; w 0.5: at V = 2, 1;
        // at V = 4, exp(-(ln 2)^2 / 0.5) = 0.382546; h 0.2 mm, e 0.5: V_p = 1.41421, at V = 2
        // exp(-(0.346574)^2 / 0.5) = 0.786450.
        let mut sd = ShapeD::draw(&mut rand::SeedableRng::seed_from_u64(1));
        sd.bue = [0.5, 0.5, 0.5, 20e-6];
        assert!(close(bue_window(&sd, 2.0, 0.1e-3, (1.0, 4.0)), 1.0, 1e-12));
        assert!(close(bue_window(&sd, 4.0, 0.1e-3, (1.0, 4.0)), 0.382_546, 1e-5));
        assert!(close(bue_window(&sd, 2.0, 0.2e-3, (1.0, 4.0)), 0.786_450, 1e-5));
        // Channel: theta 0.1 rad, leakage 0.5, Fc 1000, Ft 500: Fc' = 995.004 + 49.917 + 25 = 1069.921,
        // Ft' = -99.833 + 497.502 = 397.669.
        sd.xt = [1.0, 0.5];
        let (fc, ft) = channel(0.1, &sd, 1000.0, 500.0);
        assert!(close(fc, 1069.921, 1e-6) && close(ft, 397.669, 1e-5), "{fc} {ft}");
    }

    #[test]
    fn every_hook_vanishes_at_strength_zero_and_acts_above_it() {
        let k = Consts::nominal(&MATERIALS[0]);
        let sd = ShapeD::draw(&mut rand::SeedableRng::seed_from_u64(3));
        let c = Cond { v: 150.0 / 60.0, h: 0.08e-3, w: 2e-3, rake: 5f64.to_radians() };
        let base = oxley::solve_near(&c, &k, &Mods::none(), None).unwrap();
        let plain = |s: &Solution| [s.fc, s.ft, s.tc, s.t_int];
        let off = plain(&oxley::solve_near(&c, &k, &Mods::none(), Some(base.phi)).unwrap());
        let span = (1.0, 3.0);
        for id in MECHANISMS {
            let y0 = truth_row(id, 0.0, &sd, &c, &k, &base, 1.0, span, &plain).unwrap();
            assert!(y0.iter().zip(&off).all(|(a, b)| a.to_bits() == b.to_bits()), "{id}: {y0:?} vs {off:?}");
            let hi = strength_range(id).1;
            let y1 = truth_row(id, 0.5 * hi, &sd, &c, &k, &base, 1.0, span, &plain).unwrap();
            let moved = y1.iter().zip(&off).map(|(a, b)| (a / b).ln().abs()).fold(0.0, f64::max);
            assert!(moved > 0.005, "{id}: {y1:?} vs {off:?}");
        }
    }

    #[test]
    fn family_d_generates_and_hits_its_targets() {
        let p = std::path::Path::new("t.csv");
        for (i, hidden) in MECHANISMS.iter().chain(["null", "decoy:drift"].iter()).enumerate() {
            let d = dataset::generate(Family::D, i, hidden, 0, 5, None, crate::concealed::NuisanceScope::Full).unwrap();
            let tests = cutcal_io::tests_csv::parse_tests(p, &d.recordings).unwrap();
            assert_eq!(tests.len(), d.truth.conditions);
            assert!(d.truth.shape_d.is_some() && d.truth.family == "d");
            if let Some(target) = d.truth.target_enr {
                assert!(d.truth.at_bound || (d.truth.enr / target).ln().abs() < 0.1, "{hidden}: {}", d.truth.enr);
            }
        }
    }
}
