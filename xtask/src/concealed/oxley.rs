//! Family `a` of the generator: Oxley's machining theory (Oxley 1989, *Mechanics of Machining*,
//! Ch. 4-5) with a Johnson-Cook flow stress, written from the equations as listed by Lalwani, Mehta
//! & Jain 2009 (J. Mater. Process. Technol. 209, 5305-5312, Sec. 2). Own code and own solver:
//!
//! - primary zone AB: l_AB = h / sin(phi), V_s = V cos(a) / cos(phi - a), gamma_AB =
//!   cos(a) / (2 sin(phi) cos(phi - a)), eps_AB = gamma_AB / sqrt3, epsdot_AB = C0 V_s / (sqrt3 l_AB);
//!   T_AB = T_w + eta dT_SZ, dT_SZ = (1 - beta) F_s cos(a) / (rho S h cos(phi - a)) (fixed point in T_AB);
//!   Boothroyd partition beta = 0.5 - 0.35 log10(R_T tan phi) (R_T tan phi <= 10), else
//!   0.3 - 0.15 log10(R_T tan phi), R_T = rho S V h / K;
//! - tan(theta) = 1 + 2 (pi/4 - phi) - C0 n_eq; lambda = theta - phi + a; R = F_s / cos(theta);
//!   Fc = R cos(lambda - a), Ft = R sin(lambda - a); t_c = h cos(phi - a) / sin(phi);
//! - contact length l_c = h sin(theta) / (cos(lambda) sin(phi)) (1 + C0 n_eq / (3 (1 + 2 (pi/4 - phi) - C0 n_eq)));
//! - interface: tau_int = F / l_c, sigma_N = N / l_c; T_int = T_w + dT_SZ + psi dT_M,
//!   dT_M = dT_C 10^(0.06 - 0.195 delta sqrt(R_T t_c / l_c) + 0.5 log10(R_T t_c / l_c)),
//!   dT_C = F sin(phi) / (rho S h cos(phi - a)); k_chip from JC at eps_int = (2 gamma_AB +
//!   0.5 l_c / (delta t_c)) / sqrt3, epsdot_int = V_c / (sqrt3 delta t_c), T_int;
//! - closure: phi such that tau_int = k_chip (times the generator's Zorev factor when the friction
//!   mechanism is on); C0 such that sigma'_N = k_AB (1 + pi/2 - 2a - 2 C0 n_eq) equals sigma_N;
//!   delta minimising Fc (Oxley's minimum-work assumption).
//!
//! Family `d` uses this solver unchanged; its mechanisms enter through neutral hooks of [`Mods`]
//! (`primary_mult`, `tanh_softening`, `partition_d`, `hybrid_friction`; `forms_d.rs`), which leave
//! family a's arithmetic bit-identical when off.
//!
//! Search ranges C0 in [2, 10], phi in [5, 45] deg, delta in [0.005, 0.2] (Lalwani's ranges, phi
//! widened). Every loop is capped; a condition with no root is an error, never a silent value.

use std::f64::consts::{FRAC_PI_4, PI};

use super::energy::weiner_beta;
use super::forms_d;
use super::material::{Cond, Consts, Solution};
use super::mechanism::Mods;

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// Boothroyd (1963) partition of the shear-zone heat into the work, as used by Oxley 1989.
pub fn boothroyd_beta(rt_tan_phi: f64) -> f64 {
    let x = rt_tan_phi.max(1e-6);
    let b = if x <= 10.0 { 0.5 - 0.35 * x.log10() } else { 0.3 - 0.15 * x.log10() };
    b.clamp(0.0, 1.0)
}

/// Loewen & Shaw (1954) share of the shear-plane heat that goes to the chip,
/// R1 = 1 / (1 + 1.328 sqrt(kappa gamma / (V h))).
pub fn loewen_shaw_r1(kappa: f64, gamma: f64, v: f64, h: f64) -> f64 {
    1.0 / (1.0 + 1.328 * (kappa * gamma / (v * h)).sqrt())
}

/// Loewen & Shaw (1954) share R2 of the tool-chip frictional heat flux q (W/m^2) that goes into the
/// chip, equating the mean interface temperature of the moving chip (Jaeger 1942 band source of
/// half-length l = l_c / 2: rise 0.754 q l / (K sqrt(L)), L = V_c l / (2 kappa)) and of the stationary
/// tool (uniform disc of the contact area l_c w: mean rise 8 q a / (3 pi K_tool); Carslaw & Jaeger
/// 1959); the chip arrives `dt_chip` above the tool. Returns (R2, chip-side rise at R2 = 1).
#[allow(clippy::too_many_arguments)]
pub fn loewen_shaw_r2(
    q: f64,
    l_c: f64,
    w: f64,
    vc: f64,
    k_chip: f64,
    kappa: f64,
    k_tool: f64,
    dt_chip: f64,
) -> (f64, f64) {
    let l_half = 0.5 * l_c;
    let peclet = (vc * l_half / (2.0 * kappa)).max(1.0);
    let rise_chip = 0.754 * q * l_half / (k_chip * peclet.sqrt());
    let a_eq = (l_c * w / PI).sqrt();
    let rise_tool = 8.0 * q * a_eq / (3.0 * PI * k_tool);
    (((rise_tool - dt_chip) / (rise_chip + rise_tool)).clamp(0.0, 1.0), rise_chip)
}

/// The state at a trial (phi, C0, delta).
#[derive(Debug, Clone, Copy)]
pub struct State {
    /// The outputs.
    pub sol: Solution,
    /// tau_int - target interface shear stress, Pa (phi closure).
    pub friction_gap: f64,
    /// sigma'_N - sigma_N, Pa (C0 closure).
    pub normal_gap: f64,
}

/// Evaluates Oxley's equations at a trial (phi, C0, delta); `None` when the geometry is impossible.
pub fn state(c: &Cond, k: &Consts, mods: &Mods, phi: f64, c0: f64, delta: f64) -> Option<State> {
    let a = c.rake + mods.rake_shift;
    if phi <= 0.0 || phi - a >= PI / 2.0 {
        return None;
    }
    let cpa = (phi - a).cos();
    let l_ab = c.h / phi.sin();
    let vs = c.v * a.cos() / cpa;
    let vc = c.v * phi.sin() / cpa;
    let gamma_ab = a.cos() / (2.0 * phi.sin() * cpa);
    let eps_ab = gamma_ab / SQRT3;
    let epsdot_ab = c0 * vs / (SQRT3 * l_ab);
    let flow = |eps: f64, rate: f64, t: f64| {
        let sigma = k.jc.stress(eps, rate, t, mods.exp_softening) * mods.flow_mult;
        // Family d's thermal-softening hook (neutral when `None`).
        mods.tanh_softening.map_or(sigma, |ts| sigma * ts.factor(eps, t, k.jc.tm))
    };
    // T_AB fixed point (F_s depends on k_AB(T_AB)); damped, capped at 100 steps.
    let mut t_ab = k.t_work + 200.0;
    let (mut k_ab, mut dt_sz) = (0.0, 0.0);
    for _ in 0..100 {
        // `primary_mult`: family d's size-effect hook on the primary zone only (1 = neutral, exact).
        k_ab = flow(eps_ab, epsdot_ab, t_ab) / SQRT3 * mods.primary_mult;
        let fs = k_ab * l_ab;
        let s = k.cp_at(t_ab);
        let rt = k.rho * s * c.v * c.h / k.k_at(t_ab);
        let beta_b = boothroyd_beta(rt * phi.tan());
        let beta = if mods.partition_blend > 0.0 {
            let kappa = k.k_at(t_ab) / (k.rho * s);
            let beta_ls = 1.0 - loewen_shaw_r1(kappa, 2.0 * gamma_ab, c.v, c.h);
            (beta_b + mods.partition_blend * (beta_ls - beta_b)).clamp(0.0, 0.95)
        } else if mods.partition_d > 0.0 {
            // Family d: blend towards Weiner's (1955) shear-plane partition.
            (beta_b + mods.partition_d * (weiner_beta(rt * phi.tan()) - beta_b)).clamp(0.0, 0.95)
        } else {
            beta_b
        };
        dt_sz = (1.0 - beta) * fs * a.cos() / (k.rho * s * c.h * cpa);
        let next = k.t_work + k.eta * dt_sz;
        let step = next - t_ab;
        t_ab += 0.7 * step;
        if step.abs() < 0.01 {
            break;
        }
    }
    let n_eq = k.jc.n_eq(eps_ab);
    let fs = k_ab * l_ab;
    let q = 1.0 + 2.0 * (FRAC_PI_4 - phi) - c0 * n_eq;
    if q <= 0.0 {
        return None;
    }
    let theta = q.atan();
    let lambda = theta - phi + a;
    if lambda <= 0.0 || lambda >= PI / 2.0 {
        return None;
    }
    let r = fs / theta.cos();
    let (fc, ft) = (r * (lambda - a).cos(), r * (lambda - a).sin());
    let (f, n) = (r * lambda.sin(), r * lambda.cos());
    let tc = c.h * cpa / phi.sin();
    let l_c = c.h * theta.sin() / (lambda.cos() * phi.sin()) * (1.0 + c0 * n_eq / (3.0 * q));
    let tau_int = f / l_c;
    let sigma_n = n / l_c;
    let sigma_n_b = k_ab * (1.0 + PI / 2.0 - 2.0 * a - 2.0 * c0 * n_eq);
    // Interface temperature (Oxley 1989 Eq 5.x as in Lalwani 2009), properties at T_AB.
    let s = k.cp_at(t_ab);
    let rt = k.rho * s * c.v * c.h / k.k_at(t_ab);
    let dt_c = f * phi.sin() / (k.rho * s * c.h * cpa);
    let x = rt * tc / l_c;
    let mut dt_m = dt_c * 10f64.powf(0.06 - 0.195 * delta * x.sqrt() + 0.5 * x.log10());
    if mods.partition_blend > 0.0 {
        // Heat-partition mechanism, interface: Oxley puts all frictional heat into the chip; the
        // truth gives the tool its Loewen-Shaw share 1 - R2.
        let q_flux = f * vc / l_c;
        let (r2, _) = loewen_shaw_r2(q_flux, l_c, c.w, vc, k.k_at(t_ab), k.k_at(t_ab) / (k.rho * s), k.k_tool, dt_sz);
        dt_m *= 1.0 - mods.partition_blend.min(1.0) * (1.0 - r2);
    }
    if mods.partition_d > 0.0 {
        // Family d, interface: the tool takes its Péclet-dependent share of the frictional heat.
        let kappa = k.k_at(t_ab) / (k.rho * s);
        dt_m *= 1.0 - mods.partition_d.min(1.0) * forms_d::tool_share(k.k_at(t_ab), k.k_tool, vc, l_c, kappa);
    }
    let t_int = k.t_work + dt_sz + k.psi * dt_m;
    let eps_int = (2.0 * gamma_ab + 0.5 * l_c / (delta * tc)) / SQRT3;
    let epsdot_int = vc / (SQRT3 * delta * tc);
    let k_chip = flow(eps_int, epsdot_int, t_int) / SQRT3;
    // Friction mechanism: Zorev's mean shear over k_chip instead of full sticking, blended in by
    // its strength (`Mods::friction_blend`).
    // Family d: the hybrid Coulomb-Tresca law with speed-dependent mu (`forms_d::HybridFriction`).
    let target = match (mods.friction, mods.hybrid_friction) {
        (Some(z), _) => k_chip * (1.0 - mods.friction_blend * (1.0 - z.factor(sigma_n / k_chip, vc))),
        (None, Some(hf)) => hf.target(k_chip, sigma_n, vc),
        (None, None) => k_chip,
    };
    let sol = Solution { fc, ft, tc, t_int, t_ab, k_ab, phi };
    Some(State { sol, friction_gap: tau_int - target, normal_gap: sigma_n_b - sigma_n })
}

/// Root of `g` on [lo, hi] by a coarse scan and bisection; capped. Without a `hint` the first sign
/// change is taken; with one, the sign change nearest to it (continuation on one solution branch).
fn root(lo: f64, hi: f64, steps: usize, hint: Option<f64>, mut g: impl FnMut(f64) -> Option<f64>) -> Option<f64> {
    let mut prev: Option<(f64, f64)> = None;
    let mut chosen: Option<(f64, f64, f64)> = None;
    for i in 0..=steps {
        let x = lo + (hi - lo) * i as f64 / steps as f64;
        let Some(y) = g(x) else { continue };
        if let Some((xp, yp)) = prev {
            if yp.signum() != y.signum() {
                let nearer =
                    |h: f64| chosen.is_some_and(|(a, b, _)| (0.5 * (xp + x) - h).abs() < (0.5 * (a + b) - h).abs());
                if chosen.is_none() || hint.is_some_and(nearer) {
                    chosen = Some((xp, x, yp));
                }
                if hint.is_none() {
                    break;
                }
            }
        }
        prev = Some((x, y));
    }
    let (mut a, mut b, mut ya) = chosen?;
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        let Some(ym) = g(m) else { return Some(m) };
        if ym.signum() == ya.signum() {
            a = m;
            ya = ym;
        } else {
            b = m;
        }
        if b - a < 1e-7 * (1.0 + b.abs()) {
            break;
        }
    }
    Some(0.5 * (a + b))
}

/// phi solving tau_int = k_chip at (C0, delta).
fn solve_phi(c: &Cond, k: &Consts, mods: &Mods, c0: f64, delta: f64, hint: Option<f64>) -> Option<State> {
    let phi = root(5f64.to_radians(), 45f64.to_radians(), 16, hint, |p| {
        state(c, k, mods, p, c0, delta).map(|s| s.friction_gap)
    })?;
    state(c, k, mods, phi, c0, delta)
}

/// The first sign change of `g` on [lo, hi] (coarse scan of `steps`) across which `g` is
/// continuous, refined by bisection; capped. A sign change where `g` jumps (both ends still far from
/// 0 once the bracket has shrunk to nothing) is a switch between solution branches of an inner
/// closure, not a root, and is skipped.
fn continuous_root(lo: f64, hi: f64, steps: usize, mut g: impl FnMut(f64) -> Option<f64>) -> Option<f64> {
    let pts: Vec<(f64, f64)> = (0..=steps)
        .filter_map(|i| {
            let x = lo + (hi - lo) * i as f64 / steps as f64;
            g(x).map(|y| (x, y))
        })
        .collect();
    for w in pts.windows(2) {
        let ((mut a, mut ya), (mut b, mut yb)) = (w[0], w[1]);
        if ya.signum() == yb.signum() {
            continue;
        }
        let scale = ya.abs().max(yb.abs());
        let mut failed = false;
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            let Some(ym) = g(m) else {
                failed = true;
                break;
            };
            if ym.signum() == ya.signum() {
                a = m;
                ya = ym;
            } else {
                b = m;
                yb = ym;
            }
            if b - a < 1e-7 * (1.0 + b.abs()) {
                break;
            }
        }
        if !failed && ya.abs().min(yb.abs()) <= 1e-3 * scale {
            return Some(0.5 * (a + b));
        }
    }
    None
}

/// C0 solving sigma'_N = sigma_N at delta (or, with no sign change across which the gap is
/// continuous, the C0 nearest to it).
fn solve_c0(c: &Cond, k: &Consts, mods: &Mods, delta: f64, hint: Option<f64>) -> Option<State> {
    let gap = |c0: f64| solve_phi(c, k, mods, c0, delta, hint).map(|s| s.normal_gap);
    if let Some(c0) = continuous_root(2.0, 10.0, 8, gap) {
        return solve_phi(c, k, mods, c0, delta, hint);
    }
    let mut best: Option<State> = None;
    for i in 0..=8 {
        let c0 = 2.0 + i as f64;
        if let Some(s) = solve_phi(c, k, mods, c0, delta, hint) {
            if best.map(|b| s.normal_gap.abs() < b.normal_gap.abs()).unwrap_or(true) {
                best = Some(s);
            }
        }
    }
    best
}

/// Solves one condition: delta minimising Fc (golden section in ln delta over [0.005, 0.2] after a
/// coarse scan), C0 and phi by their closures. Without `phi_hint` the first shear-angle root above
/// 5 deg is taken; with one (rad), the root nearest it: where the closure tau_int = k_chip has
/// several roots (at low speed it can), a hidden mechanism is solved from the mechanism-free
/// solution's shear angle, so that its effect is the continuous change of one solution and never a
/// jump to another branch.
pub fn solve_near(c: &Cond, k: &Consts, mods: &Mods, phi_hint: Option<f64>) -> Result<Solution, String> {
    let fc_at = |ld: f64| solve_c0(c, k, mods, ld.exp(), phi_hint);
    let (lo, hi) = (0.005f64.ln(), 0.2f64.ln());
    let scan: Vec<(f64, Option<State>)> =
        (0..=6).map(|i| lo + (hi - lo) * i as f64 / 6.0).map(|x| (x, fc_at(x))).collect();
    let fc = |s: &Option<State>| s.map_or(f64::INFINITY, |s| s.sol.fc);
    let (ib, _) = scan.iter().enumerate().min_by(|a, b| fc(&a.1 .1).total_cmp(&fc(&b.1 .1))).ok_or("no delta")?;
    if !fc(&scan[ib].1).is_finite() {
        return Err(format!(
            "Oxley: no shear-angle root at V {:.0} m/min, h {:.3} mm, rake {:.1} deg",
            c.v * 60.0,
            c.h * 1e3,
            c.rake.to_degrees()
        ));
    }
    let (mut a, mut b) = (scan[ib.saturating_sub(1)].0, scan[(ib + 1).min(6)].0);
    let g = 0.618_033_988_749_895;
    let mut best = scan[ib].1;
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut s1, mut s2) = (fc_at(x1), fc_at(x2));
    for _ in 0..12 {
        for s in [s1, s2] {
            if fc(&s) < fc(&best) {
                best = s;
            }
        }
        if fc(&s1) < fc(&s2) {
            b = x2;
            x2 = x1;
            s2 = s1;
            x1 = b - g * (b - a);
            s1 = fc_at(x1);
        } else {
            a = x1;
            x1 = x2;
            s1 = s2;
            x2 = a + g * (b - a);
            s2 = fc_at(x2);
        }
    }
    for s in [s1, s2] {
        if fc(&s) < fc(&best) {
            best = s;
        }
    }
    let sol = best.ok_or("Oxley: no solution")?.sol;
    if sol.is_sane(c.h) {
        Ok(sol)
    } else {
        Err(format!("Oxley: non-physical solution at V {:.0} m/min, h {:.3} mm", c.v * 60.0, c.h * 1e3))
    }
}

#[cfg(test)]
mod tests {
    use super::super::material::{Consts, MATERIALS};
    use super::*;

    #[test]
    fn boothroyd_and_loewen_shaw_by_hand() {
        // R_T tan(phi) = 1: 0.5; = 100: 0.3 - 0.15 * 2 = 0.0 ... = 20: 0.3 - 0.15 log10 20 = 0.10485.
        assert!((boothroyd_beta(1.0) - 0.5).abs() < 1e-12);
        assert!((boothroyd_beta(20.0) - 0.104_845).abs() < 1e-5);
        // kappa 1.3e-5, gamma 2.5, V 3, h 1e-4: 1 / (1 + 1.328 sqrt(0.108333)) = 0.69583.
        assert!((loewen_shaw_r1(1.3e-5, 2.5, 3.0, 1e-4) - 0.695_83).abs() < 1e-4);
    }

    #[test]
    fn root_takes_the_first_sign_change_or_the_one_nearest_the_hint() {
        // (x - 1)(x - 2)(x - 3) on [0, 4] has roots 1, 2 and 3.
        let g = |x: f64| Some((x - 1.0) * (x - 2.0) * (x - 3.0));
        let first = root(0.0, 4.0, 16, None, g).unwrap();
        assert!((first - 1.0).abs() < 1e-6, "{first}");
        let near = root(0.0, 4.0, 16, Some(2.9), g).unwrap();
        assert!((near - 3.0).abs() < 1e-6, "{near}");
        let mid = root(0.0, 4.0, 16, Some(2.2), g).unwrap();
        assert!((mid - 2.0).abs() < 1e-6, "{mid}");
    }

    #[test]
    fn a_jump_across_zero_is_not_taken_for_a_root() {
        // g jumps from -1 to +1 at x = 1 (a branch switch) and crosses 0 continuously at x = 3.
        let g = |x: f64| {
            Some(if x < 1.0 {
                -1.0
            } else if x < 2.0 {
                1.0
            } else {
                2.0 - (x - 2.0) * 2.0
            })
        };
        // On [0, 4] with 8 steps: the first sign change is the jump (0.5 -> 1.0), skipped; then g
        // goes 1, 2, ..., and crosses 0 at x = 3.
        let r = continuous_root(0.0, 4.0, 8, g).unwrap();
        assert!((r - 3.0).abs() < 1e-6, "{r}");
        // Only a jump: no root.
        assert!(continuous_root(0.0, 2.0, 8, |x: f64| Some(if x < 1.0 { -1.0 } else { 1.0 })).is_none());
    }

    #[test]
    fn lalwani_2009_aisi1045_case_1() {
        // Lalwani et al. 2009 (their prediction for Ivester case 1): V 200 m/min, h 0.15 mm, rake -7 deg,
        // w 1.6 mm: Fc 576 N, Ft 364 N, t_c 0.43 mm, T_AB 385 degC, T_int 942 degC (delta 0.040, C0 5.8).
        let k = Consts::nominal(&MATERIALS[0]);
        let c = Cond { v: 200.0 / 60.0, h: 0.15e-3, w: 1.6e-3, rake: (-7f64).to_radians() };
        let s = solve_near(&c, &k, &Mods::none(), None).unwrap();
        let (fc, ft) = (s.fc * c.w, s.ft * c.w);
        assert!((fc / 576.0 - 1.0).abs() < 0.06, "Fc {fc} N vs 576");
        assert!((ft / 364.0 - 1.0).abs() < 0.15, "Ft {ft} N vs 364");
        assert!((s.tc * 1e3 / 0.43 - 1.0).abs() < 0.08, "tc {} mm vs 0.43", s.tc * 1e3);
        assert!((s.t_ab - 385.0).abs() < 40.0, "T_AB {} vs 385", s.t_ab);
        assert!((s.t_int - 942.0).abs() < 90.0, "T_int {} vs 942", s.t_int);
    }
}
