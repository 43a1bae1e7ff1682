//! Family `c` of the generator (never tuned on): the shear angle from Merchant's minimum-energy
//! principle solved numerically with a strain-, rate- and temperature-dependent flow stress, a
//! primary zone of fixed relative thickness, the hybrid Coulomb-Tresca contact of FE codes, Weiner's
//! shear-plane heat partition and Jaeger's maximum band-source temperature in the chip, with a
//! Johnson-Cook flow stress. It shares no closure with family `a` (Oxley) or `b` (Merchant's
//! generalised relation):
//!
//! - shear angle: phi minimises the cutting force Fc = (cutting power) / V over 5-50 deg (Merchant
//!   1945, J. Appl. Phys. 16, 267-275: the shear angle takes the value that makes the work of cutting
//!   a minimum). As Merchant did, Fc is minimised at the friction angle of the solution; the flow
//!   stress keeps its full dependence on phi (strain, rate, temperature), so the minimum is no longer
//!   2 phi + lambda - a = 90 deg and is found numerically (13-point scan, then at most 60
//!   golden-section steps); lambda is then the root of G(lambda) = lambda, G the contact's friction
//!   angle at that phi (Illinois method, at most 60 steps). Minimising with lambda(phi) inside Fc
//!   would give two near-equal minima, one in the Coulomb and one in the Tresca regime (AISI 1045,
//!   30 m/min, h 0.1 mm, rake -5 deg: 29 and 36 deg), and the nuisance would flip the chip between
//!   them. A minimum within 0.5 deg of either end of the range is a generation failure;
//! - primary zone: parallel-sided, of thickness Delta = l_AB / C0 with l_AB = h / sin(phi) and a fixed
//!   C0 = 6 (Oxley & Welsh 1963, Proc. 4th Int. MTDR Conf., the early constant ratio of shear-plane
//!   length to zone thickness; unlike family a, C0 is not solved from stress equilibrium):
//!   gamma = cos(a) / (sin(phi) cos(phi - a)), exit strain eps = gamma / sqrt3, strain rate
//!   epsdot = V_s / (sqrt3 Delta), V_s = V cos(a) / cos(phi - a); tau_s = JC(eps, epsdot, T_s) / sqrt3;
//!   F_s = tau_s h / sin(phi); R = F_s / cos(phi + lambda - a), N = R cos(lambda), F = R sin(lambda),
//!   Fc = R cos(lambda - a), Ft = R sin(lambda - a) (Merchant's force circle);
//!   t_c = h cos(phi - a) / sin(phi), V_c = V sin(phi) / cos(phi - a);
//! - contact length: l_c = h (zeta (1 - tan a) + sec a), zeta = t_c / h (Klushin 1958, as quoted by
//!   Astakhov 1999, *Metal Cutting Mechanics*, and Astakhov 2006, *Tribology of Metal Cutting*);
//! - contact law: the hybrid Coulomb-Tresca ("shear stress limit") law of FE codes (Abaqus contact
//!   friction with a shear stress limit; DEFORM's hybrid friction), on the mean stresses:
//!   tau = min(mu sigma_N, k_chip), mu = 0.5 (`mechanism::FAMILY_C_MU`), sigma_N = N / l_c, k_chip =
//!   JC(eps, epsdot, T_int) / sqrt3 (the chip's shear flow stress at its exit strain and rate, at the
//!   interface temperature); lambda solves tan(lambda) = tau / sigma_N with the force system above by
//!   a bisection of at most 80 steps;
//! - shear-plane temperature: Weiner 1955 (Trans. ASME 77, 1331-1341): the shear plane a plane heat
//!   source moving through the work with conduction in the direction of motion neglected. Under that
//!   assumption (and the free surface's image neglected) each column of work sees a line source
//!   sweeping its depth h at V tan(phi), and the share of the heat below the cut is, with
//!   S = R_T tan(phi) / 4, R_T = rho c V h / K,
//!   beta = erfc(sqrt S) / 2 + erf(sqrt S) / (4 S) - exp(-S) / (2 sqrt(pi S))
//!   (derived here from Weiner's assumption, [`weiner_beta`]; -> 1/2 as S -> 0, ~ 1 / (4 S) for large
//!   S); dT_s = (1 - beta) tau_s gamma / (rho c), T_s = T_w + eta dT_s (eta as in families a and b),
//!   fixed point capped at 200 steps; erf by Press et al. 1992 (*Numerical Recipes*, Sec. 6.2, erfcc);
//! - interface temperature: ALL frictional heat q = F V_c / l_c into the chip as a Jaeger (1942, Proc.
//!   R. Soc. N.S.W. 76, 203) band source of length l_c moving at V_c over a semi-infinite body, in its
//!   MAXIMUM form at large Peclet number, dT_chip = 2 q sqrt(kappa l_c / (pi V_c)) / K (the surface
//!   rise under a constant flux q after the time l_c / V_c, Carslaw & Jaeger 1959, Sec. 2.9; it is
//!   1.128 q l / (K sqrt L), l = l_c / 2, L = V_c l / (2 kappa), 3/2 of the mean 0.754 q l / (K sqrt L)
//!   family b uses; L is floored at 1); T_int = T_w + dT_s + psi dT_chip (psi as in families a and b;
//!   as Oxley's psi scales a maximum chip temperature rise), properties at T_w + dT_s; T_int by a
//!   bisection of at most 60 steps.
//!
//! Mechanism hooks ([`Mods`]): `flow_mult` and `exp_softening` on every flow stress, `rake_shift` on
//! the rake; `friction` REPLACES the Coulomb-Tresca law by a Zorev stick-slip law (its a = 0 limit is
//! the Coulomb-Tresca law; `mechanism::mods`); `partition_blend` p blends the Weiner partition towards
//! Boothroyd's (1963; `oxley::boothroyd_beta`), beta = beta_W + p (beta_B - beta_W), and gives the
//! tool its Loewen & Shaw (1954) share of the frictional heat, dT_chip times 1 - p (1 - R2)
//! (`oxley::loewen_shaw_r2`); p runs to 2 in family c (`mechanism::strength_range`): beyond 1 the
//! partition moves as far again past Boothroyd's beta and Loewen-Shaw's tool share (beta clamped to
//! [0, 0.95], the chip's share to >= 0): this contact passes the interface temperature to the forces
//! only where the Tresca limit binds. Every loop is capped; a non-convergence or a non-physical state
//! is an `Err` naming the condition, counted as a generation failure.

use std::f64::consts::PI;

use super::material::{Cond, Consts, Solution};
use super::mechanism::{Mods, FAMILY_C_MU};
use super::oxley::{boothroyd_beta, loewen_shaw_r2};

const SQRT3: f64 = 1.732_050_807_568_877_2;
/// Ratio of shear-plane length to primary-zone thickness (Oxley & Welsh 1963).
const C0: f64 = 6.0;
/// Search range of the shear angle, deg.
const PHI_DEG: (f64, f64) = (5.0, 50.0);

/// erfc(x) for x >= 0 (Press et al. 1992, *Numerical Recipes*, Sec. 6.2, `erfcc`: fractional error
/// below 1.2e-7 everywhere; a Chebyshev fit, smooth in x).
fn erfc(x: f64) -> f64 {
    #[rustfmt::skip]
    const C: [f64; 10] = [
        -1.265_512_23, 1.000_023_68, 0.374_091_96, 0.096_784_18, -0.186_288_06,
        0.278_868_07, -1.135_203_98, 1.488_515_87, -0.822_152_23, 0.170_872_77,
    ];
    let t = 1.0 / (1.0 + 0.5 * x.max(0.0));
    t * (-x * x + C.iter().rev().fold(0.0, |acc, c| acc * t + c)).exp()
}

/// Weiner's (1955) share beta of the shear-plane heat that goes into the work, as a function of
/// R_T tan(phi) (module docs).
pub fn weiner_beta(rt_tan_phi: f64) -> f64 {
    let s = 0.25 * rt_tan_phi.max(1e-2);
    let r = s.sqrt();
    let b = 0.5 * erfc(r) + (1.0 - erfc(r)) / (4.0 * s) - (-s).exp() / (2.0 * (PI * s).sqrt());
    b.clamp(0.0, 0.5)
}

/// Mean interface shear stress of the hybrid Coulomb-Tresca law, tau = min(mu sigma_N, k).
pub fn coulomb_tresca(mu: f64, sigma_n: f64, k: f64) -> f64 {
    (mu * sigma_n).min(k)
}

/// Jaeger's maximum surface temperature rise under a band source of flux q (W/m^2) and length l_c
/// moving at v over a semi-infinite body of conductivity `k` and diffusivity `kappa`, at large
/// Peclet number: 2 q sqrt(kappa l_c / (pi v)) / K, with L = v l_c / (4 kappa) floored at 1.
pub fn jaeger_max_rise(q: f64, l_c: f64, v: f64, k: f64, kappa: f64) -> f64 {
    let l = 0.5 * l_c;
    let peclet = (v * l / (2.0 * kappa)).max(1.0);
    2.0 / PI.sqrt() * q * l / (k * peclet.sqrt())
}

/// The primary zone at a trial shear angle (independent of the contact).
struct Primary {
    a: f64,
    vc: f64,
    tc: f64,
    l_c: f64,
    fs: f64,
    tau_s: f64,
    dt_s: f64,
    t_s: f64,
    eps: f64,
    epsdot: f64,
}

impl Primary {
    /// Fc at friction angle `lambda` (Merchant's force circle).
    fn fc(&self, phi: f64, lambda: f64) -> f64 {
        self.fs * (lambda - self.a).cos() / (phi + lambda - self.a).cos()
    }
}

fn primary(c: &Cond, k: &Consts, mods: &Mods, phi: f64) -> Result<Primary, String> {
    let a = c.rake + mods.rake_shift;
    if phi - a >= 0.5 * PI - 1e-3 {
        return Err("phi - a reaches 90 deg".into());
    }
    let cpa = (phi - a).cos();
    let vs = c.v * a.cos() / cpa;
    let gamma = a.cos() / (phi.sin() * cpa);
    let eps = gamma / SQRT3;
    let epsdot = vs / (SQRT3 * c.h / phi.sin() / C0);
    // Shear-plane temperature: damped fixed point in T_s.
    let (mut t_s, mut tau_s, mut dt_s) = (k.t_work + 200.0, 0.0, 0.0);
    for i in 0..=200 {
        if i == 200 {
            return Err("the shear-plane temperature did not converge in 200 steps".into());
        }
        tau_s = k.jc.stress(eps, epsdot, t_s, mods.exp_softening) * mods.flow_mult / SQRT3;
        let rc = k.rho * k.cp_at(t_s);
        let x = rc * c.v * c.h / k.k_at(t_s) * phi.tan();
        let beta_w = weiner_beta(x);
        let beta = (beta_w + mods.partition_blend.min(2.0) * (boothroyd_beta(x) - beta_w)).clamp(0.0, 0.95);
        dt_s = (1.0 - beta) * tau_s * gamma / rc;
        let step = k.t_work + k.eta * dt_s - t_s;
        t_s += 0.7 * step;
        if step.abs() < 1e-12 * (1.0 + t_s.abs()) {
            break;
        }
    }
    let tc = c.h * cpa / phi.sin();
    let l_c = c.h * (tc / c.h * (1.0 - a.tan()) + 1.0 / a.cos());
    if !(tau_s > 0.0 && tau_s.is_finite() && l_c > 0.0) {
        return Err("non-physical primary zone or contact length".into());
    }
    let vc = c.v * phi.sin() / cpa;
    Ok(Primary { a, vc, tc, l_c, fs: tau_s * c.h / phi.sin(), tau_s, dt_s, t_s, eps, epsdot })
}

/// The contact at shear angle `phi`: (lambda, T_int). For a trial T_int, lambda solves
/// tan(lambda) = tau / sigma_N by bisection (tau / sigma_N - tan(lambda) falls from positive at
/// lambda = 0 to negative where cos(phi + lambda - a) -> 0); T_int is the root of
/// T_w + dT_s + psi dT_chip(T_int) - T_int, which falls with T_int (a hotter chip is softer, the
/// frictional heat smaller), by bisection on [T_w + dT_s, T_m + 1000].
fn interface(c: &Cond, k: &Consts, mods: &Mods, p: &Primary, phi: f64) -> Result<(f64, f64), String> {
    let t_chip = k.t_work + p.dt_s;
    let (kc, kappa) = (k.k_at(t_chip), k.k_at(t_chip) / (k.rho * k.cp_at(t_chip)));
    let lam_hi = (0.5 * PI - (phi - p.a)).min(89f64.to_radians()) - 1e-9;
    let at = |t_int: f64| -> Result<(f64, f64), String> {
        let k_chip = k.jc.stress(p.eps, p.epsdot, t_int, mods.exp_softening) * mods.flow_mult / SQRT3;
        let sigma_n = |lam: f64| p.fs * lam.cos() / ((phi + lam - p.a).cos() * p.l_c);
        let gap = |lam: f64| {
            let sn = sigma_n(lam);
            let tau = match mods.friction {
                Some(z) => z.factor(sn / k_chip, p.vc) * k_chip,
                None => coulomb_tresca(FAMILY_C_MU, sn, k_chip),
            };
            tau / sn - lam.tan()
        };
        if !(gap(1e-9) > 0.0 && gap(lam_hi) < 0.0) {
            return Err("no friction angle solves tan(lambda) = tau / sigma_N".into());
        }
        let lambda = bisect(1e-9, lam_hi, 80, 1e-14, |m| Ok(gap(m) > 0.0))?;
        let f = p.fs * lambda.sin() / (phi + lambda - p.a).cos();
        let q = f * p.vc / p.l_c;
        let share = if mods.partition_blend > 0.0 {
            let (r2, _) = loewen_shaw_r2(q, p.l_c, c.w, p.vc, kc, kappa, k.k_tool, p.dt_s);
            (1.0 - mods.partition_blend.min(2.0) * (1.0 - r2)).max(0.0)
        } else {
            1.0
        };
        Ok((lambda, t_chip + k.psi * share * jaeger_max_rise(q, p.l_c, p.vc, kc, kappa) - t_int))
    };
    let (lo, hi) = (t_chip, k.jc.tm + 1000.0);
    if !(at(lo)?.1 >= 0.0 && at(hi)?.1 < 0.0) {
        return Err("no interface temperature in the bracket".into());
    }
    let t_int = bisect(lo, hi, 60, 1e-8, |m| Ok(at(m)?.1 >= 0.0))?;
    Ok((at(t_int)?.0, t_int))
}

/// Bisection on [lo, hi], at most `steps` halvings or until the bracket is below `tol`:
/// `up(m)` says whether the root lies above m. Returns the bracket's midpoint.
fn bisect(
    mut lo: f64,
    mut hi: f64,
    steps: usize,
    tol: f64,
    mut up: impl FnMut(f64) -> Result<bool, String>,
) -> Result<f64, String> {
    for _ in 0..steps {
        let m = 0.5 * (lo + hi);
        if up(m)? {
            lo = m;
        } else {
            hi = m;
        }
        if hi - lo < tol {
            break;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// phi minimising Fc at friction angle `lambda` over the search range: a 13-point scan, then a
/// golden-section search of at most 60 steps around the best point (a minimum at an end of the range
/// is refused by [`solve`] for the final solution only).
fn min_energy_phi(c: &Cond, k: &Consts, mods: &Mods, lambda: f64) -> Result<f64, String> {
    let (lo, hi) = (PHI_DEG.0.to_radians(), PHI_DEG.1.to_radians());
    let fc = |p: f64| primary(c, k, mods, p).map_or(f64::INFINITY, |s| s.fc(p, lambda));
    let n = 12;
    let grid: Vec<(f64, f64)> = (0..=n).map(|i| lo + (hi - lo) * i as f64 / n as f64).map(|p| (p, fc(p))).collect();
    let (ib, best) = grid.iter().enumerate().min_by(|x, y| x.1 .1.total_cmp(&y.1 .1)).ok_or("no phi")?;
    if !best.1.is_finite() {
        return Err(primary(c, k, mods, grid[n / 2].0).err().unwrap_or_else(|| "no state at any phi".into()));
    }
    let (mut a, mut b) = (grid[ib.saturating_sub(1)].0, grid[(ib + 1).min(n)].0);
    let g = 0.618_033_988_749_895;
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (fc(x1), fc(x2));
    for _ in 0..60 {
        if b - a < 1e-11 {
            break;
        }
        if f1 < f2 {
            b = x2;
            (x2, f2) = (x1, f1);
            x1 = b - g * (b - a);
            f1 = fc(x1);
        } else {
            a = x1;
            (x1, f1) = (x2, f2);
            x2 = a + g * (b - a);
            f2 = fc(x2);
        }
    }
    Ok(0.5 * (a + b))
}

/// Solves one condition with family c: lambda is the root of G(lambda) - lambda, G(lambda) the
/// contact's friction angle at the phi minimising Fc at lambda, by the Illinois method (Dowell &
/// Jarratt 1971) on [0.001 rad, atan(mu_max)], mu_max bounding tau / sigma_N; at most 60 steps.
pub fn solve(c: &Cond, k: &Consts, mods: &Mods) -> Result<Solution, String> {
    let err = |what: &str| {
        format!(
            "family c: {what} at V {:.0} m/min, h {:.3} mm, rake {:.1} deg",
            c.v * 60.0,
            c.h * 1e3,
            c.rake.to_degrees()
        )
    };
    let state = |lambda: f64| -> Result<(f64, Primary, f64, f64), String> {
        let phi = min_energy_phi(c, k, mods, lambda)?;
        let p = primary(c, k, mods, phi)?;
        let (lam, t_int) = interface(c, k, mods, &p, phi)?;
        Ok((phi, p, lam, t_int))
    };
    let g = |lambda: f64| state(lambda).map(|s| s.2 - lambda).map_err(|e| err(&e));
    let mu_max = mods.friction.map_or(FAMILY_C_MU, |z| z.mu0 * 0.05f64.powf(-z.q));
    let (mut a, mut b) = (1e-3, mu_max.atan() + 1e-9);
    let (mut ga, mut gb) = (g(a)?, g(b)?);
    if !(ga > 0.0 && gb <= 0.0) {
        return Err(err("no friction angle consistent with the minimum-energy shear angle"));
    }
    let mut side = 0;
    let mut lambda = b;
    for i in 0..=60 {
        if i == 60 {
            return Err(err("the friction angle did not converge in 60 steps"));
        }
        lambda = (a * gb - b * ga) / (gb - ga);
        let gl = g(lambda)?;
        if gl.abs() < 1e-12 || b - a < 1e-12 {
            break;
        }
        if gl > 0.0 {
            (a, ga) = (lambda, gl);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            (b, gb) = (lambda, gl);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    let (phi, p, lam, t_int) = state(lambda).map_err(|e| err(&e))?;
    let (lo, hi) = (PHI_DEG.0 + 0.5, PHI_DEG.1 - 0.5);
    if !(lo..=hi).contains(&phi.to_degrees()) {
        return Err(err(&format!(
            "the Fc minimum is at the end of the shear-angle range ({:.1} deg)",
            phi.to_degrees()
        )));
    }
    let r = p.fs / (phi + lam - p.a).cos();
    let (fc, ft) = (r * (lam - p.a).cos(), r * (lam - p.a).sin());
    let sol = Solution { fc, ft, tc: p.tc, t_int, t_ab: p.t_s, k_ab: p.tau_s, phi };
    if sol.is_sane(c.h) {
        Ok(sol)
    } else {
        Err(err("non-physical solution"))
    }
}

#[cfg(test)]
mod tests {
    use super::super::material::{Consts, MATERIALS};
    use super::super::mechanism::Zorev;
    use super::*;

    /// Solves the grid and checks each solution against the ranges (kc GPa, chip ratio, Ft/Fc, T_int).
    fn check(mat: usize, speeds: &[f64], feeds: &[f64], ranges: [(f64, f64); 4]) {
        let k = Consts::nominal(&MATERIALS[mat]);
        for &v in speeds {
            for &h in feeds {
                for rake in [-5.0f64, 0.0, 10.0] {
                    let c = Cond { v: v / 60.0, h: h * 1e-3, w: 2e-3, rake: rake.to_radians() };
                    let s = solve(&c, &k, &Mods::none()).unwrap();
                    let got = [s.fc / c.h / 1e9, s.tc / c.h, s.ft / s.fc, s.t_int];
                    for ((x, (lo, hi)), what) in got.iter().zip(ranges).zip(["kc", "ratio", "Ft/Fc", "T_int"]) {
                        assert!((lo..hi).contains(x), "{} {v} {h} {rake}: {what} {x}", MATERIALS[mat].name);
                    }
                }
            }
        }
    }

    #[test]
    fn family_c_is_physical_over_the_steel_range() {
        // Specific cutting force 1.2-6 GPa, chip ratio 1.1-5, Ft/Fc 0.05-1.2, T_int 150-1300 degC (the
        // grid gives 1.4-2.6 GPa, 1.28-1.75, 0.08-0.61, 320-1244 degC: Merchant's minimum-energy shear
        // angle is known to give thin chips).
        for mat in [0, 1] {
            check(
                mat,
                &[30.0, 100.0, 400.0],
                &[0.03, 0.1, 0.3],
                [(1.2, 6.0), (1.1, 5.0), (0.05, 1.2), (150.0, 1300.0)],
            );
        }
    }

    #[test]
    fn family_c_solves_ti6al4v_in_its_range() {
        // 20-60 m/min, h 0.05-0.15 mm (the range every family draws for this alloy).
        check(2, &[20.0, 40.0, 60.0], &[0.05, 0.1, 0.15], [(1.0, 6.0), (1.05, 5.0), (0.05, 1.2), (150.0, 1500.0)]);
    }

    #[test]
    fn partition_contact_and_source_by_hand() {
        // Weiner at R_T tan(phi) = 4 (S = 1): erfc(1) / 2 + erf(1) / 4 - exp(-1) / (2 sqrt(pi))
        // = 0.0786496 + 0.2106752 - 0.1037769 = 0.1855479.
        assert!((weiner_beta(4.0) - 0.185_547_9).abs() < 1e-6, "{}", weiner_beta(4.0));
        // -> 1/2 for a slow cut, ~ 1 / (R_T tan phi) for a fast one (400: 0.0025 - tiny).
        assert!((weiner_beta(0.01) - 0.5).abs() < 0.04 && (weiner_beta(400.0) - 0.0025).abs() < 1e-5);
        // Coulomb-Tresca: mu 0.5, sigma_N 400 MPa, k 250 MPa: sliding, 200 MPa; sigma_N 600 MPa: 250 MPa.
        assert!((coulomb_tresca(0.5, 400e6, 250e6) - 200e6).abs() < 1.0);
        assert!((coulomb_tresca(0.5, 600e6, 250e6) - 250e6).abs() < 1.0);
        // ... and it is Zorev's law with a uniform normal stress (a = 0).
        let z = Zorev { mu0: 0.5, q: 0.0, a: 0.0 };
        for sn in [0.4, 1.6, 2.4] {
            assert!((z.factor(sn, 2.0) - coulomb_tresca(0.5, sn, 1.0)).abs() < 1e-12, "{sn}");
        }
        // Jaeger maximum: q 1 GW/m^2, l_c 0.2 mm, V_c 2 m/s, K 40 W/(m K), kappa 1e-5 m^2/s:
        // 2 q sqrt(kappa l_c / (pi V_c)) / K = 2e9 * sqrt(3.1831e-10) / 40 = 892.06 K (L = 10).
        assert!((jaeger_max_rise(1e9, 0.2e-3, 2.0, 40.0, 1e-5) - 892.06).abs() < 0.05);
    }

    #[test]
    fn each_hook_vanishes_at_zero_strength() {
        // The friction mechanism's Zorev law at s -> 0 (mu 0.5, q 0, a 0) and a zero partition blend
        // give the mechanism-free solution.
        let k = Consts::nominal(&MATERIALS[0]);
        let c = Cond { v: 2.0, h: 0.1e-3, w: 2e-3, rake: 0.0 };
        let base = solve(&c, &k, &Mods::none()).unwrap();
        let mut m = Mods::none();
        m.friction = Some(Zorev { mu0: FAMILY_C_MU, q: 0.0, a: 1e-9 });
        let s = solve(&c, &k, &m).unwrap();
        assert!((s.fc / base.fc - 1.0).abs() < 1e-9 && (s.tc / base.tc - 1.0).abs() < 1e-9);
        // Full partition blend: Boothroyd's larger beta and a tool share cool both zones.
        m = Mods::none();
        m.partition_blend = 1.0;
        let s = solve(&c, &k, &m).unwrap();
        assert!(s.t_ab < base.t_ab && s.t_int < base.t_int, "{} {} {} {}", s.t_ab, base.t_ab, s.t_int, base.t_int);
    }
}
