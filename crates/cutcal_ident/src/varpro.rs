//! Separable least squares (variable projection) for the Eq 15 identification.
//!
//! For fixed `q = (n, C, m)` the JC stress of paper Eq 16 is linear in `A` and `B`:
//! `f_k = A u_k(q) + B v_k(q)` with `u_k = (1 + C L_k) (1 - theta_k^m)` and `v_k = eps_k^n u_k`
//! (`L_k` the rate logarithm, clamped or not as the problem states). The weighted residual
//! `r = A u + B v - y` (every term scaled by `sqrt(w_k)`) is therefore minimised exactly over
//! `(A, B)` inside their box for each `q` (a 2x2 normal-equation solve, or the best of the
//! edge/corner candidates when the unconstrained optimum leaves the box), and the bounded LM
//! ([`crate::lm`]) runs over `q` only. This is the variable projection method of Golub and Pereyra
//! (SIAM J. Numer. Anal. 10 (1973) 413-432); the Jacobian of the projected residual is the exact
//! one (their Eq 4.1 written with the 2x2 Gram matrix; Kaufman, BIT 15 (1975) 49-57, drops its
//! second term, which is not needed here because the linear block is 2x2), with the linear
//! parameters held at an active bound treated as constants.
//!
//! Everything that does not depend on the parameters (`ln eps`, the rate logarithm, `ln theta`,
//! `sqrt(w)`, `sqrt(w) F`) is cached once by [`crate::dpzd_fit::ZoneFitProblem`].

use std::cell::RefCell;

use nalgebra::{DMatrix, DVector};

use crate::error::IdentError;
use crate::lm::{Bounds, Problem};
use crate::zone_problem::CachedPoint;

/// The projected Eq 15 problem over `q = (n, C, m)`, with `A` and `B` (MPa) eliminated.
///
/// The bases and their derivatives at the last `q` evaluated are kept, so the Jacobian at an
/// accepted LM point costs no further `exp` (the problem is for one thread: it is not `Sync`).
#[derive(Debug, Clone)]
pub struct VarproProblem<'a> {
    cached: &'a [CachedPoint],
    a_box: [f64; 2],
    b_box: [f64; 2],
    last: RefCell<Evaluation>,
}

/// Bases, derivatives and linear solution at one `q`.
///
/// The powers `eps^n` and `theta^m` of every point are kept with the `n` and `m` they belong to:
/// when a step leaves `n` or `m` unchanged (bitwise; e.g. held at a bound) they are reused, so
/// such an evaluation needs no `exp`.
#[derive(Debug, Clone, Default)]
struct Evaluation {
    q: [f64; 3],
    valid: bool,
    /// `(u, v)` of every point, scaled by `sqrt(w)` (the derivatives are formed by the Jacobian).
    basis: Vec<[f64; 2]>,
    linear: Option<LinearSolution>,
    /// `n` of `eps_n`, `m` of `theta_m` (`None`: not computed yet).
    n_key: Option<u64>,
    m_key: Option<u64>,
    eps_n: Vec<f64>,
    theta_m: Vec<f64>,
}

/// The optimal linear parameters at one `q`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearSolution {
    /// A, MPa.
    pub a_mpa: f64,
    /// B, MPa.
    pub b_mpa: f64,
    /// A strictly inside its box (not held at a bound).
    pub a_free: bool,
    /// B strictly inside its box.
    pub b_free: bool,
}

impl<'a> VarproProblem<'a> {
    /// The projected problem over the cached points with the boxes of A and B (MPa).
    pub(crate) fn new(cached: &'a [CachedPoint], a_box: [f64; 2], b_box: [f64; 2]) -> Self {
        Self { cached, a_box, b_box, last: RefCell::new(Evaluation::default()) }
    }

    /// Fills `last` at `q` (bases with derivatives, the optimal `(A, B)`) unless it holds `q`.
    fn evaluate(&self, q: &DVector<f64>) -> std::cell::RefMut<'_, Evaluation> {
        let mut e = self.last.borrow_mut();
        let key = [q[0], q[1], q[2]];
        // The cache is for the identical point only (bitwise), as the LM re-evaluates it.
        let same = e.valid && e.q.iter().zip(&key).all(|(x, y)| x.to_bits() == y.to_bits());
        if !same {
            let e = &mut *e;
            let (n, cc, m) = (key[0], key[1], key[2]);
            if e.n_key != Some(n.to_bits()) {
                e.eps_n.clear();
                e.eps_n.extend(self.cached.iter().map(|c| power(c.ln_strain, n, n == 0.0)));
                e.n_key = Some(n.to_bits());
            }
            if e.m_key != Some(m.to_bits()) {
                e.theta_m.clear();
                e.theta_m.extend(self.cached.iter().map(|c| power(c.ln_theta, m, false)));
                e.m_key = Some(m.to_bits());
            }
            e.basis.clear();
            let mut s = [0.0; 5];
            for ((c, en), tm) in self.cached.iter().zip(&e.eps_n).zip(&e.theta_m) {
                let (u, v) = Self::bases(c, *en, *tm, cc);
                accumulate(&mut s, u, v, c.sqrt_weight * c.target_mpa);
                e.basis.push([u, v]);
            }
            e.linear = Some(solve_box(s, self.a_box, self.b_box));
            e.q = key;
            e.valid = true;
        }
        e
    }

    /// Bases `u`, `v` at one point from the powers `eps^n`, `theta^m`.
    ///
    /// **Source:** paper Eq 16 (the JC law), split as `A u + B v`.
    #[inline]
    fn bases(c: &CachedPoint, en: f64, tm: f64, cc: f64) -> (f64, f64) {
        let u = c.sqrt_weight * (1.0 + cc * c.ln_rate) * (1.0 - tm);
        (u, en * u)
    }

    /// Derivatives `(du/dC, du/dm)` and `(dv/dn, dv/dC, dv/dm)` at one point (`du/dn = 0`) from
    /// the powers and the bases.
    ///
    /// **Source:** paper Eq 16 differentiated: `u = sqrt(w) (1 + C L) (1 - theta^m)`, `v = eps^n u`.
    #[inline]
    fn derivatives(c: &CachedPoint, en: f64, tm: f64, cc: f64, v: f64) -> ([f64; 2], [f64; 3]) {
        let sw = c.sqrt_weight;
        let du_dc = sw * c.ln_rate * (1.0 - tm);
        let du_dm = -sw * (1.0 + cc * c.ln_rate) * tm * c.ln_theta.unwrap_or(0.0);
        ([du_dc, du_dm], [v * c.ln_strain.unwrap_or(0.0), en * du_dc, en * du_dm])
    }

    /// The optimal `(A, B)` inside their box at `q`.
    #[must_use]
    pub fn linear_solution(&self, q: &DVector<f64>) -> LinearSolution {
        let (n, cc, m) = (q[0], q[1], q[2]);
        let mut s = [0.0; 5];
        for c in self.cached {
            let (u, v) = Self::bases(c, power(c.ln_strain, n, n == 0.0), power(c.ln_theta, m, false), cc);
            accumulate(&mut s, u, v, c.sqrt_weight * c.target_mpa);
        }
        solve_box(s, self.a_box, self.b_box)
    }

    /// The full parameter vector `[A_MPa, B_MPa, n, C, m]` at `q`.
    #[must_use]
    pub fn full_parameters(&self, q: &DVector<f64>) -> DVector<f64> {
        let l = self.linear_solution(q);
        DVector::from_vec(vec![l.a_mpa, l.b_mpa, q[0], q[1], q[2]])
    }
}

/// `x^p = exp(p ln x)` from a cached `ln x`; for `x = 0` (`None`), 1 when `zero_power_is_one`
/// (`0^0`, the JC convention for n = 0 at eps = 0) else 0.
#[inline]
fn power(ln_x: Option<f64>, p: f64, zero_power_is_one: bool) -> f64 {
    match ln_x {
        Some(l) => (p * l).exp(),
        None if zero_power_is_one => 1.0,
        None => 0.0,
    }
}

/// Adds one point's terms to the sums `[u.u, u.v, v.v, u.y, v.y]` of [`solve_box`].
#[inline]
fn accumulate(s: &mut [f64; 5], u: f64, v: f64, y: f64) {
    s[0] += u * u;
    s[1] += u * v;
    s[2] += v * v;
    s[3] += u * y;
    s[4] += v * y;
}

/// Minimises `Q(a, b) = |a u + b v - y|^2` over the box from the sums
/// `s = [u.u, u.v, v.v, u.y, v.y]`.
///
/// A convex quadratic: the unconstrained optimum (2x2 normal equations) when it lies in the box,
/// else the best of the four edge minima (each a clamped 1-D minimum), which contains the corners.
fn solve_box(s: [f64; 5], a_box: [f64; 2], b_box: [f64; 2]) -> LinearSolution {
    let [uu, uv, vv, uy, vy] = s;
    let q = |a: f64, b: f64| a * a * uu + 2.0 * a * b * uv + b * b * vv - 2.0 * a * uy - 2.0 * b * vy;
    let det = uu * vv - uv * uv;
    if det > 1e-13 * uu * vv && det > 0.0 {
        let a = (uy * vv - vy * uv) / det;
        let b = (vy * uu - uy * uv) / det;
        if a > a_box[0] && a < a_box[1] && b > b_box[0] && b < b_box[1] {
            return LinearSolution { a_mpa: a, b_mpa: b, a_free: true, b_free: true };
        }
    }
    let clamp_free = |x: f64, lo: f64, hi: f64| -> (f64, bool) {
        if !x.is_finite() || x <= lo {
            (lo, false)
        } else if x >= hi {
            (hi, false)
        } else {
            (x, true)
        }
    };
    let mut best: Option<(f64, LinearSolution)> = None;
    let mut consider = |sol: LinearSolution| {
        let val = q(sol.a_mpa, sol.b_mpa);
        if best.as_ref().is_none_or(|(v, _)| val < *v) {
            best = Some((val, sol));
        }
    };
    for a in a_box {
        let (b, b_free) = if vv > 0.0 { clamp_free((vy - a * uv) / vv, b_box[0], b_box[1]) } else { (b_box[0], false) };
        consider(LinearSolution { a_mpa: a, b_mpa: b, a_free: false, b_free });
    }
    for b in b_box {
        let (a, a_free) = if uu > 0.0 { clamp_free((uy - b * uv) / uu, a_box[0], a_box[1]) } else { (a_box[0], false) };
        consider(LinearSolution { a_mpa: a, b_mpa: b, a_free, b_free: false });
    }
    best.map_or(LinearSolution { a_mpa: a_box[0], b_mpa: b_box[0], a_free: false, b_free: false }, |(_, s)| s)
}

impl Problem for VarproProblem<'_> {
    fn parameter_count(&self) -> usize {
        3
    }

    fn residual_count(&self) -> usize {
        self.cached.len()
    }

    /// Projected residuals `A(q) u + B(q) v - y` (paper Eq 15, weighted).
    fn residuals(&self, q: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        let e = self.evaluate(q);
        let l = e.linear.unwrap_or_else(|| solve_box([0.0; 5], self.a_box, self.b_box));
        for ((o, [u, v]), c) in out.iter_mut().zip(&e.basis).zip(self.cached) {
            *o = l.a_mpa * u + l.b_mpa * v - c.sqrt_weight * c.target_mpa;
        }
        Ok(())
    }

    /// Exact Jacobian of the projected residual (Golub and Pereyra 1973):
    /// `dr/dq_j = d_j + Phi_f dc_j`, `d_j = Phi'_j c`, `G dc_j = -Phi'_{f,j}^T r - Phi_f^T d_j`,
    /// with `Phi_f` the columns of the linear parameters not held at a bound and `G = Phi_f^T Phi_f`.
    fn jacobian(&self, q: &DVector<f64>, _bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        let e = self.evaluate(q);
        let l = e.linear.unwrap_or_else(|| solve_box([0.0; 5], self.a_box, self.b_box));
        let (a, b) = (l.a_mpa, l.b_mpa);
        let cc = e.q[1];
        // d_j = dPhi/dq_j c and the sums needed for dc_j.
        // s_ur[j] = du_j . r, s_vr[j] = dv_j . r, s_ud[j] = u . d_j, s_vd[j] = v . d_j.
        let (mut s_ur, mut s_vr, mut s_ud, mut s_vd) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
        let (mut uu, mut uv, mut vv) = (0.0, 0.0, 0.0);
        let rows = e.basis.len();
        // Column-major storage: column j is `cols[j * rows..(j + 1) * rows]`.
        let (col_n, rest) = out.as_mut_slice().split_at_mut(rows);
        let (col_c, col_m) = rest.split_at_mut(rows);
        let points = e.basis.iter().zip(self.cached).zip(e.eps_n.iter().zip(&e.theta_m));
        for ((([u, v], c), (en, tm)), (on, (oc, om))) in points.zip(col_n.iter_mut().zip(col_c.iter_mut().zip(col_m))) {
            let (u, v) = (*u, *v);
            let (du2, dv) = Self::derivatives(c, *en, *tm, cc, v);
            let r = a * u + b * v - c.sqrt_weight * c.target_mpa;
            let du = [0.0, du2[0], du2[1]];
            let d = [b * dv[0], a * du[1] + b * dv[1], a * du[2] + b * dv[2]];
            (*on, *oc, *om) = (d[0], d[1], d[2]);
            for j in 0..3 {
                s_ur[j] += du[j] * r;
                s_vr[j] += dv[j] * r;
                s_ud[j] += u * d[j];
                s_vd[j] += v * d[j];
            }
            uu += u * u;
            uv += u * v;
            vv += v * v;
        }
        for j in 0..3 {
            let (da, db) = match (l.a_free, l.b_free) {
                (true, true) => {
                    let det = uu * vv - uv * uv;
                    let (ra, rb) = (-s_ur[j] - s_ud[j], -s_vr[j] - s_vd[j]);
                    ((vv * ra - uv * rb) / det, (uu * rb - uv * ra) / det)
                }
                (true, false) => ((-s_ur[j] - s_ud[j]) / uu, 0.0),
                (false, true) => (0.0, (-s_vr[j] - s_vd[j]) / vv),
                (false, false) => (0.0, 0.0),
            };
            if da != 0.0 || db != 0.0 {
                let col = &mut out.as_mut_slice()[j * rows..(j + 1) * rows];
                for (o, [u, v]) in col.iter_mut().zip(&e.basis) {
                    *o += da * u + db * v;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        // Independent check of the box solution: no point of a 41 x 41 grid of the box (corners
        // and edges included) has a smaller objective.
        #[test]
        fn box_solution_is_never_beaten_by_a_grid_point(
            u in proptest::collection::vec(0.0..2.0f64, 6), v in proptest::collection::vec(0.0..2.0f64, 6),
            y in proptest::collection::vec(-5.0..5.0f64, 6),
            a_lo in -3.0..1.0f64, a_w in 0.0..4.0f64, b_lo in -3.0..1.0f64, b_w in 0.0..4.0f64,
        ) {
            let dot = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
            let s = [dot(&u, &u), dot(&u, &v), dot(&v, &v), dot(&u, &y), dot(&v, &y)];
            let (a_box, b_box) = ([a_lo, a_lo + a_w], [b_lo, b_lo + b_w]);
            let l = solve_box(s, a_box, b_box);
            prop_assert!(l.a_mpa >= a_box[0] && l.a_mpa <= a_box[1] && l.b_mpa >= b_box[0] && l.b_mpa <= b_box[1]);
            let obj = |a: f64, b: f64| (0..6).map(|k| (a * u[k] + b * v[k] - y[k]).powi(2)).sum::<f64>();
            let best = obj(l.a_mpa, l.b_mpa);
            for i in 0..=40 {
                for j in 0..=40 {
                    let a = a_box[0] + a_w * f64::from(i) / 40.0;
                    let b = b_box[0] + b_w * f64::from(j) / 40.0;
                    prop_assert!(best <= obj(a, b) + 1e-9 * (1.0 + best), "({}, {}) beats {:?}", a, b, l);
                }
            }
        }
    }

    #[test]
    fn box_solution_is_the_unconstrained_optimum_inside_and_an_edge_outside() {
        // u = (1, 1, 1), v = (0, 1, 2), y = 1 + 2 v: a = 1, b = 2 exactly (independent: by hand).
        let (u, v) = ([1.0, 1.0, 1.0], [0.0, 1.0, 2.0]);
        let y: Vec<f64> = v.iter().map(|x| 1.0 + 2.0 * x).collect();
        let dot = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
        let s = [dot(&u, &u), dot(&u, &v), dot(&v, &v), dot(&u, &y), dot(&v, &y)];
        let l = solve_box(s, [0.0, 10.0], [0.0, 10.0]);
        assert!((l.a_mpa - 1.0).abs() < 1e-12 && (l.b_mpa - 2.0).abs() < 1e-12 && l.a_free && l.b_free);
        // b <= 1.5: with b = 1.5 held, a = mean(y - 1.5 v) = mean(1, 1.5, 2) = 1.5.
        let l = solve_box(s, [0.0, 10.0], [0.0, 1.5]);
        assert!((l.b_mpa - 1.5).abs() < 1e-12 && !l.b_free && l.a_free);
        assert!((l.a_mpa - 1.5).abs() < 1e-12, "{l:?}");
        // Both out: a <= 0.5 and b <= 1.5 -> corner (0.5, 1.5) (the a-edge minimum for b is
        // (v.y - 0.5 u.v)/v.v = (13 - 1.5)/5 = 2.3 > 1.5, clamped).
        let l = solve_box(s, [0.0, 0.5], [0.0, 1.5]);
        assert_eq!((l.a_mpa, l.b_mpa, l.a_free, l.b_free), (0.5, 1.5, false, false));
    }
}
