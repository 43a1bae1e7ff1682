//! Bracketed one-dimensional root finding and minimisation (Brent 1973), every loop capped and
//! every failure a typed [`ModelError`].

use crate::error::ModelError;

/// Brent's root finder on a sign-changing bracket `[a, b]` with known `f(a)`, `f(b)`.
///
/// **Source:** Brent, *Algorithms for Minimization without Derivatives* (1973), Ch. 4 (zero):
/// inverse quadratic interpolation safeguarded by bisection.
///
/// Returns [`ModelError::NoSolution`] if the bracket does not change sign and
/// [`ModelError::NoConvergence`] after `max_iter` iterations; errors of `f` propagate.
#[allow(clippy::too_many_arguments)] // the bracket with its two known values is one unit
pub(crate) fn brent_root<F>(
    mut f: F,
    a0: f64,
    b0: f64,
    fa0: f64,
    fb0: f64,
    xtol: f64,
    max_iter: usize,
    what: &str,
) -> Result<f64, ModelError>
where
    F: FnMut(f64) -> Result<f64, ModelError>,
{
    let (mut a, mut b, mut fa, mut fb) = (a0, b0, fa0, fb0);
    if !(fa.is_finite() && fb.is_finite()) || (fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0) {
        return Err(ModelError::NoSolution {
            what: what.to_string(),
            low: a0,
            high: b0,
            detail: format!("no sign change: f(low) = {fa0:e}, f(high) = {fb0:e}"),
        });
    }
    if fa.abs() < f64::MIN_POSITIVE {
        return Ok(a);
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    let mut last = (b - a).abs();
    for _ in 0..max_iter {
        if (fb > 0.0) == (fc > 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let xm = 0.5 * (c - b);
        last = xm.abs();
        if xm.abs() <= tol1 || fb.abs() < f64::MIN_POSITIVE {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            // `a` and `c` are the same point exactly when c was just assigned from a (bit equality
            // is the point here): then use the secant step, else inverse quadratic interpolation.
            let (mut p, mut q) = if a.to_bits() == c.to_bits() {
                (2.0 * xm * s, 1.0 - s)
            } else {
                let q = fa / fc;
                let r = fb / fc;
                (s * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0)), (q - 1.0) * (r - 1.0) * (s - 1.0))
            };
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * xm * q - (tol1 * q).abs();
            let min2 = (e * q).abs();
            if 2.0 * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = f(b)?;
        if !fb.is_finite() {
            return Err(ModelError::out_of_range(format!("{what}: function value"), fb, "a finite number"));
        }
    }
    Err(ModelError::NoConvergence { what: what.to_string(), iterations: max_iter, last_change: last, tolerance: xtol })
}

/// Newton's method from `x0` on `[lo, hi]`; `f` returns the value and the derivative.
///
/// **Source:** Newton-Raphson with the interval safeguard of `rtsafe` (Press et al., *Numerical
/// Recipes*, 3rd ed. 2007, Sec. 9.4): an iterate that would leave the interval is put on its end,
/// and a second push past the same end gives up.
///
/// Returns the last evaluated `x` once the step from it is at most `xtol`; `None` when the
/// iteration leaves the interval,
/// meets a zero or non-finite derivative, an error of `f`, or `max_iter` (callers then bracket the
/// whole interval with [`brent_root`]: the root is the same to `xtol`, only the work differs).
pub(crate) fn newton_1d<F>(mut f: F, x0: f64, lo: f64, hi: f64, xtol: f64, max_iter: usize) -> Option<f64>
where
    F: FnMut(f64) -> Result<(f64, f64), ModelError>,
{
    if !(x0.is_finite() && hi > lo) {
        return None;
    }
    let mut x = x0.clamp(lo, hi);
    for _ in 0..max_iter {
        let (fx, dfx) = f(x).ok()?;
        if !(fx.is_finite() && dfx.is_finite()) || dfx == 0.0 {
            return None;
        }
        let step = fx / dfx;
        if step.abs() <= xtol {
            // The evaluated point: within about |step| <= xtol of the root (quadratic convergence),
            // so the caller can reuse what it computed there.
            return Some(x);
        }
        let xn = x - step;
        let clipped = xn.clamp(lo, hi);
        if clipped.to_bits() != xn.to_bits() && clipped.to_bits() == x.to_bits() {
            return None; // pushed past the same end twice: no root inside from here
        }
        x = clipped;
    }
    None
}

/// Result of [`brent_min`]: the abscissa and value of the minimum found.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Minimum {
    pub x: f64,
    pub f: f64,
}

/// Brent's minimiser on `[a, b]` (golden section with parabolic steps).
///
/// **Source:** Brent (1973), Ch. 5 (localmin).
///
/// Returns [`ModelError::NoConvergence`] after `max_iter` iterations; errors of `f` propagate.
pub(crate) fn brent_min<F>(
    mut f: F,
    a0: f64,
    b0: f64,
    xtol: f64,
    max_iter: usize,
    what: &str,
) -> Result<Minimum, ModelError>
where
    F: FnMut(f64) -> Result<f64, ModelError>,
{
    const CGOLD: f64 = 0.381_966_011_250_105_1; // (3 - sqrt 5) / 2
    let (mut a, mut b) = (a0.min(b0), a0.max(b0));
    let mut x = a + CGOLD * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let mut d: f64 = 0.0;
    let mut e: f64 = 0.0;
    for _ in 0..max_iter {
        let xm = 0.5 * (a + b);
        let tol1 = xtol * x.abs() + 1e-14;
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            return Ok(Minimum { x, f: fx });
        }
        let mut golden = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let etemp = e;
            e = d;
            if !(p.abs() >= (0.5 * q * etemp).abs() || p <= q * (a - x) || p >= q * (b - x)) {
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(xm - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= xm { a - x } else { b - x };
            d = CGOLD * e;
        }
        let u = if d.abs() >= tol1 { x + d } else { x + tol1.copysign(d) };
        let fu = f(u)?;
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w.to_bits() == x.to_bits() {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v.to_bits() == x.to_bits() || v.to_bits() == w.to_bits() {
                (v, fv) = (u, fu);
            }
        }
    }
    Err(ModelError::NoConvergence { what: what.to_string(), iterations: max_iter, last_change: b - a, tolerance: xtol })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_root_finds_sqrt2_and_reports_no_bracket() {
        // x^2 - 2 = 0 on [0, 2]: root sqrt(2) = 1.41421356237...
        let f = |x: f64| Ok(x * x - 2.0);
        let r = brent_root(f, 0.0, 2.0, -2.0, 2.0, 1e-12, 100, "sqrt2").unwrap();
        assert!((r - 2f64.sqrt()).abs() < 1e-11);
        let e = brent_root(f, 2.0, 3.0, 2.0, 7.0, 1e-12, 100, "sqrt2").unwrap_err();
        assert!(matches!(e, ModelError::NoSolution { .. }));
    }

    #[test]
    fn brent_root_hits_its_cap_as_a_typed_error() {
        let f = |x: f64| Ok(x - 0.3);
        let e = brent_root(f, 0.0, 1.0, -0.3, 0.7, 1e-300, 1, "cap").unwrap_err();
        assert!(matches!(e, ModelError::NoConvergence { iterations: 1, .. }));
    }

    #[test]
    fn newton_finds_sqrt2_and_gives_up_outside_the_interval() {
        // x^2 - 2 = 0: root sqrt(2); on [2, 3] there is none and Newton is pushed past 2 twice.
        let f = |x: f64| Ok((x * x - 2.0, 2.0 * x));
        let r = newton_1d(f, 1.0, 0.0, 2.0, 1e-13, 50).unwrap();
        assert!((r - 2f64.sqrt()).abs() < 1e-12);
        assert!(newton_1d(f, 2.5, 2.0, 3.0, 1e-13, 50).is_none());
    }

    #[test]
    fn brent_min_finds_parabola_vertex() {
        // (x - 0.7)^2 + 1 on [0, 2]: minimum at 0.7, value 1.
        let m = brent_min(|x: f64| Ok((x - 0.7).powi(2) + 1.0), 0.0, 2.0, 1e-8, 100, "parabola").unwrap();
        assert!((m.x - 0.7).abs() < 1e-6);
        assert!((m.f - 1.0).abs() < 1e-12);
    }
}
