//! Family `b` of the generator (never tuned on): a shear-plane model with a Merchant-type
//! shear-angle closure, a Zorev stick-slip tool-chip contact and Loewen-Shaw temperatures, with a
//! Johnson-Cook flow stress. It shares no equation of its closure with family `a`:
//!
//! - shear angle: Merchant's generalised relation 2 phi + lambda - a = C_M (Merchant 1945,
//!   J. Appl. Phys. 16, 267-275 and 318-324), C_M = 75 deg for steels (between Merchant's 90 deg
//!   and Lee & Shaffer's 1951 relation phi + lambda - a = 45 deg);
//! - primary zone: thin zone of thickness Delta = 25 um (h / 0.1 mm)^0.5 (a thickness growing with
//!   h, cf. Tounsi et al. 2002, Int. J. Mach. Tools Manuf. 42, 1373-1383): gamma =
//!   cos(a) / (sin(phi) cos(phi - a)), eps = gamma / sqrt3 (exit strain), epsdot = V_s / (sqrt3 Delta);
//!   tau_s = JC(eps, epsdot, T_s) / sqrt3; F_s = tau_s h / sin(phi); R = F_s / cos(phi + lambda - a);
//!   Fc = R cos(lambda - a), Ft = R sin(lambda - a);
//! - shear-plane temperature: Loewen & Shaw 1954 (Trans. ASME 76, 217-231): dT_s = R1 tau_s gamma /
//!   (rho c), R1 = 1 / (1 + 1.328 sqrt(kappa gamma / (V h))); T_s = T_w + eta dT_s (eta as Oxley's);
//! - contact length: Poletika's l_c = h zeta^1.5, zeta = t_c / h (as quoted by Astakhov 1999,
//!   *Metal Cutting Mechanics*);
//! - friction: Zorev 1963 stick-slip (mu 0.6, a = 3; `mechanism::Zorev`), F = zeta_Z k_chip l_c,
//!   lambda = atan(F / N) solved by scan + bisection; chip flow stress at eps_c = eps + l_c / (2 sqrt3
//!   delta_s), epsdot_c = V_c / (sqrt3 delta_s), delta_s = 0.05 t_c, T_int;
//! - interface temperature: Loewen & Shaw 1954 partition R2 of the frictional heat q = F V_c / l_c
//!   between the moving chip (Jaeger 1942 band source, mean rise 0.754 q l / (K sqrt(L)), l = l_c / 2,
//!   L = V_c l / (2 kappa)) and the stationary tool (uniform disc of the contact's area, mean rise
//!   8 q a / (3 pi K_tool); Carslaw & Jaeger 1959); T_int = T_w + dT_s + psi R2 dT_chip; fixed point
//!   in T_int, capped.

use super::material::{Cond, Consts, Solution};
use super::mechanism::{Mods, FAMILY_B_FRICTION};
use super::oxley::{boothroyd_beta, loewen_shaw_r1, loewen_shaw_r2};

const SQRT3: f64 = 1.732_050_807_568_877_2;
/// Merchant's constant C_M, rad.
const C_MERCHANT_DEG: f64 = 75.0;

struct Eval {
    gap: f64,
    sol: Solution,
    t_int_new: f64,
}

fn eval(c: &Cond, k: &Consts, mods: &Mods, lambda: f64, t_int: f64) -> Option<Eval> {
    let a = c.rake + mods.rake_shift;
    let phi = 0.5 * (C_MERCHANT_DEG.to_radians() - lambda + a);
    if !(2f64.to_radians()..60f64.to_radians()).contains(&phi) {
        return None;
    }
    let cpa = (phi - a).cos();
    let vs = c.v * a.cos() / cpa;
    let vc = c.v * phi.sin() / cpa;
    let gamma = a.cos() / (phi.sin() * cpa);
    let eps = gamma / SQRT3;
    let thick = 25e-6 * (c.h / 0.1e-3).sqrt();
    let epsdot = vs / (SQRT3 * thick);
    let flow = |e: f64, r: f64, t: f64| k.jc.stress(e, r, t, mods.exp_softening) * mods.flow_mult;
    let (mut t_s, mut tau_s, mut dt_s) = (k.t_work + 200.0, 0.0, 0.0);
    for _ in 0..100 {
        tau_s = flow(eps, epsdot, t_s) / SQRT3;
        let rc = k.rho * k.cp_at(t_s);
        let kappa = k.k_at(t_s) / rc;
        let r1_ls = loewen_shaw_r1(kappa, gamma, c.v, c.h);
        let r1 = if mods.partition_blend > 0.0 {
            let rt = rc * c.v * c.h / k.k_at(t_s);
            let r1_b = 1.0 - boothroyd_beta(rt * phi.tan());
            (r1_ls + mods.partition_blend * (r1_b - r1_ls)).clamp(0.05, 1.0)
        } else {
            r1_ls
        };
        dt_s = r1 * tau_s * gamma / rc;
        let next = k.t_work + k.eta * dt_s;
        let step = next - t_s;
        t_s += 0.7 * step;
        if step.abs() < 0.01 {
            break;
        }
    }
    let fs = tau_s * c.h / phi.sin();
    let r = fs / (phi + lambda - a).cos();
    let (fc, ft) = (r * (lambda - a).cos(), r * (lambda - a).sin());
    let n = r * lambda.cos();
    let tc = c.h * cpa / phi.sin();
    let l_c = c.h * (tc / c.h).powf(1.5);
    let sigma_n = n / l_c;
    let delta_s = 0.05 * tc;
    let eps_c = eps + l_c / (2.0 * SQRT3 * delta_s);
    let epsdot_c = vc / (SQRT3 * delta_s);
    let k_chip = flow(eps_c, epsdot_c, t_int) / SQRT3;
    let law = mods.friction.unwrap_or(FAMILY_B_FRICTION);
    let f = law.factor(sigma_n / k_chip, vc) * k_chip * l_c;
    let gap = (f / n).atan() - lambda;
    // Loewen-Shaw interface temperature.
    let t_chip = k.t_work + dt_s;
    let q = f * vc / l_c;
    let kc = k.k_at(t_chip);
    let kappa_c = kc / (k.rho * k.cp_at(t_chip));
    let (r2_ls, rise_chip) = loewen_shaw_r2(q, l_c, c.w, vc, kc, kappa_c, k.k_tool, dt_s);
    // Heat-partition mechanism, interface: towards Oxley/Boothroyd's "all frictional heat to the chip".
    let r2 = r2_ls + mods.partition_blend.min(1.0) * (1.0 - r2_ls);
    let t_int_new = t_chip + k.psi * r2 * rise_chip;
    let sol = Solution { fc, ft, tc, t_int: t_int_new, t_ab: t_s, k_ab: tau_s, phi };
    Some(Eval { gap, sol, t_int_new })
}

/// Solves one condition with family b.
pub fn solve(c: &Cond, k: &Consts, mods: &Mods) -> Result<Solution, String> {
    let err = |what: &str| {
        format!(
            "family b: {what} at V {:.0} m/min, h {:.3} mm, rake {:.1} deg",
            c.v * 60.0,
            c.h * 1e3,
            c.rake.to_degrees()
        )
    };
    let mut t_int = k.t_work + 500.0;
    for _ in 0..200 {
        let g = |l: f64| eval(c, k, mods, l, t_int).map(|e| e.gap);
        let lambda =
            root(0.5f64.to_radians(), 60f64.to_radians(), 30, g).ok_or_else(|| err("no friction-angle root"))?;
        let e = eval(c, k, mods, lambda, t_int).ok_or_else(|| err("no state"))?;
        let step = e.t_int_new - t_int;
        if step.abs() < 0.02 {
            return if e.sol.is_sane(c.h) { Ok(e.sol) } else { Err(err("non-physical solution")) };
        }
        t_int += 0.5 * step;
    }
    Err(err("interface temperature did not converge in 200 steps"))
}

fn root(lo: f64, hi: f64, steps: usize, g: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let mut prev: Option<(f64, f64)> = None;
    for i in 0..=steps {
        let x = lo + (hi - lo) * i as f64 / steps as f64;
        let Some(y) = g(x) else { continue };
        if let Some((xp, yp)) = prev {
            if yp.signum() != y.signum() {
                let (mut a, mut b, mut ya) = (xp, x, yp);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    let Some(ym) = g(m) else { break };
                    if ym.signum() == ya.signum() {
                        a = m;
                        ya = ym;
                    } else {
                        b = m;
                    }
                    if b - a < 1e-9 {
                        break;
                    }
                }
                return Some(0.5 * (a + b));
            }
        }
        prev = Some((x, y));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::super::material::{Consts, MATERIALS};
    use super::*;

    #[test]
    fn family_b_is_physical_over_the_steel_range() {
        for mat in &MATERIALS[..2] {
            let k = Consts::nominal(mat);
            for v in [30.0, 100.0, 400.0] {
                for h in [0.03e-3, 0.1e-3, 0.3e-3] {
                    for rake in [-5.0f64, 0.0, 10.0] {
                        let c = Cond { v: v / 60.0, h, w: 2e-3, rake: rake.to_radians() };
                        let s = solve(&c, &k, &Mods::none()).unwrap();
                        let ratio = s.tc / h;
                        // Specific cutting force 1.5-6 GPa, chip ratio 1.2-5, Ft/Fc 0.2-1.2, T_int 150-1300 degC.
                        let kc = s.fc / h / 1e9;
                        assert!((1.2..6.0).contains(&kc), "{} {v} {h} {rake}: kc {kc}", mat.name);
                        assert!((1.1..5.0).contains(&ratio), "{} {v} {h} {rake}: ratio {ratio}", mat.name);
                        assert!(
                            (0.1..1.2).contains(&(s.ft / s.fc)),
                            "{} {v} {h} {rake}: Ft/Fc {}",
                            mat.name,
                            s.ft / s.fc
                        );
                        assert!((150.0..1300.0).contains(&s.t_int), "{} {v} {h} {rake}: T_int {}", mat.name, s.t_int);
                    }
                }
            }
        }
    }
}
